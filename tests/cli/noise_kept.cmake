# The noise type at one tau does not depend on the other taus asked for (issue 28): on an
# 8192-point phase record (white FM with random-walk FM growing in, written here with Python's
# seeded generator), m = 1024 was white FM with `--taus 1024` and flicker FM with
# `--taus 512,1024` (bounds 5 % apart). Now the type there comes from a factor fixed by the
# record (kept_noise_factor), so the point is the same bits whatever else is asked: alone, with
# 512, in the octave run, out of core (--memory 1K) and, within the stream mode, alone or in
# its octave run.
set(noise_kept_check [=[
python3 - "$W/phase.txt" <<'PY' || fail "python3 could not write the record"
import random, sys
r = random.Random(1)
walk = phase = 0.0
with open(sys.argv[1], "w") as f:
    for i in range(8192):
        walk += 0.02 * r.gauss(0, 1)
        phase += r.gauss(0, 1) + walk
        f.write("%.17g\n" % (phase * 1e-9))
PY
point() {  # point NAME ARGS...: the m = 1024 point of the JSON output as "alpha ci_low ci_high"
  local name=$1; shift
  run adev "$W/phase.txt" --kind phase --rate 1 --stat oadev --format json -o "$W/$name.json" --force "$@"
  expect 0 ''
  python3 -c '
import json, sys
points = json.load(open(sys.argv[1]))["results"][0]["points"]
p = [p for p in points if p["m"] == 1024][0]
print(p["alpha"], repr(p["ci_low"]), repr(p["ci_high"]))' "$W/$name.json" > "$W/$name.point" ||
    fail "no m = 1024 point in $name.json"
  echo "$name: $(cat "$W/$name.point")"
}
point alone --taus 1024
point pair --taus 512,1024
point octave --taus octave
point out_of_core --taus 1024 --memory 1K
for other in pair octave out_of_core; do
  cmp -s "$W/alone.point" "$W/$other.point" ||
    fail "m = 1024 with --taus 1024 ($(cat "$W/alone.point")) differs from $other ($(cat "$W/$other.point"))"
done
point stream_alone --taus 1024 --mode stream
point stream_octave --taus octave --mode stream
cmp -s "$W/stream_alone.point" "$W/stream_octave.point" ||
  fail "stream: m = 1024 alone ($(cat "$W/stream_alone.point")) differs from octave ($(cat "$W/stream_octave.point"))"
echo "ok: the same type and bounds at m = 1024 whatever other taus are asked for"
]=])
add_test(NAME cli_noise_kept_independent_of_taus
         COMMAND bash -c "${sigmatau_cli_shell_prologue}${noise_kept_check}" noise_kept
                 $<TARGET_FILE:sigmatau_cli> ${CMAKE_CURRENT_BINARY_DIR}/cli_noise_kept none)
