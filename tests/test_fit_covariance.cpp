// OAVAR covariance lag sums (lib/src/fit_covariance_lagsum.cpp, fit_covariance_kernels.cpp):
// the discrete Gauss rule, the lag correlations against the FFT of the per-sample PSDs, the
// sums against the previous FFT path and against direct sums over every lag, precision at
// m = 2^22, and bounded cost at the lengths of a 10 GB bag.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "../../lib/src/fit_covariance_lags.hpp"  // internal interface under test
#include "../../lib/src/fit_internal.hpp"
#include "fit_covariance_fft.hpp"  // the previous FFT path, the reference
#include "test_support.hpp"

namespace {

using namespace sigmatau;
__extension__ typedef __int128 Int128;
using namespace sigmatau::detail;

constexpr double kTau0 = 0.005;  // 200 Hz
constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kPi = 3.14159265358979323846;
const std::string kNames[] = {"Q", "N", "B", "K", "GM1", "GM2", "GM3"};

/// Every lag summed one by one with the same correlations (the quadrature's reference).
LagSums direct_lag_sums(const PairCorrelation& corr, std::int64_t n_phase) {
  const std::int64_t na = n_phase - 2 * corr.ma(), nb = n_phase - 2 * corr.mb();
  const int t = corr.terms();
  LagSums s{Eigen::MatrixXd::Zero(t, t), Eigen::VectorXd::Zero(t)};
  std::vector<double> c(static_cast<std::size_t>(t));
  for (std::int64_t lag = -(na - 1); lag <= nb - 1; ++lag) {
    corr.evaluate(static_cast<double>(lag), c);
    const double w = static_cast<double>(std::min(na, nb - lag) - std::max<std::int64_t>(0, -lag));
    for (int i = 0; i < t; ++i) {
      s.c1(i) += w * c[static_cast<std::size_t>(i)];
      for (int j = 0; j < t; ++j)
        s.cc(i, j) += w * c[static_cast<std::size_t>(i)] * c[static_cast<std::size_t>(j)];
    }
  }
  return s;
}

/// |x - y| relative to the scale of the element: |y| on the diagonal and for c1, the geometric
/// mean of the two diagonal elements off it (cross sums can pass through zero).
double rel_error(const LagSums& x, const LagSums& y, int i, int j) {
  const double scale = i == j ? std::abs(y.cc(i, i)) : std::sqrt(std::abs(y.cc(i, i) * y.cc(j, j)));
  return std::abs(x.cc(i, j) - y.cc(i, j)) / scale;
}

struct Layout {
  std::int64_t ma, mb, n_phase;
};

/// Unequal, equal, small, and close to N / 2 (a handful of terms).
const std::vector<Layout> kLayouts{{1, 1, 200},      {1, 2, 1001},      {1, 64, 4097},
                                   {3, 5, 10000},    {7, 7, 50},        {16, 1024, 4097},
                                   {100, 37, 60001}, {512, 512, 1030},  {999, 1000, 2003},
                                   {1, 2048, 4100},  {300, 2000, 4001}, {4096, 4096, 65537}};

}  // namespace

TEST_CASE("the discrete Gauss rule sums polynomials of degree < 2n over 0..M-1 exactly") {
  for (const std::int64_t big_m : {12, 50, 1000, 23457}) {
    const DiscreteGaussRule rule = discrete_gauss_rule(big_m, 12);
    for (int k = 0; k <= 23; k += 1) {
      // Scaled to [0, 1] so that the powers stay O(1); the reference in long double.
      long double exact = 0;
      for (std::int64_t i = 0; i < big_m; ++i) {
        exact += std::pow(static_cast<long double>(i) / static_cast<long double>(big_m), k);
      }
      double rule_sum = 0;
      for (int j = 0; j < 12; ++j)
        rule_sum += rule.weights(j) * std::pow(rule.nodes(j) / static_cast<double>(big_m), k);
      INFO("M = " << big_m << " degree " << k);
      // 1e-12: positive weights, so only the rounding of 12 nodes and of the eigensolver
      // (~1e-14 relative at these sizes) separates the two.
      SIGMATAU_CHECK_REL(rule_sum, static_cast<double>(exact), 1e-12);
    }
  }
}

TEST_CASE("Q, N and K lag correlations equal the inverse FFT of their per-sample PSDs") {
  // The FFT is exact for these trigonometric polynomials once P > 2 (m_a + m_b + 1).
  for (const Layout& layout : kLayouts) {
    const std::int64_t ma = layout.ma, mb = layout.mb;
    std::int64_t big_p = 256;
    while (big_p < 4 * (ma + mb + 1)) big_p *= 2;
    const auto ref = fft_lag_correlations(ma, mb, kTau0, std::nullopt, big_p);
    const PairCorrelation corr(ma, mb, kTau0);
    std::vector<double> c(4);
    for (const int t : {0, 1, 3}) {
      const auto& r = ref[static_cast<std::size_t>(t)];
      const double scale = *std::max_element(
          r.begin(), r.end(), [](double x, double y) { return std::abs(x) < std::abs(y); });
      double worst = 0;
      for (std::int64_t u = 0; u <= big_p / 2; ++u) {
        corr.evaluate(static_cast<double>(u + ma - mb), c);
        worst = std::max(worst,
                         std::abs(c[static_cast<std::size_t>(t)] - r[static_cast<std::size_t>(u)]));
      }
      INFO(kNames[t] << " m_a = " << ma << " m_b = " << mb << " worst " << worst << " of "
                     << scale);
      // 1e-12 of the largest |c|: the FFT's rounding grows like eps log P; the closed forms
      // lose at most ~(m_a + m_b)^0 digits (cubics of |d| <= 2 (m_a + m_b) over m_a m_b).
      CHECK(worst <= 1e-12 * std::abs(scale));
    }
  }
}

TEST_CASE(
    "flicker and Gauss-Markov lag correlations equal the FFT of their PSDs when aliasing is "
    "negligible") {
  // With P = 2^18 the FFT's c is aliased by the tail c(u + k P) ~ -m_a m_b / (pi (kP)^2) (the
  // flicker far field; GM decays faster); the check is over u < 16 (m_a + m_b), where the sums
  // are carried, and the tolerance is that alias.
  const std::int64_t big_p = std::int64_t{1} << 18;
  for (const auto& factors : std::vector<std::pair<std::int64_t, std::int64_t>>{
           {1, 1}, {1, 3}, {4, 4}, {5, 16}, {40, 33}}) {
    const std::int64_t ma = factors.first, mb = factors.second;
    for (const std::optional<double> gm :
         {std::optional<double>{}, std::optional<double>{0.3}, std::optional<double>{0.01}}) {
      const auto ref = fft_lag_correlations(ma, mb, kTau0, gm, big_p);
      const std::vector<double> rates = gm ? std::vector<double>{*gm} : std::vector<double>{};
      const PairCorrelation corr(ma, mb, kTau0, rates);
      const int t = gm ? 4 : 2;
      std::vector<double> c(static_cast<std::size_t>(corr.terms()));
      const auto& r = ref[static_cast<std::size_t>(t)];
      const double scale = std::abs(*std::max_element(
          r.begin(), r.end(), [](double x, double y) { return std::abs(x) < std::abs(y); }));
      // The aliased tail: sum_{k != 0} m_a m_b / (pi (k P)^2) = pi m_a m_b / (3 P^2) (10 % over).
      const double alias =
          1.1 * kPi * static_cast<double>(ma * mb) / (3.0 * static_cast<double>(big_p * big_p));
      double worst = 0;
      for (std::int64_t u = 0; u < 16 * (ma + mb); ++u) {
        corr.evaluate(static_cast<double>(u + ma - mb), c);
        worst = std::max(worst,
                         std::abs(c[static_cast<std::size_t>(t)] - r[static_cast<std::size_t>(u)]));
      }
      INFO(kNames[t] << " m_a = " << ma << " m_b = " << mb << " worst " << worst << " of "
                     << scale);
      CHECK(worst <= alias + 1e-12 * scale);
    }
  }
}

namespace {

/// The flicker correlation's second difference over (m_a, m_b) at `lag` summed directly from
/// flicker_phase_covariance, with the sum of the magnitudes of its nine terms (its rounding
/// scale): the reference for evaluate()'s series.
std::pair<double, double> direct_second_difference(double lag, std::int64_t ma, std::int64_t mb) {
  double direct = 0, magnitude = 0;
  const double g[3] = {1, -2, 1};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double v = g[i] * g[j] *
                       flicker_phase_covariance(lag + j * static_cast<double>(mb) -
                                                i * static_cast<double>(ma));
      direct += v;
      magnitude += std::abs(v);
    }
  }
  return {direct, magnitude};
}

}  // namespace

TEST_CASE("the flicker far-field series joins the direct sum of generalized covariances") {
  // evaluate() switches to the series at |u| = 6 (m_a + m_b). Just beyond it the direct sum of
  // the nine G(d) ~ d^2 ln d loses eps x sum |g g G| to cancellation: that is the tolerance.
  for (const auto& factors : std::vector<std::pair<std::int64_t, std::int64_t>>{
           {1, 1}, {1, 5}, {8, 3}, {100, 100}, {1000, 17}, {65536, 4096}}) {
    const std::int64_t ma = factors.first, mb = factors.second;
    const PairCorrelation corr(ma, mb, kTau0);
    std::vector<double> c(4);
    for (const double factor : {6.01, 6.5, 9.0}) {
      const double u = std::ceil(factor * static_cast<double>(ma + mb));
      const double lag = u + static_cast<double>(ma - mb);
      corr.evaluate(lag, c);
      const auto sums = direct_second_difference(lag, ma, mb);
      const double direct = sums.first, magnitude = sums.second;
      const double mm = static_cast<double>(ma) * static_cast<double>(mb);
      INFO("m_a = " << ma << " m_b = " << mb << " u = " << u << " series " << c[2] << " direct "
                    << direct / mm);
      CHECK(std::abs(c[2] - direct / mm) <= 64 * kEps * magnitude / mm + 1e-10 * std::abs(c[2]));
    }
  }
}

TEST_CASE("the flicker inner series joins the direct second difference for unequal factors") {
  // With m_a << m_b the second difference over m_a of G ~ d^2 ln d cancels (d / m_a)^2 digits,
  // so evaluate() takes it as a series from |d| >= max(6 m_a, 64). Against the direct sum at
  // lags across the support; tolerance: the direct sum's own rounding, eps x sum |g g G|.
  for (const auto& factors : std::vector<std::pair<std::int64_t, std::int64_t>>{
           {1, 64}, {1, 1000}, {2, 5000}, {7, 3000}, {3000, 7}, {100, 20000}}) {
    const std::int64_t ma = factors.first, mb = factors.second;
    const PairCorrelation corr(ma, mb, kTau0);
    std::vector<double> c(4);
    const std::int64_t span = ma + mb;
    double worst = 0;
    for (std::int64_t u = -span; u <= span; u += std::max<std::int64_t>(1, span / 997)) {
      const double lag = static_cast<double>(u + ma - mb);
      corr.evaluate(lag, c);
      const auto sums = direct_second_difference(lag, ma, mb);
      const double direct = sums.first, magnitude = sums.second;
      const double mm = static_cast<double>(ma) * static_cast<double>(mb);
      const double err = std::abs(c[2] - direct / mm);
      worst = std::max(worst, err / (64 * kEps * magnitude / mm + 1e-12));
      INFO("m_a = " << ma << " m_b = " << mb << " u = " << u << " series " << c[2] << " direct "
                    << direct / mm);
      CHECK(err <= 64 * kEps * magnitude / mm + 1e-12);
    }
    MESSAGE("m_a = " << ma << " m_b = " << mb << ": worst error / tolerance " << worst);
  }
}

TEST_CASE("Q, N, K and ramp lag sums agree with the previous FFT path to 1e-10") {
  // The FFT window (-P/2, P/2) holds every lag where these terms are non-zero, so the previous
  // path is exact for them up to rounding: any difference is an error of the new one.
  for (const Layout& layout : kLayouts) {
    const std::int64_t ma = layout.ma, mb = layout.mb, n = layout.n_phase;
    const LagSums fft = covariance_lag_sums_fft(ma, mb, n, kTau0, std::nullopt, 8);
    const LagSums fresh = covariance_lag_sums(PairCorrelation(ma, mb, kTau0), n);
    for (const int i : {0, 1, 3}) {
      for (const int j : {0, 1, 3}) {
        INFO(kNames[i] << "," << kNames[j] << " m_a = " << ma << " m_b = " << mb << " N = " << n
                       << ": " << fresh.cc(i, j) << " vs " << fft.cc(i, j));
        CHECK(rel_error(fresh, fft, i, j) <= 1e-10);
      }
      INFO("ramp x " << kNames[i] << " m_a = " << ma << " m_b = " << mb << " N = " << n);
      const double scale = std::max(std::abs(fft.c1(i)), 1e-300);
      // The ramp sums sum w c cancel (c sums to ~0 over a support): relative to sum w |c|,
      // bounded here by sqrt(n_a cc) (Cauchy-Schwarz with sum w <= n_a n_b).
      const double bound = std::sqrt(std::abs(fft.cc(i, i)) * static_cast<double>(n - 2 * ma) *
                                     static_cast<double>(n - 2 * mb));
      CHECK(std::abs(fresh.c1(i) - fft.c1(i)) <= 1e-10 * std::max(scale, bound));
    }
  }
}

TEST_CASE("flicker and Gauss-Markov lag sums by quadrature equal the direct sum over every lag") {
  double worst = 0;
  for (const Layout& layout : kLayouts) {
    const std::int64_t ma = layout.ma, mb = layout.mb, n = layout.n_phase;
    // The last set: three Gauss-Markov terms at once (a fast, a slow and a near-white one),
    // each with its own correlations and cross sums.
    for (const std::vector<double>& gm : std::vector<std::vector<double>>{
             {}, {0.02}, {1e-4}, {0.02, 1e-4, 0.3}}) {
      const PairCorrelation corr(ma, mb, kTau0, gm);
      const LagSums fresh = covariance_lag_sums(corr, n);
      const LagSums direct = direct_lag_sums(corr, n);
      for (int i = 0; i < corr.terms(); ++i) {
        for (int j = 0; j <= i; ++j) {
          INFO(kNames[i] << "," << kNames[j] << " m_a = " << ma << " m_b = " << mb << " N = " << n
                         << ": " << fresh.cc(i, j) << " vs " << direct.cc(i, j));
          // 1e-12: the Gauss runs converge to ~1e-16 (rho = 5.8, 12 nodes); what remains is
          // the rounding of the direct sum of up to 1.3e5 terms, ~sqrt(n) eps = 4e-14
          // (observed 2.5e-14 at worst).
          CHECK(rel_error(fresh, direct, i, j) <= 1e-12);
          worst = std::max(worst, rel_error(fresh, direct, i, j));
        }
      }
    }
  }
  MESSAGE("worst relative difference, quadrature against every lag: " << worst);
}

TEST_CASE("lag sums at m = 2^22 keep 1e-12 relative accuracy against a long double reference") {
  // Every lag of the support of the compact terms (|u| < m_a + m_b), with c from exact
  // 128-bit integer second-difference sums and summed in long double (independent of the
  // library code).
  const std::int64_t m = std::int64_t{1} << 22;
  for (const auto& factors : std::vector<std::pair<std::int64_t, std::int64_t>>{{m, m}, {3, m}}) {
    const std::int64_t ma = factors.first, mb = factors.second;
    const std::int64_t n = 4 * m + 12345;
    const std::int64_t na = n - 2 * ma, nb = n - 2 * mb;
    long double cc[4][4] = {};
    const long double tau0 = kTau0,
                      mm = static_cast<long double>(ma) * static_cast<long double>(mb);
    for (std::int64_t u = -(ma + mb); u <= ma + mb; ++u) {
      const std::int64_t lag = u + ma - mb;
      if (lag < -(na - 1) || lag > nb - 1) continue;
      // Exact integer second-difference sums (|d| < 2^25, |d|^3 < 2^75 fits in 128 bits).
      Int128 sq = 0, sn = 0, sk = 0;
      const int g[3] = {1, -2, 1};
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
          const Int128 d = std::abs(lag + j * mb - i * ma);
          sq += g[i] * g[j] * (d == 0 ? 1 : 0);
          sn += g[i] * g[j] * d;
          sk += g[i] * g[j] * (d * d * d - d);
        }
      }
      long double c[4] = {static_cast<long double>(sq), static_cast<long double>(sn), 0,
                          static_cast<long double>(sk)};
      c[0] /= mm * tau0 * tau0;
      c[1] /= -2 * mm * tau0;
      c[3] *= tau0 / (12 * mm);
      const long double w =
          static_cast<long double>(std::min(na, nb - lag) - std::max<std::int64_t>(0, -lag));
      for (const int i : {0, 1, 3}) {
        for (const int j : {0, 1, 3}) cc[i][j] += w * c[i] * c[j];
      }
    }
    const LagSums fresh = covariance_lag_sums(PairCorrelation(ma, mb, kTau0), n);
    double worst = 0;
    for (const int i : {0, 1, 3}) {
      for (const int j : {0, 1, 3}) {
        const double scale = std::sqrt(static_cast<double>(std::abs(cc[i][i] * cc[j][j])));
        worst = std::max(worst, std::abs(fresh.cc(i, j) - static_cast<double>(cc[i][j])) / scale);
        INFO(kNames[i] << "," << kNames[j] << " m_a = " << ma << " m_b = " << mb << ": "
                       << fresh.cc(i, j) << " vs " << static_cast<double>(cc[i][j]));
        // 1e-12: the quadrature is exact for these polynomials; c itself loses ~2 digits to
        // the cancellation of the nine cubics of |d| ~ 4 m (observed ~1e-14).
        CHECK(std::abs(fresh.cc(i, j) - static_cast<double>(cc[i][j])) <= 1e-12 * scale);
      }
    }
    MESSAGE("m_a = " << ma << " m_b = " << mb << ": worst relative error " << worst);
  }
}

TEST_CASE(
    "the covariance basis at 10 GB bag lengths is finite, symmetric and positive on the diagonal") {
  // 2^25 samples with octave factors to 2^23: the old FFT path needed ~3 GiB here.
  std::vector<std::int64_t> m;
  for (std::int64_t x = 1; x <= (std::int64_t{1} << 23); x *= 2) m.push_back(x);
  const std::int64_t n = (std::int64_t{1} << 25) + 1;
  const CovarianceBasis basis = build_covariance_basis(m, n, kTau0, {});
  for (std::size_t b = 0; b < m.size(); ++b) {
    for (std::size_t a = 0; a <= b; ++a) {
      const Eigen::MatrixXd& h = basis.h[basis.pair_index(a, b)];
      CHECK(h.allFinite());
      CHECK((h - h.transpose()).cwiseAbs().maxCoeff() == 0);
      if (a == b) {
        for (int t = 1; t < 4; ++t) CHECK(h(t, t) > 0);  // N, B, K: a variance, sum of w c^2
      }
    }
  }
}
