# Extreme values and corrupt inputs (issue 28): each is refused with a clear message, or warned
# about, instead of a crash, an overflow or a silent empty result.
set(extreme_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_extreme)
file(REMOVE_RECURSE ${extreme_dir})
file(MAKE_DIRECTORY ${extreme_dir})
set(extreme_white ${CMAKE_CURRENT_SOURCE_DIR}/data/cli/white_2ch_10Hz.csv)

# Dynamic Allan windows too short to form: 1500 windows over 2000 samples are 2 samples each;
# windows of 16 samples fit 2 x 2000 / 16 - 1 = 249 times. Before: empty windows, no word.
sigmatau_cli_test(NAME cli_extreme_dynamic_windows_too_many EXIT 0
  STDERR "warning: dynamic Allan deviation: none of the 1500 windows asked was formed: over 2000 samples each would hold 2 samples, fewer than the 16 an OADEV curve needs. at most 249 windows fit"
  ARGS analyze ${extreme_white} --time-column t --gyro-unit deg/s --dynamic
       --dynamic-windows 1500 -o ${extreme_dir}/dynamic --force)

# A ROS 1 message on a connection no record declares (make_test_bags: undeclared.bag, message
# 200 of 400): skipped without a word while the topic note counted it. Now a counted warning
# naming the connection and the record, the index's count set against the messages found, and
# the topic note counting what was read.
sigmatau_cli_test(NAME cli_extreme_bag_undeclared_connection EXIT 0
  STDERR "sigmatau: note: .*undeclared.bag: reading /imu/data, the only sensor_msgs/Imu topic \\(choose with --topic\\). its topics: /imu/data \\(sensor_msgs/Imu, 399 messages\\).*warning: .*undeclared.bag: skipped 1 message on connection 9, which no connection record declares \\(the first: record at byte offset [0-9]+ \\(in the chunk at byte offset [0-9]+\\)\\): its topic is unknown.*warning: .*undeclared.bag: the bag states 400 messages on /imu/data, but 399 were found in it and read"
  ARGS adev ${CMAKE_CURRENT_BINARY_DIR}/cli_bags/undeclared.bag --gaps report --stat oadev)
set_tests_properties(cli_extreme_bag_undeclared_connection PROPERTIES FIXTURES_REQUIRED cli_bags)
# Under the default --gaps error the gap the skipped message leaves is the error, which says what
# the reader skipped.
sigmatau_cli_test(NAME cli_extreme_bag_undeclared_gap EXIT 2
  STDERR "time stamp gap of 10 ms .*before data row 200.*. while reading: skipped 1 message on connection 9"
  ARGS adev ${CMAKE_CURRENT_BINARY_DIR}/cli_bags/undeclared.bag --stat oadev)
set_tests_properties(cli_extreme_bag_undeclared_gap PROPERTIES FIXTURES_REQUIRED cli_bags)

# Names that are not UTF-8 (issue 28): a header written by a Windows program holds "°" as the
# byte 0xB0 (Windows-1252), and a file name may hold 0xE9 (é in Latin-1). JSON output ended in
# "internal error: [json.exception.type_error.316]", exit 3, in adev/psd/fit --format json and
# analyze. Now the name is read as Windows-1252 with a warning, every output is UTF-8, and the
# name shows as "temp °C" in JSON, Markdown, HTML and plot labels; a file name that is not UTF-8
# is written with U+FFFD in JSON.
set(extreme_utf8_check [=[
printf 't,gx,gy,temp \xb0C\n' > "$W/latin1.csv"
awk -F, 'NR > 2 { print $0 "," 25 + $2 }' "$LOG" >> "$W/latin1.csv"
cp "$W/latin1.csv" "$W/caf"$'\xe9'".csv"
utf8() { iconv -f UTF-8 -t UTF-8 "$1" > /dev/null 2>&1 || fail "$1 is not UTF-8"; }
for input in "$W/latin1.csv" "$W/caf"$'\xe9'".csv"; do
  for verb in adev psd fit; do
    run $verb "$input" --time-column t --unit deg/s --format json -o "$W/$verb.json" --force
    expect 0 'the name of column 3, "temp \\xB0C", is not UTF-8: it is read as Windows-1252 \(Latin-1\), "temp °C"'
    utf8 "$W/$verb.json"
    grep -q '"temp °C"' "$W/$verb.json" || fail "$verb.json does not name \"temp °C\""
  done
  run adev "$input" --time-column t --plot "$W/adev.svg" -o "$W/adev.txt" --force
  expect 0 "is not UTF-8"
  utf8 "$W/adev.svg"
  grep -q 'temp °C' "$W/adev.svg" || fail "the plot's legend does not name \"temp °C\""
  run analyze "$input" --time-column t -o "$W/report" --force
  expect 0 "is not UTF-8"
  for f in "$W"/report/*; do utf8 "$f"; done
  for f in results.json summary.md report.html; do
    grep -q 'temp °C' "$W/report/$f" || fail "$f does not name \"temp °C\""
  done
done
grep -q $'/caf\xef\xbf\xbd.csv"' "$W/report/results.json" || fail "the path is not written with U+FFFD"
echo "ok: every output UTF-8, the name read as Windows-1252"
]=])
add_test(NAME cli_extreme_names_not_utf8
         COMMAND bash -c "${sigmatau_cli_shell_prologue}${extreme_utf8_check}" extreme_utf8
                 $<TARGET_FILE:sigmatau_cli> ${extreme_dir}/utf8 ${extreme_white})

# Rates and times whose arithmetic overflows (issue 28): one check (sampling_limits.hpp) in every
# verb, the flag named. `fit --rate 1e80` gave terms of 0 with NaN intervals and p = nan, exit 0.
foreach(verb adev psd fit calibrate)
  sigmatau_cli_test(NAME cli_extreme_rate_${verb} EXIT 2
    STDERR "--rate must be a rate from 1e-09 Hz to 1e\\+12 Hz .*got 1e\\+80 Hz"
    ARGS ${verb} ${extreme_white} --rate 1e80)
endforeach()
sigmatau_cli_test(NAME cli_extreme_rate_analyze EXIT 2
  STDERR "--rate must be a rate from 1e-09 Hz to 1e\\+12 Hz .*got 1e-80 Hz"
  ARGS analyze ${extreme_white} --rate 1e-80 -o ${extreme_dir}/rate_analyze --force)
sigmatau_cli_test(NAME cli_extreme_rate_out EXIT 2
  STDERR "--rate-out must be a rate from 1e-09 Hz to 1e\\+12 Hz .*got 1e\\+300 Hz"
  ARGS analyze ${extreme_white} --time-column t --rate-out 1e300 -o ${extreme_dir}/rate_out --force)
sigmatau_cli_test(NAME cli_extreme_rate_convert EXIT 2 STDERR "--rate must be a rate from 1e-09 Hz"
  ARGS convert --spec bosch_bmi088 --rate 1e80 --to kalibr)
sigmatau_cli_test(NAME cli_extreme_tref_convert EXIT 2
  STDERR "--tref must be a time from 1e-12 s to 1e\\+18 s, got 1e\\+300 s"
  ARGS convert --spec adi_adis16465 --rate 200 --tref 1e300 --to kalibr)
sigmatau_cli_test(NAME cli_extreme_rate_simulate EXIT 2 STDERR "--rate must be a rate from 1e-09 Hz"
  ARGS simulate --model "N=0.15 deg/sqrt(h)" --rate 1e80 --duration 1s -o ${extreme_dir}/sim.csv --force)
sigmatau_cli_test(NAME cli_extreme_rate_demo EXIT 2 STDERR "--rate must be a rate from 1e-09 Hz"
  ARGS demo --rate 1e-80 -o ${extreme_dir}/demo --force)
# A trim of 1e300 s became -2^63 samples (a negative trim, exit 0).
sigmatau_cli_test(NAME cli_extreme_trim EXIT 2
  STDERR "trim_s: 1e\\+300 s at 10 Hz is 1e\\+301 samples, more than any log holds"
  ARGS analyze ${extreme_white} --time-column t --trim 1e300 -o ${extreme_dir}/trim --force)
# A time column 1e20 s apart measures 1e-20 Hz: refused, naming the column.
set(extreme_far_stamps ${extreme_dir}/far_stamps.csv)
set(extreme_text "t,gx\n")
foreach(i RANGE 40)
  math(EXPR v "(${i} * 7919) % 13")
  string(APPEND extreme_text "${i}e20,${v}\n")
endforeach()
file(WRITE ${extreme_far_stamps} "${extreme_text}")
foreach(verb adev psd fit)
  sigmatau_cli_test(NAME cli_extreme_time_column_${verb} EXIT 2
    STDERR "far_stamps.csv: the time column's stamps are 1e\\+20 s apart \\(median\\), a rate of 1e-20 Hz, outside the rates sigmatau computes with"
    ARGS ${verb} ${extreme_far_stamps} --time-column t --unit deg/s)
endforeach()

# Resource traps (issue 28).
# --memory 1e300 overflowed the int64 byte count (undefined behaviour).
sigmatau_cli_test(NAME cli_extreme_memory_overflow EXIT 2
  STDERR "--memory must be from 1 byte to 2\\^60 bytes \\(1024PiB\\), got \"1e300\""
  ARGS adev ${extreme_white} --time-column t --memory 1e300)
# A --segment FFTW cannot transform (its length is an int) is refused before anything is made.
sigmatau_cli_test(NAME cli_extreme_psd_segment_int EXIT 2
  STDERR "--segment must be at most 2147483647 samples"
  ARGS psd ${extreme_white} --time-column t --segment 2147483648)
# Under a 1 GiB address-space limit a segment longer than the log allocates nothing before it
# says so (main: bad_alloc, exit 3; without the limit, 2.7 GB and 8 s for 1e8 on 2 channels),
# and an input that does not fit in memory is a clear error,
# exit 2 (a pipe exact mode must hold whole; main: "internal error: std::bad_alloc", exit 3).
# The limit cannot hold under AddressSanitizer (sanitize_skip, as bad_inputs.cmake).
set(extreme_limited [=[
ulimit -v 1048576 || exit 1
for segment in 100000000 2147483647; do
  run psd "$LOG" --time-column t --segment $segment
  expect 2 "the log is shorter than one segment of $segment samples"
done
# 30 M rows "1,2,3" through a pipe: 9e7 values, 2.9 GB held in exact mode.
yes 1,2,3 | head -n 30000000 | "$S" adev - --rate 100 --stat oadev > /dev/null 2> "$W/.stderr"
rc=${PIPESTATUS[2]}; err=$(cat "$W/.stderr")
expect 2 "out of memory: the input needs more memory than this machine gives; if it comes from a pipe"
]=])
add_test(NAME cli_extreme_limited_memory
         COMMAND bash -c "${sigmatau_cli_shell_prologue}${extreme_limited}" extreme_limited
                 $<TARGET_FILE:sigmatau_cli> ${extreme_dir}/limited ${extreme_white})
set_tests_properties(cli_extreme_limited_memory PROPERTIES LABELS sanitize_skip TIMEOUT 120)

# A gzip bomb: 7.1 MB of text rows in 61 KB of gzip (117x). The memory estimate used the stored
# size (8 KB: in memory) and let such a file take 776 MB under --memory 64MiB (1 GiB of text:
# bad_alloc); it now counts what the file inflates to and goes out of core / bounded, with the
# same numbers as the plain text read in memory.
set(extreme_gzip_bomb [=[
{ echo gx,gy,gz; awk 'BEGIN { srand(5); for (i = 0; i < 1000; ++i) printf "%.4f,%.4f,%.4f\n", rand(), rand(), rand() }' > "$W/block"
  for i in $(seq 1 340); do cat "$W/block"; done; } > "$W/log.txt"
gzip -9 -c "$W/log.txt" > "$W/log.txt.gz"
echo "$(wc -c < "$W/log.txt") bytes of text in $(wc -c < "$W/log.txt.gz") of gzip"
run adev "$W/log.txt.gz" --rate 100 --stat oadev --memory 1MiB -o "$W/gz.txt"
expect 0 "log.txt.gz needs more than --memory 1MiB in memory. computing exactly out of core"
run adev "$W/log.txt" --rate 100 --stat oadev --memory 1GiB -o "$W/plain.txt"
expect 0 ""
diff <(tail -n +2 "$W/gz.txt" | grep -v "^# mode") <(tail -n +2 "$W/plain.txt" | grep -v "^# mode") > /dev/null ||
  fail "out of core on the .gz differs from in memory on the text"
run analyze "$W/log.txt.gz" --rate 100 --memory 1MiB -o "$W/report"
expect 0 "log.txt.gz needs more than --memory 1MiB in memory. analysing it in bounded memory"
echo "ok: the .gz was counted inflated, out of core and bounded, the same numbers"
]=])
add_test(NAME cli_extreme_gzip_bomb
         COMMAND bash -c "${sigmatau_cli_shell_prologue}${extreme_gzip_bomb}" extreme_gzip_bomb
                 $<TARGET_FILE:sigmatau_cli> ${extreme_dir}/gzip_bomb ${extreme_white})

# A saved adev result whose rate is out of range is refused naming its field (fit read it and
# computed with it).
file(WRITE ${extreme_dir}/rate_1e80.json
  "{\"tool\": \"sigmatau\", \"input\": {\"rate_hz\": 1e80, \"path\": \"x.csv\", \"samples\": 3000}, \"results\": [{\"statistic\": \"oadev\", \"points\": []}]}\n")
sigmatau_cli_test(NAME cli_extreme_rate_saved_adev EXIT 2
  STDERR "rate_1e80.json: input.rate_hz must be a rate from 1e-09 Hz to 1e\\+12 Hz"
  ARGS fit ${extreme_dir}/rate_1e80.json)
