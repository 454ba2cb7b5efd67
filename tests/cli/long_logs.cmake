# CLI regression cases for long logs: `sigmatau adev --mode stream|exact|auto` (issue 3).
set(example ${PROJECT_SOURCE_DIR}/examples/gyro_static_100Hz.csv.gz)
set(truncated ${PROJECT_SOURCE_DIR}/tests/data/long_logs/truncated_2ch_f64.bin)
set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_long_logs)
file(MAKE_DIRECTORY ${out_dir})

# Stream mode at m <= K has stride 1: the first points are the exact ones (same n and EDF).
sigmatau_cli_test(NAME cli_long_logs_stream_table EXIT 0
  STDOUT "0.01 +1 +119999 +0 +9.391e\\+04 +4.972498e-02 +4.983966e-02"
  ARGS adev ${example} --time-column t --columns gx --mode stream --density 8)
sigmatau_cli_test(NAME cli_long_logs_exact_table EXIT 0
  STDOUT "0.01 +1 +119999 +0 +9.391e\\+04 +4.972498e-02 +4.983966e-02"
  ARGS adev ${example} --time-column t --columns gx --mode exact)
# At m = 1024 with K = 8 the stride is 128: 1 + (N - 1 - 2m) / 128 = 922 terms.
sigmatau_cli_test(NAME cli_long_logs_stream_strided_terms EXIT 0
  STDOUT "gx,oadev,,1.024000e\\+01,1024,922,"
  ARGS adev ${example} --time-column t --columns gx --mode stream --format csv)
sigmatau_cli_test(NAME cli_long_logs_stream_stdin EXIT 0
  STDIN ${PROJECT_SOURCE_DIR}/tests/data/cli/white_2ch_10Hz.csv
  STDOUT "\"channel\": \"gy\"" ARGS adev - --time-column t --format json --mode stream)

# A record cut short: exit 2 naming the byte offset, and no output.
sigmatau_cli_test(NAME cli_long_logs_truncated EXIT 2 STDERR "truncated record at byte offset"
  NO_FILE ${out_dir}/truncated.csv
  ARGS adev ${truncated} --binary f64 --channels 2 --rate 100 --mode stream
       --format csv -o ${out_dir}/truncated.csv)
# With --partial the results for every whole record before the cut are written and the exit code
# stays 2. The cut comes inside the first 65536-row block: those rows used to be dropped, and
# nothing was written. The m = 1 line has the 4999 differences of the 5000 records (its numbers
# are those of the file cut at byte 80000 and read without error, compared when this was
# written; the next case compares the two runs on a text log).
sigmatau_cli_test(NAME cli_long_logs_truncated_partial EXIT 2
  STDERR "truncated record at byte offset 80000.*--partial: results written for the 5000 samples read before it"
  STDOUT "c0,oadev,,1.000000e-02,1,4999,0,3.912465e\\+03,9.864289e-01,9.975241e-01,1.009002e\\+00"
  ARGS adev ${truncated} --binary f64 --channels 2 --rate 100 --mode stream --partial
       --format csv)
# A text log whose last row is bad: with --partial, exit 2 and the same results as the log
# without that row (the rows of the block before the bad one are kept, time stamps included).
file(READ ${PROJECT_SOURCE_DIR}/tests/data/cli/white_2ch_10Hz.csv white_rows)
file(WRITE ${out_dir}/white_then_bad_row.csv "${white_rows}200.0,0.5,abc\n")
add_test(NAME cli_long_logs_partial_keeps_rows
         COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:sigmatau_cli>" "-DEXIT_A=2"
                 "-DARGS_A=adev@@${out_dir}/white_then_bad_row.csv@@--time-column@@t@@--mode@@stream@@--partial@@--format@@csv"
                 "-DARGS_B=adev@@${PROJECT_SOURCE_DIR}/tests/data/cli/white_2ch_10Hz.csv@@--time-column@@t@@--mode@@stream@@--format@@csv"
                 -P ${PROJECT_SOURCE_DIR}/tests/support/expect_same_output.cmake)
sigmatau_cli_test(NAME cli_long_logs_truncated_exact EXIT 2 STDERR "truncated record"
  ARGS adev ${truncated} --binary f64 --channels 2 --rate 100 --mode exact)

sigmatau_cli_test(NAME cli_long_logs_bad_mode EXIT 2 STDERR "--mode must be exact, stream or auto"
  ARGS adev ${example} --time-column t --mode fast)
sigmatau_cli_test(NAME cli_long_logs_bad_density EXIT 2 STDERR "--density"
  ARGS adev ${example} --time-column t --mode stream --density 0)
sigmatau_cli_test(NAME cli_long_logs_bad_memory EXIT 2 STDERR "--memory"
  ARGS adev ${example} --time-column t --memory lots)
sigmatau_cli_test(NAME cli_long_logs_stream_totdev EXIT 2 STDERR "totdev.*--mode exact"
  ARGS adev ${example} --time-column t --mode stream --stat totdev)
sigmatau_cli_test(NAME cli_long_logs_partial_needs_stream EXIT 2 STDERR "--partial is for --mode stream"
  ARGS adev ${example} --time-column t --mode exact --partial)
# auto/exact: a file larger than --memory allows is computed exactly out of core, with a note
# (the truncated record is still found, in the first read pass).
sigmatau_cli_test(NAME cli_long_logs_auto_switches EXIT 2 STDERR "out of core"
  ARGS adev ${truncated} --binary f64 --channels 2 --rate 100 --memory 100K)
# Out of core gives the in-memory numbers (the same line as cli_long_logs_exact_table; every
# statistic is compared bit for bit in tests/test_allan_out_of_core.cpp).
sigmatau_cli_test(NAME cli_long_logs_out_of_core_table EXIT 0
  STDOUT "0.01 +1 +119999 +0 +9.391e\\+04 +4.972498e-02 +4.983966e-02"
  ARGS adev ${example} --time-column t --columns gx --mode exact --memory 1K)
sigmatau_cli_test(NAME cli_long_logs_out_of_core_note EXIT 0 STDERR "computing exactly out of core"
  ARGS adev ${example} --time-column t --columns gx --stat ohdev,totdev --memory 1K --threads 2)
# A pipe cannot be read twice: exact mode keeps it in memory whatever --memory says.
sigmatau_cli_test(NAME cli_long_logs_stdin_in_memory EXIT 0
  STDIN ${PROJECT_SOURCE_DIR}/tests/data/cli/white_2ch_10Hz.csv
  STDOUT "\"channel\": \"gy\"" ARGS adev - --time-column t --format json --memory 1K)
