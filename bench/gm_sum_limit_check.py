#!/usr/bin/env python3
"""Monte-Carlo check of bench_gm_sum_limit's Gaussian information limit (issue 24).

bench_gm_sum_limit (GM_SUM_LIMIT_DUMP=FILE) writes, for the gm_sum profile on a 2 h log, the
octave factors, the truth's exact AVAR mu1, the nearest N + one-GM model's mu0 and the truth's
OAVAR covariance Sigma. Taking the estimates as Gaussian, the best test between the two curves
with every parameter known is linear: T = (mu1 - mu0)^T Sigma^-1 (v - (mu0 + mu1) / 2), the truth
chosen when T > 0, right with probability Phi(d / 2) under either. This script simulates both
curves with `sigmatau simulate` (3 axes per seed), measures their OADEV with `sigmatau adev`,
applies T and counts how often each is chosen right: if the counts match Phi(d / 2), the limit
computed from the Gaussian approximation holds for the real estimates (skewed at the longest
taus, where few averages remain).

Usage: bench/gm_sum_limit_check.py --sigmatau BUILD/cli/sigmatau --limit FILE [--seeds 40]
Writes a markdown line to stdout.
"""
import argparse
import json
import math
import os
import subprocess
import tempfile

import numpy as np

RAD_S_TO_DEG_H = 180 / math.pi * 3600
RAD_SQRT_S_TO_DEG_SQRT_H = 180 / math.pi * 60


def curves(sigmatau, model, seed, samples, work):
    out = os.path.join(work, f"s{seed}.f64")
    subprocess.run([sigmatau, "simulate", "--model", model, "--rate", "100", "--duration",
                    f"{samples / 100:.0f} s", "--seed", str(seed), "--format", "f64", "-o", out,
                    "--force", "--sidecar", "none"], check=True, capture_output=True)
    adev = subprocess.run([sigmatau, "adev", out, "--binary", "f64", "--channels", "3", "--rate",
                           "100", "--unit", "rad/s", "--stat", "oadev", "--taus", "octave",
                           "--format", "json"], check=True, capture_output=True, text=True)
    os.remove(out)
    result = []
    for ch in json.loads(adev.stdout)["results"]:
        points = ch["points"]
        result.append(({p["m"]: p["dev"] ** 2 for p in points}))
    return result


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sigmatau", required=True)
    ap.add_argument("--limit", required=True, help="bench_gm_sum_limit's GM_SUM_LIMIT_DUMP file")
    ap.add_argument("--seeds", type=int, default=40)
    args = ap.parse_args()
    lim = json.load(open(args.limit))
    m = [int(x) for x in lim["m"]]
    mu0, mu1 = np.array(lim["mu0"]), np.array(lim["mu1"])
    sigma = np.array(lim["sigma"])
    w = np.linalg.solve(sigma, mu1 - mu0)
    d = math.sqrt(float((mu1 - mu0) @ w))
    mid = (mu0 + mu1) / 2
    truth = "N=0.15 deg/sqrt(h), GM=20 deg/h @ 10 s, GM=10 deg/h @ 200 s"
    alt = (f"N={lim['alt_white'] * RAD_SQRT_S_TO_DEG_SQRT_H:.6f} deg/sqrt(h), "
           f"GM={lim['alt_gm_sigma'] * RAD_S_TO_DEG_H:.6f} deg/h @ {lim['alt_gm_tau_c_s']:.6f} s")
    right = {truth: 0, alt: 0}
    stats = {truth: [], alt: []}
    total = 0
    with tempfile.TemporaryDirectory(prefix="sigmatau-limit-") as work:
        for seed in range(1, args.seeds + 1):
            for model in (truth, alt):
                for avar in curves(args.sigmatau, model, seed, lim["n_samples"], work):
                    v = np.array([avar[k] for k in m])
                    t = float(w @ (v - mid))
                    right[model] += (t > 0) == (model == truth)
                    stats[model].append(t)
            total += 3
    t95 = float(np.quantile(stats[alt], 0.95))
    phi = 0.5 * (1 + math.erf(d / 2 / math.sqrt(2)))
    print(f"| d = {d:.3f}, Phi(d/2) = {100 * phi:.1f} % | truth chosen on its own curves: "
          f"{right[truth]} of {total} ({100 * right[truth] / total:.1f} %) | the one-GM model "
          f"({alt}) chosen on its own: {right[alt]} of {total} ({100 * right[alt] / total:.1f} %) | "
          f"truth chosen with the threshold at the one-GM curves' 95th percentile of T (5 % false "
          f"additions): {100 * np.mean(np.array(stats[truth]) > t95):.1f} % |")


if __name__ == "__main__":
    main()
