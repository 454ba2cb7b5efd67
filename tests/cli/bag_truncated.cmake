# A ROS bag whose recording was cut short (review_d finding 5: the recorder died, by a crash, a
# full disk or Ctrl-C, so the file has no index or summary and ends inside a record):
# - by default exit 2, naming the byte of the cut and the count of complete messages before it,
#   and saying to give --truncated use; nothing on stdout;
# - with --truncated use adev (exact, stream, out of core), psd, fit and analyze analyse those
#   messages (exit 0) and a warning names the same byte and count; adev's sample count is that
#   count. (calibrate shares the option and the note; it needs a multi-position log.)
# The cut files are made from the bags make_test_bags writes (fixture cli_bags, see bags.cmake):
# imu_lz4.mcap (no summary, lz4 chunks, 20000 Imu messages) loses its last 5000 bytes, imu.bag
# (indexed, 1.6 MB) its last 300000: the index and the last chunks. The script gets the CLI as $1, a work directory as
# $2 and the bag directory as $3, prints what it checks and exits non-zero on the first failure.
set(truncated_bag_dir ${CMAKE_CURRENT_BINARY_DIR}/cli_bags)  # bags.cmake's bag_dir
set(truncated_script [=[
set -u
S=$1; W=$2; B=$3
rm -rf "$W"; mkdir -p "$W" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
run() { "$S" "$@" >"$W/out" 2>"$W/err"; rc=$?; err=$(cat "$W/err"); }
cut_copy() {  # cut_copy SOURCE TARGET BYTES: all but the last BYTES bytes
  size=$(stat -c %s "$1") || fail "no $1"
  head -c $((size - $3)) "$1" >"$2"
}
check_cut() {  # check_cut FILE TOPIC TOTAL VERB-ARGS...: default error, then --truncated use
  f=$1; topic=$2; total=$3; shift 3
  name=$(basename "$f")
  run adev "$f" --columns gx --taus 1
  [ "$rc" = 2 ] || fail "$name default: exit $rc, expected 2: $err"
  [ -s "$W/out" ] && fail "$name default: wrote to stdout"
  at=$(printf '%s' "$err" | sed -nE 's/.*cut short at byte ([0-9]+) after [0-9]+ complete messages.*/\1/p')
  n=$(printf '%s' "$err" | sed -nE 's/.*cut short at byte [0-9]+ after ([0-9]+) complete messages.*/\1/p')
  [ -n "$at" ] && [ -n "$n" ] || fail "$name default: no byte and count in: $err"
  printf '%s' "$err" | grep -q -- "give --truncated use" || fail "$name: no way forward in: $err"
  [ "$n" -gt 0 ] && [ "$n" -lt "$total" ] || fail "$name: $n complete messages of $total"
  echo "ok: $name refused by default: cut at byte $at after $n of $total messages"
  note="warning: .*$name: the recording was cut short at byte $at \(its recorder stopped without closing the file\); the $n complete messages of $topic before the cut are used \(--truncated use\)"
  for verb in "adev --columns gx --taus 1" "adev --columns gx --taus 1 --mode stream" \
              "adev --columns gx --taus 1 --memory 1K" "psd --columns gx" "fit --columns gx" \
              "analyze --columns gx,gy,gz --force -o $W/analyze"; do
    # shellcheck disable=SC2086
    run $verb "$f" --truncated use
    [ "$rc" = 0 ] || fail "$name $verb --truncated use: exit $rc: $err"
    printf '%s' "$err" | grep -Eq -- "$note" || fail "$name $verb: no note '$note' in: $err"
    echo "ok: $name $verb --truncated use: exit 0 and the note"
  done
  grep -q "\"truncated_at_byte\": *$at[,}]" "$W/analyze/results.json" ||
    fail "$name: analyze's results.json does not record truncated_at_byte $at"
  run adev "$f" --columns gx --taus 1 --truncated use
  grep -q "$name: $n samples at 200 Hz" "$W/out" || fail "$name: not $n samples: $(head -1 "$W/out")"
  run adev "$f" --columns gx --taus 1 --truncated use --format json
  grep -q "\"truncated_at_byte\": *$at," "$W/out" || fail "$name: adev's JSON does not record truncated_at_byte $at"
  echo "ok: $name: $n samples analysed"
}
cut_copy "$B/imu_lz4.mcap" "$W/CUT.mcap" 5000
check_cut "$W/CUT.mcap" /imu/data 20000
cut_copy "$B/imu.bag" "$W/CUT.bag" 300000
check_cut "$W/CUT.bag" /imu/data 20000
# A complete bag reads without the note; --truncated is refused for other inputs and bad values.
run adev "$B/imu_lz4.mcap" --columns gx --taus 1 --truncated use
[ "$rc" = 0 ] || fail "complete bag: exit $rc: $err"
printf '%s' "$err" | grep -q "cut short" && fail "complete bag: a cut note: $err"
run adev "$B/imu.csv" --time-column t --time-unit ns --columns gx --truncated use
[ "$rc" = 2 ] || fail "CSV --truncated use: exit $rc"
printf '%s' "$err" | grep -q -- "--truncated is for ROS bags" || fail "CSV: $err"
run adev "$W/CUT.mcap" --truncated keep
[ "$rc" = 2 ] || fail "--truncated keep: exit $rc"
printf '%s' "$err" | grep -q 'unknown --truncated value "keep" (expected error or use)' || fail "$err"
echo "ok: complete bag silent, CSV and an unknown value refused"
]=])
add_test(NAME cli_bag_truncated
         COMMAND bash -c "${truncated_script}" cli_bag_truncated $<TARGET_FILE:sigmatau_cli>
                 ${CMAKE_CURRENT_BINARY_DIR}/cli_bag_truncated ${truncated_bag_dir})
set_tests_properties(cli_bag_truncated PROPERTIES FIXTURES_REQUIRED cli_bags TIMEOUT 300)
