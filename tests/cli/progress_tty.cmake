# Progress on a terminal (review D, finding 15): a log read several times (exact out of core:
# twice per group of --threads channels) says which pass each 0-100 % line belongs to; with
# stderr not a terminal nothing is drawn. `script` (util-linux, in every Debian) gives the TTY;
# skipped when it is missing.
set(progress_script [=[
set -u
S=$1; W=$2; LOG=$3
rm -rf "$W"; mkdir -p "$W" || exit 1
command -v script >/dev/null || { echo "no script(1): skipped"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }
script -qc "$S adev $LOG --time-column t --memory 1K --threads 1 -o $W/tty.txt" "$W/typescript" >/dev/null ||
  fail "adev on a TTY failed: $(cat "$W/typescript")"
shown=$(tr '\r' '\n' <"$W/typescript")
for pass in "pass 1 \(scan\): read" "pass 2 of 4 \(phase, channels 1-1 of 2\): read" \
            "pass 3 of 4 \(scan, channels 2-2 of 2\): read" "pass 4 of 4 \(phase, channels 2-2 of 2\): read"; do
  printf '%s' "$shown" | grep -Eq "$pass" || fail "no '$pass' in: $shown"
done
echo "ok: four labelled passes on a TTY"
"$S" adev "$LOG" --time-column t --memory 1K --threads 1 -o "$W/pipe.txt" 2>"$W/err" || fail "adev failed"
grep -q "read " "$W/err" && fail "progress drawn without a TTY: $(cat "$W/err")"
cmp -s "$W/tty.txt" "$W/pipe.txt" || fail "the results differ with and without a TTY"
echo "ok: nothing drawn without a TTY, same results"
]=])
add_test(NAME cli_progress_tty
         COMMAND bash -c "${progress_script}" cli_progress_tty $<TARGET_FILE:sigmatau_cli>
                 ${CMAKE_CURRENT_BINARY_DIR}/cli_progress_tty
                 ${PROJECT_SOURCE_DIR}/tests/data/cli/white_2ch_10Hz.csv)
set_tests_properties(cli_progress_tty PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 60)
