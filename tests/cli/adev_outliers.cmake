# `adev` and `psd` run the outlier check `analyze` runs (data_checks.hpp, OutlierChecker, through
# cli/outlier_warnings.hpp): the warning reaches stderr and the JSON's `warnings` with the channel,
# the count and the first and largest rows and values in the declared unit, and it is the same
# text in every mode: adev exact in memory, exact out of core (--memory 1K: the file is read
# twice, the check rides on the first pass) and --mode stream (block by block); psd in memory
# (--gaps split) and block by block. A clean channel gets none. (That the check gives the same
# result however the values are split is test_outlier_check's; here the verbs' wiring.)
#
# The log: 140,000 rows at 100 Hz, i.e. three reader blocks of up to 65536 rows, so the stream
# and out-of-core checks see the values in pieces (34 outlier blocks of 4096 rows and a tail of
# 736). Gyro in deg/s, noise 0.01 deg/s from awk's rand() as a sum of 12 uniforms (Irwin-Hall:
# never beyond 6 sigma, so no draw can pass 8 robust sigma, whose estimate is within a few % of
# sigma); gx gets spikes of 0.5 deg/s at row 1234, -0.3 at row 70000 (second reader block) and
# 0.2 at row 139999 (in the tail), i.e. 50, 30 and 20 sigma; gy and gz are clean.
# A phase log (--kind phase, 10,000 rows) is checked on its differences: one difference of 50
# sigma (a step in the phase) at row 5000.
set(adev_outliers_check [=[
awk 'BEGIN { srand(7); print "gx,gy,gz";
  for (i = 0; i < 140000; i++) {
    a = 0; b = 0; c = 0;
    for (k = 0; k < 12; k++) { a += rand(); b += rand(); c += rand() }
    gx = 0.01 * (a - 6);
    if (i == 1234) gx = 0.5; if (i == 70000) gx = -0.3; if (i == 139999) gx = 0.2;
    printf "%.6f,%.6f,%.6f\n", gx, 0.01 * (b - 6), 0.01 * (c - 6) } }' >"$W/spiky.csv"
message='gx: 3 samples beyond 8 robust sigma of their 4096-row block \(outliers or spikes: they raise the Allan deviation at short taus and the white-noise level N\); largest [0-9.]+ sigma \(0\.5 deg/s\) at row 1234, first at row 1234 \(0\.5 deg/s\)'
clean='(gy|gz): [0-9]+ samples? beyond'
# check NAME JSON: the warning on stderr (after the input's name, as adev's other warnings), one
# outlier line in the JSON's warnings, none for gy / gz; keeps the JSON's outlier line in
# $W/NAME.line for the comparison between modes.
check() {
  printf '%s' "$err" | grep -Eq -- "^sigmatau: warning: [^ ]*(spiky|timed)\.csv: $message" ||
    fail "$1: no outlier warning on stderr: $err"
  if printf '%s' "$err" | grep -Eq -- "$clean"; then fail "$1: a clean channel is flagged: $err"; fi
  grep -Eq -- "^ *\"warnings\": \[" "$2" || fail "$1: no warnings list in the JSON"
  grep -E -- "^  \"$message\"" "$2" >"$W/$1.line" || fail "$1: the JSON's warnings lack the outlier warning"
  [ "$(grep -c 'robust sigma' "$2")" = 1 ] || fail "$1: not exactly one outlier line in the JSON"
  echo "ok: $1 warns about gx's 3 spikes on stderr and in the JSON, not about gy, gz"
}
run adev "$W/spiky.csv" --rate 100 --gyro-unit deg/s --format json -o "$W/exact.json"
expect 0 ""
check exact "$W/exact.json"
run adev "$W/spiky.csv" --rate 100 --gyro-unit deg/s --format json -o "$W/ooc.json" --memory 1K
expect 0 "computing exactly out of core"
check out_of_core "$W/ooc.json"
run adev "$W/spiky.csv" --rate 100 --gyro-unit deg/s --format json -o "$W/stream.json" --mode stream
expect 0 ""
check stream "$W/stream.json"
# --threads 1: the blocks are checked on the reading thread instead of a worker.
run adev "$W/spiky.csv" --rate 100 --gyro-unit deg/s --format json -o "$W/stream1.json" --mode stream --threads 1
expect 0 ""
check stream_threads_1 "$W/stream1.json"
# --unit: the samples are scaled to SI as they are read; the message still shows deg/s.
run adev "$W/spiky.csv" --rate 100 --unit deg/s --format json -o "$W/unit.json" --mode stream
expect 0 ""
check unit "$W/unit.json"
run psd "$W/spiky.csv" --rate 100 --gyro-unit deg/s --segment 1024 --format json -o "$W/psd.json"
expect 0 ""
check psd_blocks "$W/psd.json"
awk 'NR == 1 { print "t," $0; next } { printf "%.2f,%s\n", (NR - 2) / 100, $0 }' "$W/spiky.csv" >"$W/timed.csv"
run psd "$W/timed.csv" --time-column t --gaps split --gyro-unit deg/s --format json -o "$W/psd_memory.json"
expect 0 ""
check psd_memory "$W/psd_memory.json"
for mode in out_of_core stream stream_threads_1 unit psd_blocks psd_memory; do
  cmp -s "$W/exact.line" "$W/$mode.line" || fail "$mode's outlier warning differs from exact's: $(cat "$W/$mode.line")"
done
echo "ok: the same outlier warning in every mode of adev and psd"
run adev "$W/spiky.csv" --rate 100 --gyro-unit deg/s --columns gy,gz --format json -o "$W/clean.json"
expect 0 ""
if printf '%s' "$err" | grep -q 'robust sigma'; then fail "clean channels warned: $err"; fi
grep -Eq '^ "warnings": \[\],?$' "$W/clean.json" || fail "clean channels: the JSON's warnings are not empty"
run adev "$W/spiky.csv" --rate 100 --gyro-unit deg/s --columns gy,gz --mode stream --format json -o "$W/clean_stream.json"
expect 0 ""
grep -Eq '^ "warnings": \[\],?$' "$W/clean_stream.json" || fail "clean channels (stream): the JSON's warnings are not empty"
echo "ok: no outlier warning on the clean channels gy, gz"

# Phase data: the check runs on the differences of consecutive samples (as analyze's).
awk 'BEGIN { srand(5); print "p"; x = 0;
  for (i = 0; i < 10000; i++) {
    a = 0; for (k = 0; k < 12; k++) a += rand();
    d = 0.01 * (a - 6); if (i == 5000) d = 0.5;
    x += d; printf "%.6f\n", x } }' >"$W/phase.csv"
phase='p: 1 difference of consecutive samples beyond 8 robust sigma of their 4096-row block \(steps in the phase, spikes in the frequency: they raise the deviation at short taus\); .*at row 5000, first at row 5000'
for mode in "--mode exact" "--memory 1K" "--mode stream"; do
  # shellcheck disable=SC2086
  run adev "$W/phase.csv" --rate 100 --kind phase $mode --format json -o "$W/phase.json" --force
  expect 0 "$phase"
  grep -Eq -- "^  \"$phase" "$W/phase.json" || fail "phase ($mode): the JSON's warnings lack the outlier warning"
done
echo "ok: phase data are checked on their differences in every adev mode"
]=])
add_test(NAME cli_adev_outliers
         COMMAND bash -c "${sigmatau_cli_shell_prologue}${adev_outliers_check}" cli_adev_outliers
                 $<TARGET_FILE:sigmatau_cli> ${CMAKE_CURRENT_BINARY_DIR}/cli_adev_outliers none)
set_tests_properties(cli_adev_outliers PROPERTIES TIMEOUT 180)
