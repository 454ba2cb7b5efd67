# Outputs that are not plain new files (review D, findings 1, 5 and 16):
# - a character device, a FIFO, /dev/stdout and a process substitution (/dev/fd/N) are written
#   straight into, with or without --force, and stay what they were (as root the old writer
#   renamed a regular file over them: /dev/null became a regular file). The device is made with
#   mknod in the work directory (root only; skipped otherwise), never the machine's /dev/null;
# - a symbolic link is followed, never replaced: its target gets the usual rules;
# - missing parent directories are still created, beside a link's target (not the link);
# - past `ulimit -f` the process is not killed by SIGXFSZ: "File too large", exit 2, no .tmp-.
# Each script gets the CLI as $1, a fresh work directory as $2 and a 2-channel log as $3; it
# prints what it checks, exits non-zero on the first failure, 77 (skipped) when the machine
# cannot provide the condition.
set(special_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_output_special)
set(special_log ${PROJECT_SOURCE_DIR}/tests/data/cli/white_2ch_10Hz.csv)  # t,gx,gy; 2000 rows

function(sigmatau_output_special_test name script)
  add_test(NAME ${name} COMMAND bash -c "${script}" ${name} $<TARGET_FILE:sigmatau_cli>
                                ${special_dir}/${name} ${special_log})
  set_tests_properties(${name} PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 120)
endfunction()

string(CONCAT special_prologue "${sigmatau_cli_shell_prologue}" [=[
type_is() {  # type_is PATH TYPE (as stat -c %F names it)
  t=$(stat -c %F "$1" 2>&1); [ "$t" = "$2" ] || fail "$1 is a $t, expected a $2"
}
no_temporary() {
  left=$(ls -A "$1" | grep -E '\.tmp-|\.partial-'); [ -z "$left" ] || fail "left in $1: $left"
}
]=])

# A character device (a scratch copy of the null device, 1:3) and a link to it: adev, psd and
# --plot write into it; analyze refuses it as a directory even with --force. Each stays a device.
set(device_check [=[
mknod "$W/nul" c 1 3 2>/dev/null || { echo "mknod needs root: skipped"; exit 77; }
ln -s nul "$W/link"; ln -s nul "$W/plot.svg"
run adev "$LOG" --time-column t -o "$W/nul"
expect 0 ""
run adev "$LOG" --time-column t -o "$W/nul" --force
expect 0 ""
run adev "$LOG" --time-column t --format json -o "$W/link" --force
expect 0 ""
run psd "$LOG" --time-column t -o "$W/link"
expect 0 ""
if command -v gnuplot >/dev/null; then
  run adev "$LOG" --time-column t --plot "$W/plot.svg" --force
  expect 0 ""
else
  echo "no gnuplot: --plot not checked"
fi
run analyze "$LOG" --time-column t --gyro-unit deg/s -o "$W/link" --force
expect 2 "it is a device, pipe or socket; expected a directory name"
type_is "$W/nul" "character special file"
type_is "$W/link" "symbolic link"
type_is "$W/plot.svg" "symbolic link"
no_temporary "$W"
echo "ok: the device and the links to it are unchanged"
]=])
sigmatau_output_special_test(cli_output_special_device "${special_prologue}${device_check}")

# A FIFO read by `cat`, /dev/stdout into a pipe and into a file, a link to /proc/self/fd/1, and a
# process substitution: all get the whole table, without --force.
set(pipe_check [=[
want='^# gx  oadev'
mkfifo "$W/fifo" || exit 1
cat "$W/fifo" >"$W/from_fifo" 2>/dev/null & reader=$!
run adev "$LOG" --time-column t -o "$W/fifo"
# A writer that never opened the FIFO leaves its reader waiting: an empty write ends it.
[ "$rc" = 0 ] || timeout 5 bash -c ': >"$1"' _ "$W/fifo"
wait "$reader"
expect 0 ""
grep -q "$want" "$W/from_fifo" || fail "the FIFO's reader got: $(head -c 200 "$W/from_fifo")"
type_is "$W/fifo" "fifo"
echo "ok: through the FIFO"
"$S" adev "$LOG" --time-column t -o /dev/stdout 2>"$W/.stderr" | cat >"$W/from_pipe"
grep -q "$want" "$W/from_pipe" || fail "-o /dev/stdout into a pipe: $(cat "$W/.stderr")"
echo "ok: -o /dev/stdout into a pipe"
echo "kept" >"$W/appended"
"$S" adev "$LOG" --time-column t -o /dev/stdout >>"$W/appended" 2>"$W/.stderr" || fail "$(cat "$W/.stderr")"
[ "$(head -1 "$W/appended")" = kept ] && grep -q "$want" "$W/appended" ||
  fail "-o /dev/stdout >> file: $(head -c 200 "$W/appended")"
echo "ok: -o /dev/stdout appended to a file (>>)"
ln -s /proc/self/fd/1 "$W/so"
"$S" psd "$LOG" --time-column t -o "$W/so" --force 2>"$W/.stderr" | cat >"$W/from_link"
grep -q '^gx  *N = ' "$W/from_link" || fail "-o link to /proc/self/fd/1: $(cat "$W/.stderr")"
type_is "$W/so" "symbolic link"
echo "ok: a link to /proc/self/fd/1"
"$S" adev "$LOG" --time-column t -o >(gzip >"$W/out.gz") 2>"$W/.stderr" || fail "$(cat "$W/.stderr")"
for i in 1 2 3 4 5 6 7 8 9 10; do gzip -t "$W/out.gz" 2>/dev/null && break; sleep 0.2; done
gzip -dc "$W/out.gz" | grep -q "$want" || fail "process substitution: $(gzip -dc "$W/out.gz" | head -c 200)"
echo "ok: a process substitution"
no_temporary "$W"
]=])
sigmatau_output_special_test(cli_output_special_pipes "${special_prologue}${pipe_check}")

# A link to a regular file: refused without --force, the target replaced with it, the link kept;
# a dangling link creates its target; a temporary file goes beside the target, not the link.
set(link_check [=[
mkdir "$W/real" "$W/links"
echo keep >"$W/real/a.json"
ln -s ../real/a.json "$W/links/a.json"
run adev "$LOG" --time-column t --format json -o "$W/links/a.json"
expect 2 "a\.json \(-> .*real/a\.json\) exists; use --force"
[ "$(cat "$W/real/a.json")" = keep ] || fail "the target was changed without --force"
run adev "$LOG" --time-column t --format json -o "$W/links/a.json" --force
expect 0 ""
type_is "$W/links/a.json" "symbolic link"
grep -q '"tool"' "$W/real/a.json" || fail "the target was not replaced"
ln -s ../real/new.txt "$W/links/new.txt"
run psd "$LOG" --time-column t -o "$W/links/new.txt"
expect 0 ""
type_is "$W/links/new.txt" "symbolic link"
type_is "$W/real/new.txt" "regular file"
no_temporary "$W/real"; no_temporary "$W/links"
echo "ok: links followed and kept"
]=])
sigmatau_output_special_test(cli_output_special_links "${special_prologue}${link_check}")

# Missing parent directories are still created (review D finding 5: kept, as the test suite
# relies on it, and documented): for a link into a missing directory, beside the link's target,
# never beside the link; analyze -o DIR/ (a trailing slash) writes DIR itself.
set(parents_check [=[
mkdir "$W/links"
ln -s ../elsewhere/deeper/out.txt "$W/links/out.txt"
run adev "$LOG" --time-column t -o "$W/links/out.txt"
expect 0 ""
type_is "$W/links/out.txt" "symbolic link"
grep -q '^# gx  oadev' "$W/elsewhere/deeper/out.txt" || fail "nothing written through the link"
[ ! -e "$W/links/elsewhere" ] || fail "a directory was made beside the link"
no_temporary "$W/elsewhere/deeper"; no_temporary "$W/links"
run analyze "$LOG" --time-column t --gyro-unit deg/s -o "$W/new/report/"
expect 0 ""
[ -s "$W/new/report/results.json" ] || fail "analyze -o DIR/ did not write DIR"
no_temporary "$W/new"
echo "ok: directories made where the output goes"
]=])
sigmatau_output_special_test(cli_output_special_parents "${special_prologue}${parents_check}")

# A file-size limit with SIGXFSZ at its default action (as in an interactive shell; reset with
# env where the test runner ignores it): "File too large", exit 2, no temporary file.
set(fsize_check [=[
reset=""
env --default-signal=XFSZ true 2>/dev/null && reset="env --default-signal=XFSZ"
mkdir "$W/out"
( ulimit -f 4; $reset "$S" adev "$LOG" --time-column t --taus all --format json -o "$W/out/full.json" ) \
  >"$W/.stdout" 2>"$W/.stderr"
rc=$?; err=$(cat "$W/.stderr")
expect 2 "cannot write $W/out/full\.json: File too large"
left=$(ls -A "$W/out"); [ -z "$left" ] || fail "left behind: $left"
echo "ok: nothing left"
]=])
sigmatau_output_special_test(cli_output_special_file_size_limit "${special_prologue}${fsize_check}")

# simulate into a FIFO (as `-o /dev/stdout | sigmatau adev -` does): its truth cannot go beside
# the FIFO as FIFO.json (beside /dev/stdout that is /dev/stdout.json), so without --sidecar it is
# refused before anything is written; --sidecar FILE puts it there, --sidecar none leaves it out.
set(simulate_fifo_check [=[
mkfifo "$W/log" || exit 77
model="N=0.1 deg/sqrt(h)"
run simulate --model "$model" --rate 100 --duration 10s -o "$W/log"
expect 2 "$W/log is a device or pipe, so its truth cannot go beside it as $W/log\.json: give --sidecar FILE"
[ ! -e "$W/log.json" ] || fail "log.json written"
type_is "$W/log" "fifo"
cat "$W/log" >"$W/read.csv" &
reader=$!
run simulate --model "$model" --rate 100 --duration 10s -o "$W/log" --sidecar "$W/truth.json"
wait $reader
expect 0 "wrote $W/log \(1000 samples at 100 Hz, kind rate\) and $W/truth\.json"
[ "$(wc -l <"$W/read.csv")" = 1001 ] || fail "the reader got $(wc -l <"$W/read.csv") lines, expected 1001"
grep -q '"theory"' "$W/truth.json" || fail "no truth in truth.json"
cat "$W/log" >/dev/null &
reader=$!
run simulate --model "$model" --rate 100 --duration 10s -o "$W/log" --sidecar none
wait $reader
expect 0 "without its truth \(--sidecar none\)"
[ ! -e "$W/log.json" ] || fail "log.json written with --sidecar none"
type_is "$W/log" "fifo"
echo "ok: simulate into a FIFO"
]=])
sigmatau_output_special_test(cli_output_special_simulate_fifo "${special_prologue}${simulate_fifo_check}")
