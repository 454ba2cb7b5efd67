# `analyze` on a log with spikes (data_checks.hpp, check_outliers): the outlier warning reaches
# stderr, results.json, summary.md and report.html with the channel, the count and the first and
# largest rows and values in the declared unit; the clean channels get none; the bounded-memory
# run (--memory 1K) writes the same files as the in-memory one.
#
# The log: 20,000 rows at 100 Hz (4 blocks of 4096 and a tail of 3616), gyro in deg/s, noise
# 0.01 deg/s from awk's rand() as a sum of 12 uniforms (Irwin-Hall: never beyond 6 sigma, so no
# draw can pass 8 robust sigma, whose estimate is within a few % of sigma); gx gets spikes of
# 0.5 deg/s at row 1234, -0.3 at row 9000 and 0.2 at row 19999 (in the tail), i.e. 50, 30 and
# 20 sigma.
set(outliers_check [=[
awk 'BEGIN { srand(11); print "t,gx,gy,gz";
  for (i = 0; i < 20000; i++) {
    a = 0; b = 0; c = 0;
    for (k = 0; k < 12; k++) { a += rand(); b += rand(); c += rand() }
    gx = 0.01 * (a - 6);
    if (i == 1234) gx = 0.5; if (i == 9000) gx = -0.3; if (i == 19999) gx = 0.2;
    printf "%.2f,%.6f,%.6f,%.6f\n", i / 100, gx, 0.01 * (b - 6), 0.01 * (c - 6) } }' >"$W/spiky.csv"
message='gx: 3 samples beyond 8 robust sigma of their 4096-row block .*largest [0-9.]+ sigma \(0\.5 deg/s\) at row 1234, first at row 1234 \(0\.5 deg/s\)'
run analyze "$W/spiky.csv" --time-column t --gyro-unit deg/s --trim none -o "$W/memory"
expect 0 "warning: $message"
run analyze "$W/spiky.csv" --time-column t --gyro-unit deg/s --trim none --memory 1K -o "$W/bounded"
expect 0 "bounded memory"
for f in results.json summary.md report.html; do
  grep -Eq -- "$message" "$W/memory/$f" || fail "$f does not carry the outlier warning"
  if grep -Eq -- '(gy|gz): [0-9]+ samples? beyond' "$W/memory/$f"; then fail "$f flags a clean channel"; fi
done
for f in summary.md report.html; do
  grep -Eq -- 'Warning:?.*; outliers in gx: they raise' "$W/memory/$f" || fail "$f: the banner does not name gx's outliers"
done
echo "ok: the outlier warning (3 spikes on gx, none on gy, gz) is in results.json, summary.md, report.html and their banners"
stamp='[0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}Z'
count=0
for f in "$W/memory"/*; do
  name=$(basename "$f")
  [ -f "$W/bounded/$name" ] || fail "$name: written in memory, missing from the bounded run"
  if ! diff <(sed -E "s/$stamp/<created>/g" "$f") <(sed -E "s/$stamp/<created>/g" "$W/bounded/$name") >/dev/null; then
    fail "$name differs between the in-memory and the bounded run"
  fi
  count=$((count + 1))
done
[ "$count" -ge 3 ] || fail "only $count files written"
[ "$(ls "$W/bounded" | wc -l)" = "$count" ] || fail "the bounded run wrote other files"
echo "ok: the bounded run wrote the same $count files"
]=])
add_test(NAME cli_analyze_outliers
         COMMAND bash -c "${sigmatau_cli_shell_prologue}${outliers_check}" cli_analyze_outliers
                 $<TARGET_FILE:sigmatau_cli> ${CMAKE_CURRENT_BINARY_DIR}/cli_analyze_outliers none)
set_tests_properties(cli_analyze_outliers PROPERTIES TIMEOUT 120)
