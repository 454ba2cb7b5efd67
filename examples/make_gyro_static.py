#!/usr/bin/env python3
"""Writes gyro_static_100Hz.csv.gz: a synthetic 3-axis static gyro log for the quick-start.

100 Hz, 20 min, columns t [s], gx, gy, gz [deg/s]. Per axis: a turn-on bias, white rate noise
with density N = 0.3 deg/sqrt(h) = 0.005 deg/s/sqrt(Hz) (per-sample sigma N*sqrt(fs)), and a rate
random walk K = 30 deg/h/sqrt(h). Values are rounded to 1e-6 deg/s. Seeded: the file is
reproducible with Python's standard library alone (no numpy).
"""
import gzip
import io
import math
import random

RATE_HZ = 100.0
DURATION_S = 1200.0
N_DEG_PER_S_RT_HZ = 0.3 / 60.0            # 0.3 deg/sqrt(h)
K_DEG_PER_S_PER_RT_S = 30.0 / 3600.0 / 60.0  # 30 deg/h/sqrt(h) = deg/s per sqrt(s)
BIAS_DEG_PER_S = (0.12, -0.35, 0.07)

rng = random.Random(20261122)
tau0 = 1.0 / RATE_HZ
sigma_white = N_DEG_PER_S_RT_HZ * math.sqrt(RATE_HZ)
sigma_walk = K_DEG_PER_S_PER_RT_S * math.sqrt(tau0)
walk = [0.0, 0.0, 0.0]
with open("gyro_static_100Hz.csv.gz", "wb") as raw, gzip.GzipFile(fileobj=raw, mode="wb", compresslevel=9, mtime=0) as gz, io.TextIOWrapper(gz) as f:
    f.write("# synthetic static gyro, 100 Hz; made by examples/make_gyro_static.py\n")
    f.write("# N = 0.3 deg/sqrt(h), K = 30 deg/h/sqrt(h) per axis; values in deg/s\n")
    f.write("t,gx,gy,gz\n")
    for k in range(int(DURATION_S * RATE_HZ)):
        values = []
        for axis in range(3):
            walk[axis] += rng.gauss(0.0, sigma_walk)
            values.append(BIAS_DEG_PER_S[axis] + walk[axis] + rng.gauss(0.0, sigma_white))
        f.write("%.2f,%.6f,%.6f,%.6f\n" % (k * tau0, *values))
