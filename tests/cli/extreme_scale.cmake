# Finite but extreme samples (issue 28): white noise at 1e-200 gave OADEV exactly 0, at 1e-160
# 5e-5 off, and from about 1e155 up "deviation must be finite and >= 0, got -nan" with no file
# named, while `psd` printed N = inf with exit 0. Now adev's deviations, bounds and noise types of
# the same noise at 1e-200, 1e-160, 1e155 and 1e300 are the unit-scale ones times the scale
# (relative 1e-12: each written value rounds by up to 2^-53 relative, test_extreme_scale.cpp), in
# exact, out-of-core (--memory 1K) and stream mode; a PSD, whose values are squares of the
# samples, is refused where a double cannot hold it, naming the file and the supported range; the
# fit's model and terms are the unit-scale ones (terms x scale).
set(extreme_scale_check [=[
python3 - "$W" <<'PY' || fail "python3 could not write the logs"
import random, sys
r = random.Random(5)
y = [r.gauss(0.25, 1.0) for _ in range(4096)]
for name, scale in [("unit", 1.0), ("s1e-200", 1e-200), ("s1e-160", 1e-160),
                    ("s1e155", 1e155), ("s1e300", 1e300)]:
    with open("%s/%s.txt" % (sys.argv[1], name), "w") as f:
        f.writelines("%.17g\n" % (v * scale) for v in y)
PY
compare() {  # compare SCALE UNIT_JSON SCALED_JSON
  python3 - "$@" <<'PY'
import json, sys
scale = float(sys.argv[1])
unit, scaled = (json.load(open(p))["results"] for p in sys.argv[2:4])
assert len(unit) == len(scaled), "different numbers of curves"
count = 0
for a, b in zip(unit, scaled):
    assert len(a["points"]) == len(b["points"]) > 0, a["statistic"]
    for p, q in zip(a["points"], b["points"]):
        assert p["m"] == q["m"] and p["alpha"] == q["alpha"], (a["statistic"], p, q)
        for key in ("dev", "ci_low", "ci_high"):
            rel = abs(q[key] / scale / p[key] - 1)
            assert rel <= 1e-12, "%s m=%d %s: %r vs %r x %g (rel %.2g)" % (
                a["statistic"], p["m"], key, q[key], p[key], scale, rel)
            count += 1
print("ok: %d values equal to the unit-scale ones x %g" % (count, scale))
PY
}
for mode in exact out_of_core stream; do
  case $mode in
    exact) args="--stat adev,oadev,mdev,hdev,totdev" ;;
    out_of_core) args="--stat adev,oadev,mdev,hdev,totdev --memory 1K" ;;
    stream) args="--stat adev,oadev,mdev,hdev --mode stream" ;;
  esac
  run adev "$W/unit.txt" --rate 100 $args --format json -o "$W/unit_$mode.json" --force
  expect 0 ''
  for scale in 1e-200 1e-160 1e155 1e300; do
    run adev "$W/s$scale.txt" --rate 100 $args --format json -o "$W/s${scale}_$mode.json" --force
    expect 0 ''
    compare $scale "$W/unit_$mode.json" "$W/s${scale}_$mode.json" || fail "$mode at $scale"
  done
done
# The fit (AVAR covariances are fourth powers of the deviations: at 1e100 it kept a wrong model,
# at 1e-100 its covariance was not positive definite) gives the same model and terms x scale.
run fit "$W/unit.txt" --rate 100 --unit rad/s --format json -o "$W/unit_fit.json" --force
expect 0 ''
for scale in 1e-200 1e-160 1e155 1e300; do
  run fit "$W/s$scale.txt" --rate 100 --unit rad/s --format json -o "$W/s${scale}_fit.json" --force
  expect 0 ''
  python3 - $scale "$W/unit_fit.json" "$W/s${scale}_fit.json" <<'PY' || fail "fit at $scale"
import json, sys
scale = float(sys.argv[1])
a, b = (json.load(open(p))["channels"][0] for p in sys.argv[2:4])
assert a["model_terms"] == b["model_terms"], (a["model_terms"], b["model_terms"])
count = 0
for term, p in a["parameters"].items():
    for key in ("value", "ci_low", "ci_high", "upper_bound", "adev_min"):
        if key in p:
            rel = abs(b["parameters"][term][key] / scale / p[key] - 1)
            assert rel <= 1e-12, "%s %s: rel %.2g" % (term, key, rel)
            count += 1
print("ok: fit model %s, %d values x %g" % (a["model_terms"], count, scale))
PY
done
# A deviation itself beyond the largest double (phase of 1e300 s over 1 ns) is not representable:
# a clear error naming the statistic and tau (before: "deviation must be finite and >= 0, got
# inf").
run adev "$W/s1e300.txt" --kind phase --rate 1e9 --stat oadev
expect 2 "oadev at tau = 1e-09 s is beyond the largest double .*express them in another unit"
run psd "$W/unit.txt" --rate 100
expect 0 ''
for scale in 1e-200 1e-160 1e155 1e300; do
  run psd "$W/s$scale.txt" --rate 100
  expect 2 "s$scale.txt.*beyond the range of a double.*from about 1e-150 to 1e150 at 1 Hz"
done
]=])
add_test(NAME cli_extreme_scale
         COMMAND bash -c "${sigmatau_cli_shell_prologue}${extreme_scale_check}" extreme_scale
                 $<TARGET_FILE:sigmatau_cli> ${CMAKE_CURRENT_BINARY_DIR}/cli_extreme_scale none)
