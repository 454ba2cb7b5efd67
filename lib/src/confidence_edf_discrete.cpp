/// \file confidence_edf_discrete.cpp
/// Exact equivalent degrees of freedom of the Allan-family estimators for discrete-time
/// power-law noise (the noise our simulator and most instruments produce: white FM = independent
/// rate samples, random-walk FM = their cumulative sum, flicker = Kasdin's fractional filter).
///
/// For Gaussian data an estimator A = sum_{i<M} z_i^2 of M squared differences has
/// E[A] = M c(0) and Var[A] = 2 sum_{i,i'} c((i - i') s)^2, c the autocovariance of z, so
///   edf = 2 E[A]^2 / Var[A] = M^2 c(0)^2 / (M c(0)^2 + 2 sum_{j=1}^{M-1} (M - j) c(j s)^2).
/// Greenhall & Riley (PTTI 2003) evaluate the same expression for a continuous-time model in
/// which every phase sample is the average of the phase over one sample interval (F = m for the
/// unmodified variances); at small m that model is not the discrete one (see confidence.hpp).
///
/// Discrete model (N. J. Kasdin, "Discrete simulation of colored noise and stochastic processes
/// and 1/f^alpha power law noise generation", Proc. IEEE 83(5), 1995; J. R. M. Hosking,
/// "Fractional differencing", Biometrika 68(1), 1981): the phase x has the digital spectrum
/// |2 sin(pi f)|^(alpha - 2), so w = (1 - B)^d x is stationary with fractional-differencing
/// parameter delta = 1 - d - alpha/2 < 1/2 (alpha + 2d > 1), and autocovariance (Hosking eq. 3,
/// unit innovation variance; constant factors cancel in the EDF)
///   g(0) = Gamma(1 - 2 delta) / Gamma(1 - delta)^2,  g(h) = g(h - 1) (h - 1 + delta)/(h - delta).
///
/// Glossary:
///   N      number of phase points
///   m      averaging factor
///   d      difference order (2 Allan, 3 Hadamard)
///   k      number of length-m box filters between w and z: d (unmodified), d + 1 (modified),
///          as (1 - B^m)^d x = (1 + B + ... + B^(m-1))^d w and MDEV averages m of those once more
///   L      phase points spanned by one term: d m + 1 (unmodified), (d + 1) m (modified)
///   s      stride between terms: 1 (overlapping), m (non-overlapping ADEV, HDEV)
///   M      number of terms, 1 + floor((N - L)/s)
///   c(h)   autocovariance of z at lag h = (box^k autocorrelation) * g, computed as 2k
///          window sums of width m (prefix sums), O(H + k m) for lags 0..H

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "sigmatau/confidence.hpp"

namespace sigmatau {
namespace {

using real = long double;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Lags beyond this many filter spans (k m + d) are left out of the sum for fractional delta
/// (flicker noises), whose c(h) decays like (k m / h)^2 c(0) or faster: the neglected tail is
/// below (1/kTailSpans)^3 / 3 ~ 1e-7 of the sum. For integer delta c(h) has finite support and
/// nothing is left out.
constexpr std::int64_t kTailSpans = 64;

/// Replaces v[i] by v[i] + ... + v[i + m - 1] for i in [0, size - m + 1); shrinks v by m - 1.
void window_sum(std::vector<real>& v, std::int64_t m) {
  const std::size_t width = static_cast<std::size_t>(m);
  std::vector<real> prefix(v.size() + 1, 0);
  for (std::size_t i = 0; i < v.size(); ++i) prefix[i + 1] = prefix[i] + v[i];
  const std::size_t out = v.size() + 1 - width;
  for (std::size_t i = 0; i < out; ++i) v[i] = prefix[i + width] - prefix[i];
  v.resize(out);
}

}  // namespace

double discrete_edf(Statistic statistic, int alpha, std::int64_t m, std::int64_t n_phase_points) {
  int d = 2;
  bool modified = false, overlapping = true;
  switch (statistic) {
    case Statistic::adev:
      overlapping = false;
      break;
    case Statistic::oadev:
      break;
    case Statistic::mdev:
    case Statistic::tdev:
      modified = true;
      break;
    case Statistic::hdev:
      d = 3;
      overlapping = false;
      break;
    case Statistic::ohdev:
      d = 3;
      break;
    case Statistic::totdev:
      return kNaN;
  }
  if (alpha > 2 || alpha < -4 || alpha + 2 * d <= 1 || m < 1) return kNaN;
  const std::int64_t N = n_phase_points;
  const std::int64_t k = modified ? d + 1 : d;
  const std::int64_t L = modified ? (d + 1) * m : d * m + 1;
  if (N < L) return kNaN;
  const std::int64_t s = overlapping ? 1 : m;
  const std::int64_t M = 1 + (N - L) / s;

  // Lags 0..H of c are needed; c vanishes beyond k (m - 1) - delta for integer delta.
  const real delta = 1 - d - static_cast<real>(alpha) / 2;
  const bool integer_delta = alpha % 2 == 0;
  const std::int64_t support =
      k * (m - 1) + (integer_delta ? static_cast<std::int64_t>(-delta) : kTailSpans * (k * m + d));
  const std::int64_t H = std::min((M - 1) * s, support);

  // g on lags [-k (m - 1), H + k (m - 1)]; each window sum moves the window by m - 1.
  const std::int64_t reach = k * (m - 1);
  std::vector<real> v(static_cast<std::size_t>(H + 2 * reach + 1));
  std::vector<real> g(static_cast<std::size_t>(H + reach + 1));
  g[0] = std::tgamma(1 - 2 * delta) / (std::tgamma(1 - delta) * std::tgamma(1 - delta));
  for (std::size_t h = 1; h < g.size(); ++h) {
    const real hr = static_cast<real>(h);
    g[h] = g[h - 1] * (hr - 1 + delta) / (hr - delta);
  }
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(v.size()); ++i)
    v[static_cast<std::size_t>(i)] = g[static_cast<std::size_t>(std::abs(i - reach))];
  // box^k autocorrelation = k forward and k backward window sums; both are the same window sum
  // up to a shift of the lag origin, and the shifts add up to `reach`, so v[h] = c(h) at the end.
  for (std::int64_t pass = 0; pass < 2 * k; ++pass) window_sum(v, m);

  const real c0 = v[0];
  real var = M * c0 * c0;
  for (std::int64_t j = 1; j < M && j * s <= H; ++j) {
    const real c = v[static_cast<std::size_t>(j * s)];
    var += 2 * static_cast<real>(M - j) * c * c;
  }
  const double edf = static_cast<double>(static_cast<real>(M) * M * c0 * c0 / var);
  return (edf > 0 && std::isfinite(edf)) ? edf : kNaN;
}

}  // namespace sigmatau
