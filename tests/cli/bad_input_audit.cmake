# Regression cases from the bad-input and output-safety audit of every verb (November 2026).
# Each case is a failure the audit found: exit 2 with the file and the reason on stderr, no
# internal error (exit 3), and nothing partial left next to an output.
set(audit_out ${CMAKE_CURRENT_BINARY_DIR}/cli_audit)
file(MAKE_DIRECTORY ${audit_out})
set(audit_fit ${PROJECT_SOURCE_DIR}/tests/data/check/fit_pass.json)

# A directory given where a JSON result is read was an internal error (exit 3, "basic_filebuf::
# underflow error reading the file") in `check` and `convert --fit`.
sigmatau_cli_test(NAME cli_audit_check_result_is_directory EXIT 2
  STDERR "cli_audit: cannot read: Is a directory \\(expected a JSON file\\)"
  NO_FILE ${audit_out}/check_dir.txt
  ARGS check --spec adi_adis16465 ${audit_out} -o ${audit_out}/check_dir.txt)
sigmatau_cli_test(NAME cli_audit_convert_fit_is_directory EXIT 2
  STDERR "cli_audit: cannot read: Is a directory \\(expected a JSON file\\)"
  NO_FILE ${audit_out}/convert_dir.json
  ARGS convert --fit ${audit_out} --rate 100 --to json -o ${audit_out}/convert_dir.json)
# A missing result said only "cannot open"; it now says why, as the log readers do.
sigmatau_cli_test(NAME cli_audit_check_result_missing EXIT 2
  STDERR "no_such_result.json: cannot open: No such file or directory"
  ARGS check --spec adi_adis16465 ${audit_out}/no_such_result.json)
sigmatau_cli_test(NAME cli_audit_convert_fit_missing EXIT 2
  STDERR "no_such_result.json: cannot open: No such file or directory"
  ARGS convert --fit ${audit_out}/no_such_result.json --rate 100 --to json)
# The reading path still works for a real result (the directory check must not reject files).
sigmatau_cli_test(NAME cli_audit_convert_fit_file_still_read EXIT 0 STDOUT "\"rate_hz\""
  ARGS convert --fit ${audit_fit} --rate 100 --to json)

# An interrupted run (Ctrl-C, kill, hang-up) left its partial "<output>.tmp-<random>" next to the
# output: `simulate` streams a long log into the temporary file. The run must die of the signal
# (exit 128 + signal number), remove the temporary file, and leave an existing output untouched.
# `set -m` gives the background job the default SIGINT action (a non-interactive shell otherwise
# starts it with SIGINT ignored). The simulated log is long (30 h at 1 kHz) so the signal always
# arrives mid-write; a failure kills it at once so no multi-GB file is finished.
# Arguments of the script: $1 the CLI, $2 a scratch directory, $3 the signal, $4 the exit code.
set(interrupt_check [=[
set -m
dir=$2; out=$dir/log.csv
rm -rf "$dir" && mkdir -p "$dir" && echo KEEP > "$out" || exit 1
"$1" simulate --model "N=0.15 deg/sqrt(h)" --rate 1000 --duration 30h -o "$out" --force \
  >/dev/null 2>&1 &
pid=$!
for i in $(seq 600); do ls "$dir" | grep -q '\.tmp-' && break; sleep 0.1; done
if ! ls "$dir" | grep -q '\.tmp-'; then
  echo "no temporary file appeared"; kill -KILL $pid; rm -rf "$dir"; exit 1
fi
kill -"$3" $pid; wait $pid; rc=$?
left=$(ls -A "$dir" | grep -v '^log\.csv$'); kept=$(cat "$out")
echo "exit $rc (expected $4); left behind: '$left'; output: '$kept' (expected KEEP)"
[ "$rc" != "$4" ] && kill -KILL $pid 2>/dev/null
rm -rf "$dir"
[ "$rc" = "$4" ] && [ -z "$left" ] && [ "$kept" = KEEP ]
]=])
foreach(signal_exit IN ITEMS INT:130 TERM:143 HUP:129)
  string(REPLACE ":" ";" pair "${signal_exit}")
  list(GET pair 0 signal)
  list(GET pair 1 code)
  add_test(NAME cli_audit_interrupt_${signal}_leaves_no_temporary
           COMMAND bash -c "${interrupt_check}" interrupt $<TARGET_FILE:sigmatau_cli>
                   ${audit_out}/interrupt_${signal} ${signal} ${code})
  set_tests_properties(cli_audit_interrupt_${signal}_leaves_no_temporary PROPERTIES TIMEOUT 120)
endforeach()

# Options whose bad values were taken silently as the default: psd --segment 0 or negative
# (the default 0 means "choose"; only a given value is checked) and fit --terms "" (the BIC
# choice). Both are usage errors now, like --stat "".
set(audit_log ${PROJECT_SOURCE_DIR}/tests/data/cli/white_2ch_10Hz.csv)
sigmatau_cli_test(NAME cli_audit_psd_negative_segment EXIT 2
  STDERR "--segment: expected a positive number of samples \\(at least 4\\), got -4"
  NO_FILE ${audit_out}/psd_negative_segment.txt
  ARGS psd ${audit_log} --time-column t --segment -4 -o ${audit_out}/psd_negative_segment.txt)
sigmatau_cli_test(NAME cli_audit_psd_zero_segment EXIT 2
  STDERR "--segment: expected a positive number of samples \\(at least 4\\), got 0"
  ARGS psd ${audit_log} --time-column t --segment 0)
sigmatau_cli_test(NAME cli_audit_psd_given_segment_still_used EXIT 0
  STDOUT "\"segment_length\": 64"
  ARGS psd ${audit_log} --time-column t --segment 64 --format json)
# An empty argument cannot pass through sigmatau_cli_test (CMake drops empty list elements), so
# this case runs through bash: $1 the CLI, $2 the log, $3 the output that must not appear.
add_test(NAME cli_audit_fit_empty_terms
         COMMAND bash -c [=[
err=$("$1" fit "$2" --time-column t --terms "" -o "$3" 2>&1 >/dev/null); rc=$?
echo "exit $rc (expected 2): $err"
[ "$rc" = 2 ] && [ ! -e "$3" ] && printf '%s' "$err" | grep -q -- "--terms: empty list: give terms"
]=] empty_terms $<TARGET_FILE:sigmatau_cli> ${audit_log} ${audit_out}/fit_empty_terms.txt)

# analyze: a --gyro / --accel name that is no channel of the log was skipped silently (exit 0,
# the sensor analysed with fewer axes), and --accel-unit / --gyro-unit were checked only when a
# column of that sensor was found (a wrong unit on a gyro-only log passed unnoticed).
sigmatau_cli_test(NAME cli_audit_analyze_unknown_gyro_column EXIT 2
  STDERR "--gyro: no channel \"gz\" in .*white_2ch_10Hz.csv \\(channels: gx, gy\\)"
  NO_FILE ${audit_out}/analyze_unknown_gyro
  ARGS analyze ${audit_log} --time-column t --gyro gx,gy,gz -o ${audit_out}/analyze_unknown_gyro)
sigmatau_cli_test(NAME cli_audit_analyze_accel_unit_without_accel EXIT 2
  STDERR "--accel-unit: expected length/time\\^2 \\(e.g. m/s\\^2\\), found angle/time \\(deg/s\\)"
  NO_FILE ${audit_out}/analyze_accel_unit
  ARGS analyze ${audit_log} --time-column t --accel-unit deg/s -o ${audit_out}/analyze_accel_unit)

# adev --mode stream --partial with the error on the second data row: the one row before it
# reaches no tau, so nothing can be written, and the message says so instead of leaving the
# user to look for a partial file.
sigmatau_cli_test(NAME cli_audit_adev_partial_nothing_read EXIT 2
  STDERR ":3:2: expected a number, found \"abc\" \\(--partial: no results written: the 1 sample read before it reaches no tau\\)"
  NO_FILE ${audit_out}/partial_nothing.txt
  ARGS adev ${PROJECT_SOURCE_DIR}/tests/data/bad/non_numeric.csv --rate 100 --mode stream --partial
       -o ${audit_out}/partial_nothing.txt)

# An output that cannot be created was found only when writing, after the whole run (minutes on a
# long log). check_can_write now looks at the nearest existing directory first: the bad log here
# proves the order (before, its read error came first; now the output's error does, at once).
file(WRITE ${audit_out}/plain_file "in the way\n")
sigmatau_cli_test(NAME cli_audit_output_under_a_file_fails_early EXIT 2
  STDERR "cannot create directory .*cli_audit/plain_file: Not a directory"
  ARGS adev ${PROJECT_SOURCE_DIR}/tests/data/bad/non_numeric.csv --rate 100
       -o ${audit_out}/plain_file/adev.txt)
sigmatau_cli_test(NAME cli_audit_analyze_output_under_a_file_fails_early EXIT 2
  STDERR "cannot create directory .*cli_audit/plain_file: Not a directory"
  ARGS analyze ${PROJECT_SOURCE_DIR}/tests/data/bad/non_numeric.csv --rate 100
       -o ${audit_out}/plain_file/report)
# analyze -o DIR/ (a trailing slash, as shell completion types it) created DIR and then could
# not move the finished report into place: "cannot rename: Invalid argument", exit 2.
sigmatau_cli_test(NAME cli_audit_analyze_output_trailing_slash EXIT 0
  STDOUT "wrote .*cli_audit/slash_report/ \\("
  ARGS analyze ${audit_log} --time-column t -o ${audit_out}/slash_report/ --force)

# fit on a saved adev result ignored the log options (--rate, --unit, --columns ...) silently:
# the result carries its own rate, units and channels. Now a usage error naming them.
add_test(NAME cli_audit_fit_saved_adev_fresh COMMAND ${CMAKE_COMMAND} -E rm -f ${audit_out}/adev_saved.json)
sigmatau_cli_test(NAME cli_audit_fit_saved_adev_make EXIT 0
  ARGS adev ${audit_log} --time-column t --unit deg/s --format json -o ${audit_out}/adev_saved.json)
set_tests_properties(cli_audit_fit_saved_adev_make PROPERTIES DEPENDS cli_audit_fit_saved_adev_fresh)
sigmatau_cli_test(NAME cli_audit_fit_saved_adev_with_log_options EXIT 2
  STDERR "adev_saved.json is a saved adev result .*: --rate, --unit would be ignored"
  NO_FILE ${audit_out}/fit_saved_options.txt
  ARGS fit ${audit_out}/adev_saved.json --rate 5 --unit deg/s -o ${audit_out}/fit_saved_options.txt)
sigmatau_cli_test(NAME cli_audit_fit_saved_adev_without_options EXIT 0 STDOUT "gx  joint  model "
  ARGS fit ${audit_out}/adev_saved.json)
set_tests_properties(cli_audit_fit_saved_adev_with_log_options
  cli_audit_fit_saved_adev_without_options PROPERTIES DEPENDS cli_audit_fit_saved_adev_make)

# A rate unit with --kind increment or phase was accepted by adev and psd (exit 0, deviations
# labelled (deg/s)/s); fit and analyze already refused it. Increments and phase are amounts.
sigmatau_cli_test(NAME cli_audit_adev_increment_with_rate_unit EXIT 2
  STDERR "--unit deg/s is an angular rate, but --kind increment says the values are per-sample increments"
  ARGS adev ${audit_log} --time-column t --kind increment --unit deg/s)
sigmatau_cli_test(NAME cli_audit_psd_phase_with_acceleration_unit EXIT 2
  STDERR "--unit m/s\\^2 is an acceleration, but --kind phase says the values are an integrated phase"
  ARGS psd ${audit_log} --time-column t --kind phase --unit m/s^2)
sigmatau_cli_test(NAME cli_audit_adev_increment_with_angle_unit EXIT 0 STDOUT "tau"
  ARGS adev ${audit_log} --time-column t --kind increment --unit deg --format csv)

# An interrupted plot left its scratch directory (sigmatau-plot-XXXXXX: the data files, the
# gnuplot log) in $TMPDIR. A stand-in `gnuplot` that only sleeps holds the run inside the plot
# step, with every scratch file written, while the signal arrives; TMPDIR is a private
# directory, which must be empty afterwards, and the plot must not appear.
# Arguments of the script: $1 the CLI, $2 a scratch directory, $3 the log.
set(plot_interrupt_check [=[
set -m
dir=$2; rm -rf "$dir" && mkdir -p "$dir/tmp" "$dir/bin" "$dir/out" || exit 1
printf '#!/bin/sh\necho $$ > "%s"\nexec sleep 30\n' "$dir/gnuplot.pid" > "$dir/bin/gnuplot"
chmod +x "$dir/bin/gnuplot"
TMPDIR=$dir/tmp PATH=$dir/bin:$PATH "$1" adev "$3" --time-column t --plot "$dir/out/adev.pdf" \
  >/dev/null 2>&1 &
pid=$!
for i in $(seq 300); do ls "$dir"/tmp/*/adev.dat >/dev/null 2>&1 && break; sleep 0.1; done
stop_gnuplot() { [ -s "$dir/gnuplot.pid" ] && kill -KILL "$(cat "$dir/gnuplot.pid")" 2>/dev/null; }
if ! ls "$dir"/tmp/*/adev.dat >/dev/null 2>&1; then
  echo "the plot step was never reached"; kill -KILL $pid; stop_gnuplot; rm -rf "$dir"; exit 1
fi
kill -INT $pid; wait $pid; rc=$?
left=$(cd "$dir/tmp" && find . -mindepth 1); out=$(ls -A "$dir/out")
stop_gnuplot
echo "exit $rc (expected 130); left in TMPDIR: '$left'; outputs: '$out'"
rm -rf "$dir"
[ "$rc" = 130 ] && [ -z "$left" ] && [ -z "$out" ]
]=])
add_test(NAME cli_audit_interrupted_plot_leaves_no_scratch
         COMMAND bash -c "${plot_interrupt_check}" plot_interrupt $<TARGET_FILE:sigmatau_cli>
                 ${audit_out}/plot_interrupt ${audit_log})
