#!/usr/bin/env python3
"""Stream against exact OADEV on the real IMU logs: for each log, `sigmatau adev --mode stream`
(default --density) and `--mode exact`, both --format json, default taus (octave) and --ci
(0.683), compared per channel and tau. Prints per log:
  rel. dev. max / median: |stream - exact| / exact over every (channel, tau) point,
  and where the largest one is;
  / stream CI: the largest |stream - exact| over the stream interval's half-width, taken two
  ways: the mean half-width (ci_high - ci_low) / 2, and the half facing the exact value
  (ci_high - dev when exact > stream, dev - ci_low otherwise; <= 1: the exact value is inside
  the stream interval, which is asymmetric);
  / exact CI: the same with the exact interval and the stream value (facing side <= 1: the
  stream value is inside the exact interval), and where the largest (facing side) is;
  EDF stream/exact: min and median of the ratio of the two EDFs.
Usage: bench/stream_vs_exact.py --sigmatau BUILD/cli/sigmatau [--data DIR]
DIR defaults to $SIGMATAU_DATA_DIR, else ../shared/data beside the source tree (CMake's
SIGMATAU_DATA_DIR default); the logs are DIR/imu/... When none is there the script says so and
exits 0 without a table.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys

# log name, path under DIR, sigmatau options that read it (100 Hz, no timestamps; every column)
LOGS = [
    ("ADIS16405", "imu/adis16405_imudata/adis16405_imu1_100Hz.csv.gz", ["--rate", "100"]),
    ("HiPNUC CH104", "imu/hipnuc_ch104/hipnuc_ch104_static_100Hz.csv.gz", ["--rate", "100"]),
    ("XSens MTi-G", "imu/xsens_mtig_cont_imu1/xsens_mtig_gyro_x_100Hz_contaminated.csv.gz",
     ["--rate", "100"]),
]


def run_adev(sigmatau, path, options, mode):
    command = [sigmatau, "adev", path, *options, "--mode", mode, "--format", "json"]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"{' '.join(command)} failed ({done.returncode}): {done.stderr.strip()}")
    return json.loads(done.stdout)


def points_by_key(result):
    out = {}
    for curve in result["results"]:
        for p in curve["points"]:
            out[(curve["channel"], curve["statistic"], p["m"])] = p
    return out


def facing_half_width(point, other_value):
    """Half of point's interval on the side where other_value lies."""
    if other_value >= point["dev"]:
        return point["ci_high"] - point["dev"]
    return point["dev"] - point["ci_low"]


def mean_half_width(point):
    return (point["ci_high"] - point["ci_low"]) / 2


def compare(stream, exact):
    s_points, e_points = points_by_key(stream), points_by_key(exact)
    if s_points.keys() != e_points.keys():
        sys.exit("stream and exact results have different (channel, statistic, m) points")
    rows = []
    for key in sorted(s_points):
        s, e = s_points[key], e_points[key]
        diff = abs(s["dev"] - e["dev"])
        rows.append({
            "where": f"{key[0]} at {s['tau']:g} s",
            "rel": diff / e["dev"],
            "in_stream": diff / facing_half_width(s, e["dev"]),
            "in_stream_mean": diff / mean_half_width(s),
            "in_exact": diff / facing_half_width(e, s["dev"]),
            "in_exact_mean": diff / mean_half_width(e),
            "edf_ratio": s["edf"] / e["edf"],
        })
    return rows


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sigmatau", required=True, help="the sigmatau CLI binary")
    parser.add_argument("--data", default=os.environ.get(
        "SIGMATAU_DATA_DIR", os.path.join(here, "..", "..", "shared", "data")),
        help="reference data directory (holds imu/...)")
    args = parser.parse_args()

    present = [(name, os.path.join(args.data, rel), opts) for name, rel, opts in LOGS
               if os.path.isfile(os.path.join(args.data, rel))]
    missing = [rel for _, rel, _ in LOGS if not os.path.isfile(os.path.join(args.data, rel))]
    for rel in missing:
        print(f"not found: {os.path.join(args.data, rel)}", file=sys.stderr)
    if not present:
        print(f"no IMU log under {os.path.abspath(args.data)}: nothing compared (give --data DIR "
              "or set SIGMATAU_DATA_DIR)")
        return 0

    print("| log | points | rel. dev. max (where) | rel. dev. median | / stream CI: mean; facing "
          "| / exact CI: mean; facing (where) | EDF stream/exact min (where) | EDF ratio median |")
    print("|---|---|---|---|---|---|---|---|")
    for name, path, opts in present:
        exact = run_adev(args.sigmatau, path, opts, "exact")
        stream = run_adev(args.sigmatau, path, opts, "stream")
        rows = compare(stream, exact)
        worst_rel = max(rows, key=lambda r: r["rel"])
        worst_exact = max(rows, key=lambda r: r["in_exact"])
        worst_edf = min(rows, key=lambda r: r["edf_ratio"])
        print(f"| {name} | {len(rows)} | {worst_rel['rel']:.2e} ({worst_rel['where']}) | "
              f"{statistics.median(r['rel'] for r in rows):.2e} | "
              f"{max(r['in_stream_mean'] for r in rows):.2f}; "
              f"{max(r['in_stream'] for r in rows):.2f} | "
              f"{max(r['in_exact_mean'] for r in rows):.2f}; "
              f"{worst_exact['in_exact']:.2f} ({worst_exact['where']}) | "
              f"{worst_edf['edf_ratio']:.3f} ({worst_edf['where']}) | "
              f"{statistics.median(r['edf_ratio'] for r in rows):.3f} |")
        sys.stdout.flush()
    return 0


if __name__ == "__main__":
    sys.exit(main())
