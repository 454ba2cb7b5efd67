// The exact discrete-time Allan variance of a first-order Gauss-Markov rate (issue 24: the
// term real sensors need), derived here and checked against sampled_avar and against the
// library's own OADEV of a simulated AR(1).
//
// Derivation. The rate y_k is AR(1): y_k = phi y_{k-1} + w_k, phi = exp(-tau0 / T_c),
// stationary variance s^2 (innovations s^2 (1 - phi^2)), autocovariance r(l) = s^2 phi^|l|.
// With Y_k the mean of m consecutive samples, AVAR(m) = E[(Y_{k+1} - Y_k)^2] / 2
// = Var(Y) - Cov(Y_k, Y_{k+1}), where
//   Var(Y)            = (s^2/m^2) [m + 2 sum_{l=1}^{m-1} (m - l) phi^l]
//                     = (s^2/m^2) [m (1 + phi)/(1 - phi) - 2 phi (1 - phi^m)/(1 - phi)^2],
//   Cov(Y_k, Y_{k+1}) = (s^2/m^2) sum_{i=0}^{m-1} sum_{j=m}^{2m-1} phi^(j-i)
//                     = (s^2/m^2) phi (1 - phi^m)^2 / (1 - phi)^2,
// so AVAR(m) = s^2 [m (1 - phi^2) - 3 phi + 4 phi^(m+1) - phi^(2m+1)] / [m^2 (1 - phi)^2],
// Zhang (2008)'s form in noise_model.hpp with q = s^2 (1 - phi^2).
#include <doctest/doctest.h>

#include <cmath>
#include <random>
#include <vector>

#include "sigmatau/allan.hpp"
#include "sigmatau/fit.hpp"
#include "sigmatau/noise_model.hpp"
#include "sigmatau/phase_series.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

double derived_avar(double s, double phi, std::int64_t m) {
  const double n = static_cast<double>(m);
  return s * s * (n * (1 - phi * phi) - 3 * phi + 4 * std::pow(phi, n + 1) - std::pow(phi, 2 * n + 1)) /
         (n * n * (1 - phi) * (1 - phi));
}

}  // namespace

TEST_CASE("Gauss-Markov AVAR: the derivation above is sampled_avar's closed form") {
  for (const double tau_c : {0.02, 0.5, 30.0}) {
    NoiseTerms t;
    t.gauss_markov = {GaussMarkov{2e-3, tau_c}};
    const double phi = std::exp(-0.01 / tau_c);
    for (const std::int64_t m : {1, 2, 7, 64, 1000, 100000}) {
      INFO("tau_c = " << tau_c << " m = " << m);
      // Two spellings of one closed form. The one above, in plain powers, cancels its leading
      // terms down to ~(m (1 - phi))^2 of them when phi is near 1 (T_c = 30 s: 1 - phi = 3.3e-4;
      // at m = 1 about 1e-7), so it keeps only ~1e-16 / 1e-7 relative accuracy (2.3e-6 measured
      // at m = 1); the library's form is written with expm1 to avoid that. 1e-5 for that case,
      // 1e-9 elsewhere, where the cancellation is milder than (1e-2)^2.
      const double cancellation = static_cast<double>(m) * (1 - phi) < 0.01 ? 1e-5 : 1e-9;
      SIGMATAU_CHECK_REL(sampled_avar(t, NoiseTerm::gauss_markov, m, Sampling{0.01, 0, false}),
                         derived_avar(2e-3, phi, m), cancellation);
    }
  }
}

TEST_CASE("Gauss-Markov AVAR: the OADEV of a simulated AR(1) agrees within its own scatter") {
  // 2^20 samples at 100 Hz of an AR(1) with T_c = 0.5 s (phi = 0.980), drawn here (not by the
  // simulator). Tolerance: each OAVAR estimate's standard deviation from the exact covariance
  // of the estimates for this process (oavar_covariance), 4.5 of them: six averaging factors,
  // so a right formula fails with probability ~4e-5 (normal tails; the estimates at these m
  // have EDFs of ~1e3 and more, where the chi-squared is near normal). A formula off by the
  // factor (1 + phi)/(1 - phi) or by a sample's shift in the covariance term misses by far more.
  const double tau0 = 0.01, tau_c = 0.5, s = 2e-3;
  const double phi = std::exp(-tau0 / tau_c);
  const std::size_t n = std::size_t{1} << 20;
  std::mt19937_64 rng(2024);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> y(n);
  double g = s * normal(rng);  // stationary start
  const double drive = s * std::sqrt(1 - phi * phi);
  for (auto& v : y) {
    g = phi * g + drive * normal(rng);
    v = g;
  }
  const auto series = PhaseSeries::from_rate(y, tau0);
  const std::vector<std::int64_t> m{1, 8, 32, 128, 512, 2048};
  const auto points = compute_deviation(series, Statistic::oadev, m);
  REQUIRE(points.size() == m.size());
  NoiseTerms t;
  t.gauss_markov = {GaussMarkov{s, tau_c}};
  const Eigen::MatrixXd cov = oavar_covariance(t, m, static_cast<std::int64_t>(n) + 1, tau0);
  for (std::size_t j = 0; j < m.size(); ++j) {
    const double expected = derived_avar(s, phi, m[j]);
    const double sd = std::sqrt(cov(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(j)));
    const double z = (points[j].dev * points[j].dev - expected) / sd;
    INFO("m = " << m[j] << ": OAVAR " << points[j].dev * points[j].dev << ", exact " << expected
                << ", sd " << sd << ", z " << z);
    CHECK(std::abs(z) < 4.5);
  }
}
