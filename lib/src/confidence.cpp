/// \file confidence.cpp
/// Power-law noise identification and chi-squared confidence intervals for the Allan family.
///
/// Noise identification follows Stable32 (W. J. Riley, "Handbook of Frequency Stability
/// Analysis", NIST SP 1065, 2008, sec. 5.6; Stable32 User Manual, "Noise identification"):
///  - lag-1 autocorrelation (W. J. Riley, C. A. Greenhall, "Power law noise identification using
///    the lag 1 autocorrelation", 18th EFTF, 2004) when at least kMinAcfPoints points remain at
///    the averaging factor;
///  - otherwise the B1 ratio (Barnes 1974; expected values and decision boundaries from D. A.
///    Howe, R. Beard, C. Greenhall, W. Riley, "A total estimator of the Hadamard function used
///    for GPS operations", 32nd PTTI, 2000, Tables 3-4), with the R(n) = MVAR/AVAR ratio
///    (NIST TN 1337 sec. A-6) separating white from flicker PM for the modified statistics.
/// Interval: NIST SP 1065 eq. (45), exact chi-squared quantiles from Boost.Math.
///
/// Glossary:
///   N      number of phase points of the series; M = N - 1 rate samples
///   m      averaging factor
///   z      series at the averaging factor: phase decimated by m (phase input) or rate averaged
///          over non-overlapping blocks of m samples (rate and increment input)
///   r1     lag-1 autocorrelation of z; delta = r1 / (1 + r1)
///   d      number of times z was differenced; p = -round(2 delta) - 2 d
///   mu     exponent of the variance bias, B1(N, mu) (Howe et al. Table 3)
///   K      number of complete m-sample blocks, floor((N - 1)/m)

#include <boost/math/distributions/chi_squared.hpp>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "sigmatau/confidence.hpp"
#include "sigmatau/error.hpp"
#include "noise_identification.hpp"
#include "phase_spill.hpp"

namespace sigmatau {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

using detail::kMinAcfPoints;

/// Differencing stops once delta = r1/(1 + r1) falls below this value (Riley & Greenhall 2004:
/// delta < 0.25 means the differenced series is stationary, alpha + 2d < 1/2 ... 1).
constexpr double kStationaryDelta = 0.25;

/// Fallback noise type when nothing can be estimated (constant series, fewer than 2 blocks):
/// white FM, the type for which the simple EDF rules of thumb were derived.
constexpr int kAssumedAlpha = 0;

/// Greenhall's J_max: while m (d + 1) <= 100 his unmodified-variance model averages the phase
/// over tau0 (F = m), which is where it departs from discrete-time noise (EdfModel::discrete).
constexpr std::int64_t kGreenhallAveragedPhaseSpan = 100;

int difference_order(Statistic statistic) {
  return (statistic == Statistic::hdev || statistic == Statistic::ohdev) ? 3 : 2;
}

/// Lowest alpha for which the statistic converges and Greenhall's EDF exists (alpha + 2d > 1).
int lowest_alpha(Statistic statistic) { return difference_order(statistic) == 3 ? -4 : -2; }

bool is_phase_input(const PhaseSeries& series) { return series.kind() == DataKind::phase; }

/// Lag-1 autocorrelation (Riley & Greenhall 2004 eq. 2) of z[0..n); NaN for a constant series.
double lag1_autocorrelation(const double* z, std::size_t n) {
  long double mean = 0;
  for (std::size_t i = 0; i < n; ++i) mean += z[i];
  mean /= static_cast<long double>(n);
  long double num = 0, den = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const long double a = z[i] - mean;
    den += a * a;
    if (i + 1 < n) num += a * (z[i + 1] - mean);
  }
  if (!(den > 0)) return kNaN;
  return static_cast<double>(num / den);
}

/// Lag-1 ACF method on z[0..n), differenced in place; returns false when the series is constant.
bool identify_by_acf(double* z, std::size_t n, bool phase_input, int d_max, int& alpha) {
  for (int d = 0;; ++d) {
    const double r1 = lag1_autocorrelation(z, n);
    if (std::isnan(r1)) return false;
    const double delta = r1 / (1 + r1);
    if (delta < kStationaryDelta || d >= d_max || n < 3) {
      const int p = -static_cast<int>(std::lround(2 * delta)) - 2 * d;
      alpha = p + (phase_input ? 2 : 0);
      return true;
    }
    for (std::size_t i = 0; i + 1 < n; ++i) z[i] = z[i + 1] - z[i];
    --n;
  }
}

/// Expected B1 ratio (standard variance / Allan variance) for n frequency averages and bias
/// exponent mu (Howe et al. 2000, Table 3).
double expected_b1(double n, int mu) {
  switch (mu) {
    case 2: return n * (n + 1) / 6;
    case 1: return n / 2;
    case 0: return n * std::log(n) / (2 * (n - 1) * std::numbers::ln2);
    case -1: return 1;
    default: return (n * n - 1) / (1.5 * n * (n - 1));  // mu = -2, white or flicker PM
  }
}

/// mu from a measured B1 ratio: tested downwards from mu = 2 against the boundaries between
/// neighbouring types (arithmetic mean between mu = 2 and 1, geometric mean below; Howe et al.
/// 2000, Table 4).
int mu_from_b1(double b1, double n) {
  for (int mu = 2; mu >= -1; --mu) {
    const double hi = expected_b1(n, mu), lo = expected_b1(n, mu - 1);
    const double boundary = mu == 2 ? 0.5 * (hi + lo) : std::sqrt(hi * lo);
    if (b1 > boundary) return mu;
  }
  return -2;
}

/// Expected R(n) = MVAR/AVAR (NIST TN 1337 Table A-6 / IEEE 1139): 1/m for white PM,
/// 3.37/(1.04 + 3 ln(pi m)) for flicker PM with bandwidth f_h = 1/(2 tau0).
double expected_rn(std::int64_t m, int alpha) {
  const double md = static_cast<double>(m);
  return alpha == 2 ? 1 / md : 3.37 / (1.04 + 3 * std::log(std::numbers::pi * md));
}

/// B1 (and R(n)) identification; returns false when the ratio is undefined.
bool identify_by_b1(const PhaseSeries& series, Statistic statistic, std::int64_t m, int& alpha) {
  const std::int64_t N = series.size();
  const std::int64_t K = (N - 1) / m;
  if (K < 2) return false;
  // Non-overlapping block means (in input units per sample; the ratios are unit-free).
  std::vector<double> y(static_cast<std::size_t>(K));
  const double inv_m = 1.0 / static_cast<double>(m);
  long double mean = 0;
  for (std::int64_t k = 0; k < K; ++k) {
    y[static_cast<std::size_t>(k)] = series.window_sum(k * m, m) * inv_m;
    mean += y[static_cast<std::size_t>(k)];
  }
  mean /= static_cast<long double>(K);
  long double svar = 0, avar = 0;
  for (std::size_t k = 0; k < y.size(); ++k) {
    svar += (y[k] - mean) * (y[k] - mean);
    if (k + 1 < y.size()) avar += (y[k + 1] - y[k]) * (y[k + 1] - y[k]);
  }
  svar /= static_cast<long double>(K - 1);
  avar /= 2 * static_cast<long double>(K - 1);
  if (!(avar > 0)) return false;
  // Stable32 evaluates the expected B1 with the statistic's own term count (its "#").
  const double n = static_cast<double>(term_count(statistic, m, N));
  if (!(n > 1)) return false;
  const int mu = mu_from_b1(static_cast<double>(svar / avar), n);
  if (mu > -2) {
    alpha = -mu - 1;
    return true;
  }
  // White or flicker PM. The modified statistics separate them with R(n) = MVAR/AVAR.
  alpha = 1;
  if ((statistic == Statistic::mdev || statistic == Statistic::tdev) && N >= 3 * m + 1) {
    // MVAR in per-sample units: 1/(2 m^4 (N-3m+1)) sum_j [sum_{i=j}^{j+m-1} (x_{i+2m} - 2x_{i+m}
    // + x_i)]^2, the inner sum updated in O(1) per j (SP 1065 eq. 14).
    long double inner = 0;
    for (std::int64_t i = 0; i < m; ++i)
      inner += series.window_sum(i + m, m) - series.window_sum(i, m);
    long double sum = inner * inner;
    const std::int64_t terms = N - 3 * m + 1;
    for (std::int64_t j = 0; j + 1 < terms; ++j) {
      inner += series.window_sum(j + 2 * m, m) - 2 * series.window_sum(j + m, m) +
               series.window_sum(j, m);
      sum += inner * inner;
    }
    const long double md = static_cast<long double>(m);
    const long double mvar = sum / (2 * md * md * md * md * static_cast<long double>(terms));
    const double rn = static_cast<double>(mvar / avar);
    const double boundary = std::sqrt(expected_rn(m, 1) * expected_rn(m, 2));
    alpha = rn > boundary ? 1 : 2;
  }
  return true;
}

/// TOTDEV EDF as Stable32 computes it: edf = b N/m - c for white, flicker and random-walk FM with
/// the three-digit coefficients of D. A. Howe's total-variance work (b = 1.500, 1.168, 0.927;
/// c = 0, 0.222, 0.358), which NIST SP 1065 Table 7 rounds to two digits (1.17, 0.22; 0.93,
/// 0.36): the EDF implied by Stable32's printed bounds agrees with the three-digit values within
/// 8e-4 and is 1.3-3.4e-3 below SP 1065's (tests/test_confidence_reference.cpp). For white and
/// flicker PM (not covered by Table 7) the simple
/// overlapping-ADEV formulas of SP 1065 Table 5. The Table 5 choice for alpha > 0 was identified
/// against Stable32's TOTDEV bounds (ocxo, Keysight and GPS records); Greenhall's OADEV EDF
/// differs from them by up to 1.6e-3 in the bound at flicker PM.
double totdev_edf(int alpha, std::int64_t m, std::int64_t n_phase_points) {
  const double N = static_cast<double>(n_phase_points), md = static_cast<double>(m);
  double edf = kNaN;
  switch (alpha) {
    case 2: edf = (N + 1) * (N - 2 * md) / (2 * (N - md)); break;
    case 1:
      edf = std::exp(std::sqrt(std::log((N - 1) / (2 * md)) * std::log((2 * md + 1) * (N - 1) / 4)));
      break;
    case 0: edf = 1.50 * N / md; break;
    case -1: edf = 1.168 * N / md - 0.222; break;
    case -2: edf = 0.927 * N / md - 0.358; break;
    default: break;
  }
  return edf > 0 ? edf : kNaN;
}

}  // namespace

NoiseIdentification identify_noise(const PhaseSeries& series, Statistic statistic,
                                   std::int64_t m) {
  if (!(m >= 1) || m >= series.size())
    throw Error("identify_noise: averaging factor m = " + std::to_string(m) +
                " outside 1.." + std::to_string(series.size() - 1));
  const std::int64_t points = detail::averaged_series_points(series, m);
  // Uninitialised: every value is written by fill_averaged_series before it is read.
  std::unique_ptr<double[]> z;
  if (points >= kMinAcfPoints) z.reset(new double[static_cast<std::size_t>(points)]);
  return detail::identify_noise_with(series, statistic, m, z.get());
}

namespace detail {

NoiseIdentification identify_noise_with(const PhaseSeries& series, Statistic statistic,
                                        std::int64_t m, double* scratch) {
  const std::int64_t points = averaged_series_points(series, m);
  if (points >= kMinAcfPoints) {
    fill_averaged_series(series, m, scratch);
    return identify_noise_by_acf(scratch, static_cast<std::size_t>(points),
                                 is_phase_input(series), statistic);
  }
  NoiseIdentification result;
  result.method = NoiseIdentification::Method::b1_ratio;
  int alpha = kAssumedAlpha;
  if (!identify_by_b1(series, statistic, m, alpha)) {
    alpha = kAssumedAlpha;
    result.method = NoiseIdentification::Method::assumed;
  }
  result.alpha = std::clamp(alpha, lowest_alpha(statistic), 2);
  return result;
}

std::int64_t averaged_series_points(const PhaseSeries& series, std::int64_t m) {
  const std::int64_t N = series.size();
  return is_phase_input(series) ? (N - 1) / m + 1 : (N - 1) / m;
}

void fill_averaged_series(const PhaseSeries& series, std::int64_t m, double* out) {
  const std::int64_t N = series.size();
  // A spilled phase: reading one point in m maps the pages around each point, so the resident
  // budget is checked synchronously about every 8 MiB of phase spanned (phase_spill.hpp).
  const std::int64_t check_every =
      series.spilled() ? std::max<std::int64_t>(1, (std::int64_t{512} << 10) / m) : N + 1;
  if (is_phase_input(series)) {
    for (std::int64_t k = 0, i = 0; k < N; k += m, ++i) {
      if (i % check_every == 0 && series.spilled()) enforce_spill_budget();
      out[i] = series.x(k);
    }
  } else {
    const std::int64_t K = (N - 1) / m;
    const double inv_m = 1.0 / static_cast<double>(m);
    for (std::int64_t k = 0; k < K; ++k) {
      if (k % check_every == 0 && series.spilled()) enforce_spill_budget();
      out[k] = series.window_sum(k * m, m) * inv_m;
    }
  }
}

NoiseIdentification acf_identification(int alpha, Statistic statistic) {
  NoiseIdentification result;
  result.method = NoiseIdentification::Method::lag1_acf;
  result.alpha = std::clamp(alpha, lowest_alpha(statistic), 2);
  return result;
}

NoiseIdentification identify_noise_by_acf(double* z, std::size_t n, bool phase_input,
                                          Statistic statistic) {
  NoiseIdentification result;
  result.method = NoiseIdentification::Method::lag1_acf;
  int alpha = kAssumedAlpha;
  if (!identify_by_acf(z, n, phase_input, difference_order(statistic), alpha)) {
    alpha = kAssumedAlpha;
    result.method = NoiseIdentification::Method::assumed;
  }
  result.alpha = std::clamp(alpha, lowest_alpha(statistic), 2);
  return result;
}

}  // namespace detail

double equivalent_dof(Statistic statistic, int alpha, std::int64_t m,
                      std::int64_t n_phase_points) {
  switch (statistic) {
    case Statistic::adev: return greenhall_edf(alpha, 2, m, m, 1, n_phase_points);
    case Statistic::oadev: return greenhall_edf(alpha, 2, m, m, m, n_phase_points);
    case Statistic::mdev:
    case Statistic::tdev: return greenhall_edf(alpha, 2, m, 1, m, n_phase_points);
    case Statistic::hdev: return greenhall_edf(alpha, 3, m, m, 1, n_phase_points);
    case Statistic::ohdev: return greenhall_edf(alpha, 3, m, m, m, n_phase_points);
    case Statistic::totdev: return totdev_edf(alpha, m, n_phase_points);
  }
  return kNaN;
}

EdfModel default_edf_model(DataKind kind, const Dimension& unit) {
  // Increments and phase are per-sample amounts: rad and m/s where rates are rad/s and m/s^2.
  const bool amount = kind != DataKind::rate;
  const bool gyro = unit == (amount ? dim::angle : dim::angular_rate);
  const bool accel = unit == (amount ? dim::velocity : dim::acceleration);
  return gyro || accel || unit.counts2 != 0 ? EdfModel::discrete : EdfModel::greenhall;
}

double equivalent_dof(Statistic statistic, int alpha, std::int64_t m,
                      std::int64_t n_phase_points, EdfModel model) {
  if (model == EdfModel::discrete && statistic != Statistic::totdev &&
      m * (difference_order(statistic) + 1) <= kGreenhallAveragedPhaseSpan)
    return discrete_edf(statistic, alpha, m, n_phase_points);
  return equivalent_dof(statistic, alpha, m, n_phase_points);
}

Interval chi_squared_interval(double dev, double edf, double confidence) {
  if (!(confidence > 0 && confidence < 1))
    throw Error("confidence must be in (0, 1), got " + std::to_string(confidence));
  if (!(dev >= 0) || !std::isfinite(dev))
    throw Error("deviation must be finite and >= 0, got " + std::to_string(dev));
  if (!(edf > 0) || !std::isfinite(edf)) return {kNaN, kNaN};
  const boost::math::chi_squared_distribution<double> chi2(edf);
  const double tail = (1 - confidence) / 2;
  const double chi2_upper = boost::math::quantile(chi2, 1 - tail);
  const double chi2_lower = boost::math::quantile(chi2, tail);
  return {dev * std::sqrt(edf / chi2_upper), dev * std::sqrt(edf / chi2_lower)};
}

ConfidencePoint confidence_for(const PhaseSeries& series, Statistic statistic,
                               const DeviationPoint& point, double confidence) {
  ConfidencePoint result;
  result.noise = identify_noise(series, statistic, point.m);
  result.edf = equivalent_dof(statistic, result.noise.alpha, point.m, series.size());
  result.interval = chi_squared_interval(point.dev, result.edf, confidence);
  return result;
}

}  // namespace sigmatau
