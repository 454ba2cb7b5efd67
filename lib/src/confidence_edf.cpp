/// \file confidence_edf.cpp
/// Equivalent degrees of freedom (EDF) of the Allan-family variances.
///
/// Greenhall's algorithm: C. A. Greenhall, W. J. Riley, "Uncertainty of stability variances based
/// on finite differences", Proc. 35th PTTI Meeting, 2003 (section 3: eqs. 7-10 for the kernels
/// and the basic sum, section 3.6 for the four cases, Tables 1-3 for the large-J asymptotics).
/// Table values transcribed from the paper as quoted in allantools `ci.py` and allantoolkit
/// `tables.yml` (both agree); the alpha = +2 rows of Table 2 are the closed forms
/// a0 = C(4d,2d)/C(2d,d)^2, a1 = d/2 given in the paper.
/// TOTDEV (confidence.cpp): edf = b N/m - c, NIST SP 1065 (Riley 2008) Table 7 with Howe's
/// three-digit b and c.
///
/// Glossary (paper's symbols):
///   alpha  exponent of the fractional-frequency PSD S_y(f) ~ f^alpha
///   d      order of the phase difference (1 first difference, 2 Allan, 3 Hadamard)
///   m      averaging factor, tau = m tau0
///   F      filter factor: m for unmodified variances, 1 for modified ones
///   S      stride factor: 1 for non-overlapping estimators, m for overlapping ones
///   N      number of phase points
///   L      length of the filter applied to the phase, L = m/F + m d
///   M      number of summands of the estimator, M = 1 + floor(S (N - L) / m)
///   J      number of lags in the basic sum, J = min(M, (d+1) S)
///   r      M / S
///   s_w, s_x, s_z  generalised autocovariances of the continuous-time power-law process w, of
///          the (averaged) phase x and of the d-th difference z (paper eqs. 7, 8, 9)

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "sigmatau/confidence.hpp"

namespace sigmatau {
namespace {

using real = long double;  // the kernels difference nearly equal values (see kernel_x)

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// J_max of the paper: beyond this many lags the basic sum is replaced by the asymptotic tables.
constexpr std::int64_t kJmax = 100;

/// (a0, a1) coefficient pair of Tables 1-3 (b0, b1 for Table 3). NaN marks the entries the
/// paper leaves empty (alpha + 2d <= 1, which greenhall_edf rejects before any lookup).
struct Coefficients {
  double a0;
  double a1;
};

/// Table 1 of the paper (modified variances, F = 1): rows alpha = +2 ... -4, columns d = 1..3.
/// alpha = +2 row in closed form: d=1 (2/3, 1/3), d=2 (7/9, 1/2), d=3 (22/25, 2/3).
constexpr Coefficients kTable1[7][3] = {
    {{2.0 / 3.0, 1.0 / 3.0}, {7.0 / 9.0, 1.0 / 2.0}, {22.0 / 25.0, 2.0 / 3.0}},  // alpha = +2
    {{0.840, 0.345}, {0.997, 0.616}, {1.141, 0.843}},                              // alpha = +1
    {{1.079, 0.368}, {1.033, 0.607}, {1.184, 0.848}},                              // alpha = 0
    {{kNaN, kNaN}, {1.048, 0.534}, {1.180, 0.816}},                                // alpha = -1
    {{kNaN, kNaN}, {1.302, 0.535}, {1.175, 0.777}},                                // alpha = -2
    {{kNaN, kNaN}, {kNaN, kNaN}, {1.194, 0.703}},                                  // alpha = -3
    {{kNaN, kNaN}, {kNaN, kNaN}, {1.489, 0.702}},                                  // alpha = -4
};

/// Table 2 of the paper (unmodified variances, F = m), same layout. alpha = +2: closed forms
/// a0 = C(4d,2d)/C(2d,d)^2 (3/2, 35/18, 231/100), a1 = d/2; alpha = 0: (2/3, 1/6), (2/3, 1/3),
/// (7/9, 1/2).
constexpr Coefficients kTable2[7][3] = {
    {{3.0 / 2.0, 1.0 / 2.0}, {35.0 / 18.0, 1.0}, {231.0 / 100.0, 3.0 / 2.0}},  // alpha = +2
    {{78.6, 25.2}, {790.0, 410.0}, {9950.0, 6520.0}},                          // alpha = +1
    {{2.0 / 3.0, 1.0 / 6.0}, {2.0 / 3.0, 1.0 / 3.0}, {7.0 / 9.0, 1.0 / 2.0}},  // alpha = 0
    {{kNaN, kNaN}, {0.852, 0.375}, {0.997, 0.617}},                            // alpha = -1
    {{kNaN, kNaN}, {1.079, 0.368}, {1.033, 0.607}},                            // alpha = -2
    {{kNaN, kNaN}, {kNaN, kNaN}, {1.053, 0.553}},                              // alpha = -3
    {{kNaN, kNaN}, {kNaN, kNaN}, {1.302, 0.535}},                              // alpha = -4
};

/// Table 3 of the paper (flicker PM, unmodified): s_z(0) ~ b0 + b1 ln m for d = 1..3.
constexpr Coefficients kTable3[3] = {{6.0, 4.0}, {15.23, 12.0}, {47.8, 40.0}};

const Coefficients& table1(int alpha, int d) { return kTable1[2 - alpha][d - 1]; }
const Coefficients& table2(int alpha, int d) { return kTable2[2 - alpha][d - 1]; }

/// Binomial coefficient C(n, k) for the small n used here (n <= 12).
real binomial(int n, int k) {
  if (k < 0 || k > n) return 0;
  real c = 1;
  for (int i = 1; i <= k; ++i) c = c * static_cast<real>(n - k + i) / static_cast<real>(i);
  return c;
}

/// s_w(t): generalised autocovariance of the continuous power-law process (paper eq. 7), up to
/// a constant factor (only ratios of s_z values enter the EDF).
real kernel_w(real t, int alpha) {
  const real a = std::fabs(t);
  const real log_a = a > 0 ? std::log(a) : 0;  // t^(2k) ln|t| -> 0 at t = 0
  switch (alpha) {
    case 2: return -a;
    case 1: return a * a * log_a;
    case 0: return a * a * a;
    case -1: return -a * a * a * a * log_a;
    case -2: return -a * a * a * a * a;
    case -3: return a * a * a * a * a * a * log_a;
    case -4: return a * a * a * a * a * a * a;
    default: return std::numeric_limits<real>::quiet_NaN();
  }
}

/// s_x(t) for filter factor F (paper eq. 8): F^2 [2 s_w(t) - s_w(t - 1/F) - s_w(t + 1/F)];
/// F = infinity (the limit used for large m with alpha <= 0) gives s_w with alpha + 2.
/// The second difference with step 1/F loses about 2 log10(F) digits, hence long double.
real kernel_x(real t, real F, int alpha) {
  if (std::isinf(F)) return kernel_w(t, alpha + 2);
  const real h = 1 / F;
  return F * F * (2 * kernel_w(t, alpha) - kernel_w(t - h, alpha) - kernel_w(t + h, alpha));
}

/// s_z(t): the d-th binomial difference of s_x (paper eq. 9),
/// sum_{k=-d}^{d} (-1)^k C(2d, d+k) s_x(t + k).
real kernel_z(real t, real F, int alpha, int d) {
  real sum = 0;
  for (int k = -d; k <= d; ++k) {
    const real sign = (k % 2 == 0) ? 1 : -1;
    sum += sign * binomial(2 * d, d + k) * kernel_x(t + k, F, alpha);
  }
  return sum;
}

/// BasicSum(J, M, S, F) of the paper (eq. 10):
/// s_z(0)^2 + (1 - J/M) s_z(J/S)^2 + 2 sum_{j=1}^{J-1} (1 - j/M) s_z(j/S)^2.
real basic_sum(std::int64_t J, real M, real S, real F, int alpha, int d) {
  const real z0 = kernel_z(0, F, alpha, d);
  const real zJ = kernel_z(static_cast<real>(J) / S, F, alpha, d);
  real sum = z0 * z0 + (1 - static_cast<real>(J) / M) * zJ * zJ;
  for (std::int64_t j = 1; j < J; ++j) {
    const real zj = kernel_z(static_cast<real>(j) / S, F, alpha, d);
    sum += 2 * (1 - static_cast<real>(j) / M) * zj * zj;
  }
  return sum;
}

/// 1/edf from the basic sum: BasicSum / (M s_z(0)^2) (paper eq. 10 with eq. 11).
real inverse_edf_basic(std::int64_t J, real M, real S, real F, int alpha, int d) {
  const real z0 = kernel_z(0, F, alpha, d);
  return basic_sum(J, M, S, F, alpha, d) / (M * z0 * z0);
}

}  // namespace

double greenhall_edf(int alpha, int d, std::int64_t m, std::int64_t F, std::int64_t S,
                     std::int64_t n_phase_points) {
  const std::int64_t N = n_phase_points;
  // Domain of the algorithm: d in 1..3, alpha in -4..2 with alpha + 2d > 1 (the variance
  // converges), F and S each 1 or m, at least one summand.
  if (d < 1 || d > 3 || alpha > 2 || alpha < -4 || alpha + 2 * d <= 1) return kNaN;
  if (m < 1 || (F != 1 && F != m) || (S != 1 && S != m)) return kNaN;
  const std::int64_t L = m / F + m * d;
  if (N < L) return kNaN;
  const std::int64_t M = 1 + (S * (N - L)) / m;
  const std::int64_t J = std::min(M, (d + 1) * S);
  const real Mr = static_cast<real>(M);
  const real Sr = static_cast<real>(S);
  const real r = Mr / Sr;
  const real inf = std::numeric_limits<real>::infinity();
  real inv_edf = 0;

  if (F == 1) {
    // Case 1: modified variances (also unmodified ones at m = 1), all alpha.
    if (J <= kJmax) {
      inv_edf = inverse_edf_basic(J, Mr, Sr, 1, alpha, d);
    } else if (r >= d + 1) {
      const Coefficients& c = table1(alpha, d);
      inv_edf = (c.a0 - c.a1 / r) / r;
    } else {
      inv_edf = inverse_edf_basic(kJmax, kJmax, kJmax / r, 1, alpha, d);
    }
  } else if (alpha <= 0) {
    // Case 2: unmodified variances, white FM and redder.
    if (J <= kJmax) {
      const real Fp = (m * (d + 1) <= kJmax) ? static_cast<real>(m) : inf;
      inv_edf = inverse_edf_basic(J, Mr, Sr, Fp, alpha, d);
    } else if (r >= d + 1) {
      const Coefficients& c = table2(alpha, d);
      inv_edf = (c.a0 - c.a1 / r) / r;
    } else {
      inv_edf = inverse_edf_basic(kJmax, kJmax, kJmax / r, inf, alpha, d);
    }
  } else if (alpha == 1) {
    // Case 3: unmodified variances, flicker PM (s_z(0) grows like ln m: Table 3).
    const Coefficients& b = kTable3[d - 1];
    const real bz = b.a0 + b.a1 * std::log(static_cast<real>(m));
    if (J <= kJmax) {
      inv_edf = inverse_edf_basic(J, Mr, Sr, static_cast<real>(m), alpha, d);
    } else if (r >= d + 1) {
      const Coefficients& c = table2(alpha, d);
      inv_edf = (c.a0 - c.a1 / r) / (r * bz * bz);
    } else {
      const real mp = kJmax / r;
      inv_edf = basic_sum(kJmax, kJmax, mp, mp, alpha, d) / (kJmax * bz * bz);
    }
  } else {
    // Case 4: unmodified variances, white PM: closed form.
    const std::int64_t K = static_cast<std::int64_t>(std::ceil(r));
    if (K <= d) {
      real sum = 0;
      for (std::int64_t k = 1; k < K; ++k) {
        const real c = binomial(2 * d, d - static_cast<int>(k));
        sum += (1 - static_cast<real>(k) / r) * c * c;
      }
      const real c0 = binomial(2 * d, d);
      inv_edf = (1 + 2 * sum / (c0 * c0)) / Mr;
    } else {
      const Coefficients& c = table2(alpha, d);
      inv_edf = (c.a0 - c.a1 / r) / Mr;
    }
  }
  const double edf = static_cast<double>(1 / inv_edf);
  return (edf > 0 && std::isfinite(edf)) ? edf : kNaN;
}

}  // namespace sigmatau
