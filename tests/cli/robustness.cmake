# Output safety and data warnings through the CLI (issue 9):
# - an existing output is kept without --force (content unchanged) and replaced with it, for
#   every verb that writes a file or a directory;
# - a full disk and an unwritable directory give exit 2 with the reason, and leave no file (no
#   partial output, no temporary name, no half-built analyze directory);
# - saturation, stuck-sensor and implausible-unit warnings reach results.json, summary.md and
#   report.html of `analyze`.
# The shell scripts below get the CLI as $1; each prints what it checks and exits non-zero on the
# first failure, or 77 (ctest: skipped) when the machine cannot provide the condition.
set(robust_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_robust)
set(robust_log ${PROJECT_SOURCE_DIR}/tests/data/cli/white_2ch_10Hz.csv)  # t,gx,gy; 2000 rows

function(sigmatau_robust_test name script)
  add_test(NAME ${name} COMMAND bash -c "${script}" ${name} $<TARGET_FILE:sigmatau_cli>
                                ${robust_dir}/${name} ${robust_log} ${ARGN})
  set_tests_properties(${name} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 120)
endfunction()

# Prologue: sigmatau_cli_shell_prologue (tests/CMakeLists.txt: $1 CLI, $2 a fresh work
# directory, $3 the 2-channel log; fail, run, expect), and `empty DIR`, which checks that DIR
# holds nothing (no partial or temporary file).
string(CONCAT robust_prologue "${sigmatau_cli_shell_prologue}" [=[
empty() { left=$(ls -A "$1"); [ -z "$left" ] || fail "$1 is not empty: $left"; }
]=])

# --force: $4 is the output kind (file|dir), the rest the verb's arguments without -o. The
# existing directory is an earlier report (the only kind --force replaces: output_safety.cmake)
# whose results.json was then changed.
set(force_check [=[
kind=$1; shift
out=$W/out
if [ "$kind" = dir ]; then
  "$S" "$@" -o "$out" >/dev/null 2>&1 && echo keep >"$out/results.json" || fail "no earlier report"
else
  echo keep >"$out"
fi
run "$@" -o "$out"
expect 2 "exists; use --force"
if [ "$kind" = dir ]; then
  [ "$(cat "$out/results.json")" = keep ] || fail "the existing directory was changed"
else
  [ "$(cat "$out")" = keep ] || fail "the existing file was changed"
fi
run "$@" -o "$out" --force
expect 0 ""
if [ "$kind" = dir ]; then
  [ "$(cat "$out/results.json")" != keep ] && [ -s "$out/results.json" ] || fail "--force did not replace the directory"
else
  [ "$(cat "$out")" != keep ] && [ -s "$out" ] || fail "--force did not replace the file"
fi
ls -A "$W" | grep -Eq 'tmp|partial' && fail "temporary files left: $(ls -A "$W")"
echo "ok: kept without --force, replaced with it"
]=])
sigmatau_robust_test(cli_robust_force_adev "${robust_prologue}${force_check}"
  file adev ${robust_log} --time-column t --format json)
sigmatau_robust_test(cli_robust_force_psd "${robust_prologue}${force_check}"
  file psd ${robust_log} --time-column t)
sigmatau_robust_test(cli_robust_force_fit "${robust_prologue}${force_check}"
  file fit ${robust_log} --time-column t)
sigmatau_robust_test(cli_robust_force_convert "${robust_prologue}${force_check}"
  file convert --spec safran_stim300 --rate 200 --to kalibr)
sigmatau_robust_test(cli_robust_force_simulate "${robust_prologue}${force_check}"
  file simulate --model "N=0.15 deg/sqrt(h)" --rate 100 --duration "10 s")
sigmatau_robust_test(cli_robust_force_analyze "${robust_prologue}${force_check}"
  dir analyze ${robust_log} --time-column t --gyro-unit deg/s)

# A full disk, two ways. (1) Always: a file-size limit (ulimit -f, in 1 KiB blocks) with SIGXFSZ
# ignored, so write(2) fails with EFBIG as it fails with ENOSPC on a full disk: the same code path.
# (2) Where mount(2) is allowed (root in most CI containers): a real 16 KiB tmpfs, ENOSPC.
# The outputs are far larger than the limit: `--taus all` gives ~1000 rows of JSON (~150 kB), the
# analyze directory holds SVG plots and an HTML report, simulate writes 1000 CSV rows.
set(full_disk_check [=[
limit=$1; shift
mnt=$W/disk; mkdir -p "$mnt"
if [ "$limit" = tmpfs ]; then
  mount -t tmpfs -o size=16k sigmatau_test "$mnt" 2>/dev/null || { echo "no mount(2): skipped"; exit 77; }
  trap 'umount "$mnt"' EXIT
  reason="No space left on device"
else
  trap '' XFSZ; ulimit -f 4 || exit 1
  reason="File too large"
fi
run adev "$LOG" --time-column t --taus all --format json -o "$mnt/adev.json"
expect 2 "cannot write $mnt/adev\.json.*$reason"
empty "$mnt"
run analyze "$LOG" --time-column t --gyro-unit deg/s -o "$mnt/report"
expect 2 "cannot write $mnt/report\.partial-[^/]+/.*$reason"
empty "$mnt"
run simulate --model "N=0.15 deg/sqrt(h)" --rate 100 --duration "10 s" -o "$mnt/sim.csv"
expect 2 "cannot write $mnt/sim\.csv.*$reason"
empty "$mnt"
echo "ok: no file left on the full disk"
]=])
sigmatau_robust_test(cli_robust_full_disk_fsize "${robust_prologue}${full_disk_check}" fsize)
sigmatau_robust_test(cli_robust_full_disk_tmpfs "${robust_prologue}${full_disk_check}" tmpfs)

# An unwritable directory: permission bits for a normal user; root ignores them, so for root a
# read-only tmpfs (skipped where mount(2) is refused). Then a "directory" that is a regular file,
# which fails for everyone.
set(unwritable_check [=[
dir=$W/locked; mkdir -p "$dir"
if [ "$(id -u)" = 0 ]; then
  mount -t tmpfs -o ro,size=64k sigmatau_test "$dir" 2>/dev/null || { echo "root without mount(2): skipped"; exit 77; }
  trap 'umount "$dir"' EXIT
  reason="Read-only file system"
else
  chmod 555 "$dir"; trap 'chmod 755 "$dir"' EXIT
  reason="Permission denied"
fi
run adev "$LOG" --time-column t --format json -o "$dir/adev.json"
expect 2 "cannot write $dir/adev\.json: $reason"
empty "$dir"
run analyze "$LOG" --time-column t --gyro-unit deg/s -o "$dir/report"
expect 2 "$dir/report"
empty "$dir"
run simulate --model "N=0.15 deg/sqrt(h)" --rate 100 --duration "10 s" -o "$dir/sim.csv"
expect 2 "$dir/sim\.csv"
empty "$dir"
echo plain >"$W/file"
run adev "$LOG" --time-column t --format json -o "$W/file/adev.json"
expect 2 "cannot create directory $W/file"
[ "$(cat "$W/file")" = plain ] || fail "the file in the way was changed"
echo "ok: no file left in the unwritable directory"
]=])
sigmatau_robust_test(cli_robust_unwritable_dir "${robust_prologue}${unwritable_check}")

# Data warnings in the report: 6000 rows at 100 Hz of a static IMU logged in deg/s and g (bias
# 0.5, -0.3, 1.2 deg/s; 1 g along z) but declared rad/s and m/s^2; gy stuck at 0.123 for rows
# 2000..2199 (200 >= 50 identical values), gz clipped at 2 for rows 4000..4019 (20 >= 5 values at
# its maximum; the noise never reaches 2). awk's rand() with a fixed seed: the assertions hold for
# any noise draw.
set(warnings_check [=[
awk 'BEGIN { srand(5); print "t,gx,gy,gz,ax,ay,az";
  for (i = 0; i < 6000; i++) {
    n = 0; for (k = 0; k < 12; k++) n += rand(); n -= 6;
    gx = 0.5 + 0.05 * n; gy = (i >= 2000 && i < 2200) ? 0.123 : -0.3 + 0.05 * (rand() - 0.5);
    gz = (i >= 4000 && i < 4020) ? 2 : 1.2 + 0.05 * (rand() - 0.5);
    printf "%.2f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n", i / 100, gx, gy, gz,
           0.001 * (rand() - 0.5), 0.001 * (rand() - 0.5), 1 + 0.001 * (rand() - 0.5) } }' >"$W/static.csv"
run analyze "$W/static.csv" --time-column t --gyro-unit rad/s --accel-unit m/s^2 --trim none -o "$W/out"
expect 0 "warning: .*gy.*stuck"
for f in results.json summary.md report.html; do
  for w in "gz: .*channel maximum 2 .*saturation" "gy: .*stuck sensor" \
           "static gyro .*look like deg/s, not rad/s" "static accelerometer .*look like g, not m/s\^2"; do
    grep -Eq -- "$w" "$W/out/$f" || fail "$f does not mention '$w'"
  done
  echo "ok: $f names the saturation, the stuck run and both unit problems"
done
]=])
sigmatau_robust_test(cli_robust_data_warnings_in_report "${robust_prologue}${warnings_check}")

# --nonfinite skip: the rows holding NaN or Inf are dropped and counted on stderr; the default
# (error) names the first one. 200 rows at 100 Hz with NaN in row 50 and inf in row 120.
set(nonfinite_check [=[
awk 'BEGIN { print "t,x"; for (i = 0; i < 200; i++) {
  v = (i == 50) ? "nan" : (i == 120) ? "inf" : sprintf("%d", (i * 37) % 11 - 5);
  printf "%.2f,%s\n", i / 100, v } }' >"$W/nonfinite.csv"
run adev "$W/nonfinite.csv" --time-column t
expect 2 "nonfinite\.csv:52:2: non-finite value"
run adev "$W/nonfinite.csv" --time-column t --nonfinite skip
expect 2 "nonfinite\.csv:53: time stamp gap .*2 rows were dropped by --nonfinite skip, and each leaves such a gap"
run adev "$W/nonfinite.csv" --time-column t --nonfinite skip --gaps split
expect 0 "note: .*nonfinite\.csv: 2 rows with a non-finite or non-numeric value skipped \(--nonfinite skip\)"
grep -q "198 samples" "$W/.stdout" || fail "expected 198 samples: $(head -1 "$W/.stdout")"
echo "ok: 198 samples kept"
]=])
sigmatau_robust_test(cli_robust_nonfinite "${robust_prologue}${nonfinite_check}")
