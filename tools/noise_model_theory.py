#!/usr/bin/env python3
"""Independent checks of the closed forms used in lib/src/noise_model.cpp (pure Python, no numpy).

1. Kasdin flicker filter h_0 = 1, h_k = h_{k-1}(k - 1/2)/k: its cumulative sum is (2k+1) h_k.
2. Sampled flicker AVAR per unit innovation variance, (1/2) sum_k c_k^2 with
   c = h * (box_m - delayed box_m)/m, against the direct double sum over the filter's
   autocorrelation (general ACF form, Zhang 2008) for a short truncated filter.
3. AR(1) AVAR (Zhang 2008) rearranged as f/(n^2 (1-phi)^2) and its Taylor coefficients
   c_j(n) = 4(n+1)^j - (2n+1)^j - n 2^j - 3 (c_0..c_2 = 0, c_3 = -(4n^3 + 2n)).
4. Sampled sinusoid: A^2 sin^4(n theta/2) / (n^2 sin^2(theta/2)) against a brute-force phase average.
Run: python3 tools/noise_model_theory.py  (prints the worst relative error of each check)
"""
import math

def kasdin(L):
    h = [1.0]
    for k in range(1, L):
        h.append(h[-1] * (k - 0.5) / k)
    return h

def check_cumsum():
    h = kasdin(2000); s = 0.0; worst = 0.0
    for k, v in enumerate(h):
        s += v
        worst = max(worst, abs(s / ((2 * k + 1) * v) - 1))
    return worst

def flicker_sum(m, L):
    h = kasdin(L)
    H = []; s = 0.0
    for v in h: s += v; H.append(s)
    Hk = lambda k: 0.0 if k < 0 else H[min(k, L - 1)]
    return 0.5 * sum(((Hk(k) - 2 * Hk(k - m) + Hk(k - 2 * m)) / m) ** 2 for k in range(L + 2 * m))

def flicker_acf(m, L):
    h = kasdin(L)
    r = lambda j: sum(h[i] * h[i + j] for i in range(L - j)) if j < L else 0.0
    r0 = r(0)
    acc = m * (r0 - r(m)) + sum(i * (2 * r(m - i) - r(i) - r(2 * m - i)) for i in range(1, m))
    return acc / (m * m)

def check_flicker():
    return max(abs(flicker_sum(m, 64) / flicker_acf(m, 64) - 1) for m in (1, 2, 3, 5, 8, 13))

def ar1_zhang(n, phi):
    q = 1 - phi * phi
    return q * (n - 3 * phi - n * phi ** 2 + 4 * phi ** (n + 1) - phi ** (2 * n + 1)) / (
        n * n * (1 - phi) ** 2 * (1 - phi * phi))

def ar1_series(n, a):
    f = 0.0
    for j in range(3, 60):
        f += (-a) ** j / math.factorial(j) * (4 * (n + 1) ** j - (2 * n + 1) ** j - n * 2 ** j - 3)
    return f / (n * n * (1 - math.exp(-a)) ** 2)

def check_ar1():
    return max(abs(ar1_series(n, a) / ar1_zhang(n, math.exp(-a)) - 1)
               for n in (1, 2, 10, 30) for a in (0.005, 0.01, 0.02))

def check_sinusoid():
    worst = 0.0
    for n in (1, 3, 7):
        for theta in (0.1, 0.7, 2.0):
            acc = 0.0; P = 2000
            for p in range(P):
                ph = 2 * math.pi * p / P
                y = [math.sin(theta * k + ph) for k in range(2 * n)]
                d = sum(y[n:]) / n - sum(y[:n]) / n
                acc += 0.5 * d * d / P
            closed = math.sin(n * theta / 2) ** 4 / (n * n * math.sin(theta / 2) ** 2)
            worst = max(worst, abs(acc / closed - 1))
    return worst

if __name__ == "__main__":
    print("cumulative sum (2k+1) h_k      worst rel err %.2e" % check_cumsum())
    print("flicker c-sum vs ACF form       worst rel err %.2e" % check_flicker())
    print("AR(1) Taylor series vs Zhang    worst rel err %.2e" % check_ar1())
    print("sinusoid closed vs phase avg    worst rel err %.2e" % check_sinusoid())
