#!/usr/bin/env python3
"""Calibrate's gyro bias with the Earth rate, over seeds of a simulated multi-position log:
`sigmatau simulate` writes a 12-position log (gyro white noise N = 0.15 deg/sqrt(h), accel
N = 60 ug/sqrt(Hz), 100 Hz, the default 20 s rests and 90 deg/s turns, latitude 48 deg, no
scale, misalignment or bias errors, so the true gyro bias is 0), then
`sigmatau calibrate --latitude 48 --format json` (default --ci 0.95) fits it. Per seed: the
gyro bias error (estimate - truth) per axis, the half-width of its interval, and whether the
interval holds the truth; then the mean error, the mean half-width and the count that hold it.
Usage: bench/calibrate_earth_rate.py --sigmatau BUILD/cli/sigmatau [--seeds 1-20]
[--latitude 48] [--positions 12] [--dwell "20 s"]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

MICRO = 1e6  # rad/s -> urad/s


def run(command):
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"{' '.join(command)} failed ({done.returncode}): {done.stderr.strip()}")
    return done


def seed_range(text):
    first, _, last = text.partition("-")
    return range(int(first), int(last or first) + 1)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sigmatau", required=True, help="the sigmatau CLI binary")
    parser.add_argument("--seeds", default="1-20", help="FIRST-LAST")
    parser.add_argument("--latitude", default="48", help="latitude [deg]")
    parser.add_argument("--positions", default="12")
    parser.add_argument("--dwell", default="20 s")
    parser.add_argument("--gyro-model", default="N=0.15 deg/sqrt(h)")
    parser.add_argument("--accel-model", default="N=60 ug/sqrt(Hz)")
    args = parser.parse_args()

    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        log = os.path.join(tmp, "cal.csv")
        result = os.path.join(tmp, "cal.json")
        for seed in seed_range(args.seeds):
            run([args.sigmatau, "simulate", "--model", args.gyro_model, "--accel-model",
                 args.accel_model, "--rate", "100", "--sensors", "gyro,accel", "--positions",
                 args.positions, "--dwell", args.dwell, "--latitude", f"{args.latitude} deg",
                 "--seed", str(seed), "--force", "-o", log])
            run([args.sigmatau, "calibrate", log, "--time-column", "t", "--latitude",
                 args.latitude, "--format", "json", "--force", "-o", result])
            with open(result) as f:
                gyro = json.load(f)["gyroscope"]
            if gyro["unit"] != "rad/s":
                sys.exit(f"unexpected gyro unit {gyro['unit']}")
            truth = [0.0, 0.0, 0.0]  # no --gyro-bias: the simulated bias is 0
            rows.append({
                "seed": seed,
                "model": gyro.get("earth_rate_model", "?"),
                "error": [(b - t) * MICRO for b, t in zip(gyro["bias"], truth)],
                "half": [(hi - lo) / 2 * MICRO for lo, hi in gyro["bias_ci"]],
                "holds": [lo <= t <= hi for (lo, hi), t in zip(gyro["bias_ci"], truth)],
                "confidence": gyro["confidence"],
            })

    confidence = rows[0]["confidence"]
    print(f"Gyro bias error [urad/s] and {100 * confidence:g} % interval half-width per seed "
          "(earth_rate_model from the JSON).\n")
    print("| seed | Earth rate | x error | x half | y error | y half | z error | z half | "
          "z holds |")
    print("|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        cells = " | ".join(f"{r['error'][a]:+.2f} | {r['half'][a]:.2f}" for a in range(3))
        print(f"| {r['seed']} | {r['model']} | {cells} | {'yes' if r['holds'][2] else 'no'} |")
    print(f"\n| axis | mean error | sd of error | mean half-width | intervals holding the truth |")
    print("|---|---|---|---|---|")
    for a, name in enumerate("xyz"):
        errors = [r["error"][a] for r in rows]
        print(f"| {name} | {statistics.mean(errors):+.2f} | {statistics.stdev(errors):.2f} | "
              f"{statistics.mean(r['half'][a] for r in rows):.2f} | "
              f"{sum(r['holds'][a] for r in rows)} of {len(rows)} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
