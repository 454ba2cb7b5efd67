#!/usr/bin/env python3
"""Simulated profiles with the terms real sensors add (issue 24): a Gauss-Markov sum, a
sinusoid, a filtered white noise. For each seed, `sigmatau simulate` writes 3 gyro axes (2 h by default,
100 Hz, f64) and `sigmatau fit --format json` fits them; per profile the script counts how often
the joint fit selects the true model (the same IEEE terms and the same number of Gauss-Markov
terms and sinusoids) and how often each added term's 95 % interval covers its truth (a fitted GM
matched to the true GM of nearest T_c; the sigma interval lets T_c float), and how often the
T_c and f intervals (JSON tau_c_ci_low_s / tau_c_ci_high_s, frequency_ci_low_hz /
frequency_ci_high_hz; "-" for a build without them) cover theirs.

Usage: bench/fit_added_terms_sim.py --sigmatau BUILD/cli/sigmatau [--seeds 10] [--first-seed 1]
         [--duration 2h] [--profiles gm_sum,sinusoid,filtered_white] [--work DIR]
Writes a markdown table to stdout (bench/results_fit_added_terms.md).
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

DEG_H = math.pi / 180 / 3600  # rad/s per deg/h

# name, model text, true IEEE terms, true GMs [(sigma deg/h, T_c s)], true sinusoid (A deg/h, f Hz)
PROFILES = [
    ("gm_sum", "N=0.15 deg/sqrt(h), GM=20 deg/h @ 10 s, GM=10 deg/h @ 200 s",
     ["N"], [(20, 10), (10, 200)], None),
    ("sinusoid", "N=0.15 deg/sqrt(h), B=3 deg/h, SIN=30 deg/h @ 0.5 Hz",
     ["N", "B"], [], (30, 0.5)),
    # White noise through a first-order filter of 20 ms: an AR(1) of sigma 45 deg/h (N =
    # sigma sqrt(2 T_c) = 9 deg/h/sqrt(Hz) = 0.15 deg/sqrt(h) at long taus).
    ("filtered_white", "GM=45 deg/h @ 0.02 s, B=3 deg/h",
     ["B"], [(45, 0.02)], None),
]



def high(value):
    """An interval's upper end: null in the JSON where the curve does not bound it."""
    return math.inf if value is None else value

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sigmatau", required=True)
    ap.add_argument("--seeds", type=int, default=10)
    ap.add_argument("--work", default=None)
    ap.add_argument("--first-seed", type=int, default=1, help="seeds run from this one (default 1)")
    ap.add_argument("--duration", default="2h", help="length of each simulated log (default 2h)")
    ap.add_argument("--profiles", default=None, help="comma-separated profile names (default all)")
    args = ap.parse_args()
    work = args.work or tempfile.mkdtemp(prefix="sigmatau-added-")
    print("| profile | channels | true model selected | GM sigma covered | SIN amplitude covered | "
          "T_c or f covered | median |T_c or f error| | p >= 0.001 | read-outs reported |")
    print("|---|---|---|---|---|---|---|---|---|")
    wanted = args.profiles.split(",") if args.profiles else [p[0] for p in PROFILES]
    for name, model, ieee, gms, sin in PROFILES:
        if name not in wanted:
            continue
        channels = true_model = p_ok = readings = 0
        gm_cover = gm_total = sin_cover = sin_total = 0
        pos_cover = pos_total = 0
        position_errors = []
        for seed in range(args.first_seed, args.first_seed + args.seeds):
            out = os.path.join(work, f"{name}_{seed}.f64")
            subprocess.run([args.sigmatau, "simulate", "--model", model, "--rate", "100",
                            "--duration", args.duration, "--seed", str(seed), "--format", "f64", "-o", out,
                            "--force"], check=True, capture_output=True)
            fit = subprocess.run([args.sigmatau, "fit", out, "--binary", "f64", "--channels", "3",
                                  "--rate", "100", "--unit", "rad/s", "--format", "json"],
                                 check=True, capture_output=True, text=True)
            for ch in json.loads(fit.stdout)["channels"]:
                channels += 1
                readings += ch.get("reported_from") == "curve_readings"
                j = ch.get("joint", ch)
                p_ok += (j.get("p_value") or 0) >= 1e-3
                fitted_gm = j.get("gauss_markov", [])
                fitted_sin = j.get("sinusoid")
                same = (sorted(j["model_terms"]) == sorted(ieee) and len(fitted_gm) == len(gms)
                        and (fitted_sin is not None) == (sin is not None))
                true_model += same
                for g in fitted_gm:
                    if not gms:
                        continue
                    s_true, t_true = min(gms, key=lambda t: abs(math.log(t[1] / g["tau_c_s"])))
                    gm_total += 1
                    gm_cover += g["ci_low"] <= s_true * DEG_H <= high(g["ci_high"])
                    position_errors.append(abs(g["tau_c_s"] / t_true - 1))
                    if "tau_c_ci_low_s" in g:
                        pos_total += 1
                        pos_cover += g["tau_c_ci_low_s"] <= t_true <= high(g["tau_c_ci_high_s"])
                if fitted_sin and sin:
                    sin_total += 1
                    sin_cover += fitted_sin["ci_low"] <= sin[0] * DEG_H <= fitted_sin["ci_high"]
                    position_errors.append(abs(fitted_sin["frequency_hz"] / sin[1] - 1))
                    if "frequency_ci_low_hz" in fitted_sin:
                        pos_total += 1
                        pos_cover += fitted_sin["frequency_ci_low_hz"] <= sin[1] <= fitted_sin["frequency_ci_high_hz"]
        position_errors.sort()
        median = position_errors[len(position_errors) // 2] if position_errors else float("nan")
        gm_text = f"{gm_cover} of {gm_total}" if gm_total else "-"
        sin_text = f"{sin_cover} of {sin_total}" if sin_total else "-"
        pos_text = f"{pos_cover} of {pos_total}" if pos_total else "-"
        print(f"| {name}: {model} | {channels} | {true_model} ({100 * true_model / channels:.0f} %) | "
              f"{gm_text} | {sin_text} | {pos_text} | {100 * median:.1f} % | {p_ok} | {readings} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
