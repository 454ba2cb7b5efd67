// Intervals of the added terms (lib/src/fit_added_intervals.cpp): a Gauss-Markov sigma whose
// interval lets T_c float, and the noise-sinusoid cross term of the OAVAR covariance.
#include <doctest/doctest.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <limits>
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include "../../lib/src/fit_added_intervals.hpp"  // internal interface under test
#include "../../lib/src/fit_added_terms.hpp"
#include "../../lib/src/golden_section.hpp"
#include "exact_curve.hpp"
#include "sigmatau/confidence.hpp"
#include "sigmatau/fit.hpp"
#include "sigmatau/noise_model.hpp"
#include "sigmatau/taus.hpp"
#include "test_support.hpp"

namespace {

using namespace sigmatau;
using namespace sigmatau::detail;

constexpr double kTau0 = 0.01;  // 100 Hz
constexpr double kDegH = std::numbers::pi / 180 / 3600;

/// The bench's slow Gauss-Markov (bench/fit_added_terms_sim.py, gm_sum): 10 deg/h at 200 s on
/// white noise of 0.15 deg/sqrt(h) (9 deg/h/sqrt(Hz)), a 2 h log: its bump peaks near 380 s,
/// where the octave curve has 4 points of EDF 5-40, so T_c is known only to ~10 %.
struct SlowGm {
  std::int64_t samples = 720000;
  double white = 9 * kDegH;  // rad/s/sqrt(Hz)
  double sigma = 10 * kDegH;
  double tau_c_s = 200;
  std::vector<std::int64_t> ms;
  Design d;

  explicit SlowGm(double tau_c = 200) : tau_c_s(tau_c) {
    ms = averaging_factors(TauSpec{}, Statistic::oadev, samples + 1, kTau0);
    d.a = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(ms.size()), kTermCount + 1);
    NoiseTerms unit;
    unit.white = 1.0;
    for (std::size_t j = 0; j < ms.size(); ++j) {
      d.a(static_cast<Eigen::Index>(j), 1) = sampled_avar(unit, ms[j], Sampling{kTau0, 0, false});
    }
    d.a.col(kTermCount) = gauss_markov_column(ms, kTau0, tau_c_s);
    TermVector theta = TermVector::Zero(kTermCount + 1);
    theta(1) = white * white;
    theta(kTermCount) = sigma * sigma;
    d.v = d.a * theta;
  }
  static constexpr Mask kMask = (1u << 1) | (1u << kTermCount);
};

}  // namespace

TEST_CASE("a Gauss-Markov sigma interval that lets T_c float is wider than the fixed-T_c one") {
  const SlowGm gm;
  const std::vector<double> tau_c{gm.tau_c_s};
  const CovarianceBasis basis = build_covariance_basis(gm.ms, gm.samples + 1, kTau0, tau_c);
  const Iterated fit = iterate(gm.d, SlowGm::kMask, basis);
  // The exact curve: the fit returns the truth (to the weights' convergence).
  REQUIRE(std::sqrt(fit.fit.theta(kTermCount)) == doctest::Approx(gm.sigma).epsilon(1e-6).scale(0));
  const AddedCovariance fixed =
      added_term_covariance(gm.d, fit.fit, fit.sigma, gm.ms, gm.samples + 1, kTau0, {}, {});
  const AddedCovariance floating =
      added_term_covariance(gm.d, fit.fit, fit.sigma, gm.ms, gm.samples + 1, kTau0, tau_c, {});
  // Columns: N, GM. A Schur complement can only add variance; here T_c's uncertainty dominates
  // sigma^2's (the falling side fixes sigma^2 T_c): more than twice the fixed-T_c variance.
  CHECK(floating.theta(1, 1) > 2 * fixed.theta(1, 1));
  CHECK(floating.theta(0, 0) >= fixed.theta(0, 0));
  REQUIRE(floating.ln_tau_c_sd.size() == 1);
  // T_c to ~5-15 % at one sd (the bench's median |T_c error| is 12 % for this GM).
  CHECK(floating.ln_tau_c_sd[0] > 0.03);
  CHECK(floating.ln_tau_c_sd[0] < 0.5);
  // The profile interval (T_c floating, the fit's weights) holds the truth (the exact curve's
  // estimate) and is wider than the fixed-T_c Wald interval, theta +- 1.96 sd.
  const double s2 = gm.sigma * gm.sigma, q = 1.959964 * 1.959964;
  const ProfileInterval p =
      gauss_markov_sigma2_profile(gm.d, SlowGm::kMask, fit.sigma, gm.ms, kTau0, 0, gm.tau_c_s, q);
  const double fixed_half = 1.959964 * std::sqrt(fixed.theta(1, 1));
  CHECK(p.low < s2 - fixed_half);
  CHECK(p.high > s2 + fixed_half);
  const ProfileInterval t = gauss_markov_tau_c_profile(gm.d, SlowGm::kMask, fit.sigma, gm.ms,
                                                       gm.samples + 1, kTau0, 0, gm.tau_c_s, q);
  CHECK(t.low < gm.tau_c_s);
  CHECK(t.high > gm.tau_c_s);
}

TEST_CASE("a T_c side the curve does not bound is reported unbounded, not as the search's end") {
  // A 5000 s Gauss-Markov on a 2 h log: only its rising side (AVAR ~ sigma^2 tau / T_c) is in
  // the curve, so a longer T_c with a larger sigma fits as well, up to and past the log's length
  // (7200 s, the end of the search). The high side is then infinity (JSON null), not 7200 s;
  // the low side is bounded (a shorter T_c bends the curve within the log).
  const SlowGm gm(5000);
  const std::vector<double> tau_c{gm.tau_c_s};
  const CovarianceBasis basis = build_covariance_basis(gm.ms, gm.samples + 1, kTau0, tau_c);
  const Iterated fit = iterate(gm.d, SlowGm::kMask, basis);
  const double q = 1.959964 * 1.959964;
  const ProfileInterval t = gauss_markov_tau_c_profile(gm.d, SlowGm::kMask, fit.sigma, gm.ms,
                                                       gm.samples + 1, kTau0, 0, gm.tau_c_s, q);
  CHECK(t.high == std::numeric_limits<double>::infinity());
  CHECK(t.low > 0);
  CHECK(t.low < gm.tau_c_s);
  // The bench's 200 s GM is bounded on both sides (the test above), so the sides are told
  // apart by the curve, not by the code.
  const SlowGm bounded;
  const std::vector<double> tau_c2{bounded.tau_c_s};
  const Iterated fit2 = iterate(bounded.d, SlowGm::kMask,
                                build_covariance_basis(bounded.ms, bounded.samples + 1, kTau0, tau_c2));
  const ProfileInterval t2 =
      gauss_markov_tau_c_profile(bounded.d, SlowGm::kMask, fit2.sigma, bounded.ms,
                                 bounded.samples + 1, kTau0, 0, bounded.tau_c_s, q);
  CHECK(std::isfinite(t2.high));
  CHECK(t2.low > 0);
}

TEST_CASE("the floating-T_c interval covers a seeded Gauss-Markov sigma at its level") {
  // Curves drawn from N(mu, Sigma) of the truth (Sigma the estimates' exact covariance, seeded;
  // the GLS is linear in v, so a draw below 0 at the last points is kept as it is),
  // each refitted with T_c re-found (golden section in ln T_c, the fit's weights fixed at the
  // truth's) and given 95 % intervals of sigma: Satterthwaite on the fixed-T_c and on the
  // floating-T_c (delta method) variance, and the profile likelihood the fit reports; and the
  // profile interval of T_c.
  const SlowGm gm;
  const std::vector<double> tau_c{gm.tau_c_s};
  const CovarianceBasis basis = build_covariance_basis(gm.ms, gm.samples + 1, kTau0, tau_c);
  TermVector theta = TermVector::Zero(kTermCount + 1);
  theta(1) = gm.white * gm.white;
  theta(kTermCount) = gm.sigma * gm.sigma;
  const Eigen::MatrixXd sigma = model_covariance(basis, theta, gm.d.v);
  const Eigen::MatrixXd lower = Eigen::LLT<Eigen::MatrixXd>(sigma).matrixL();
  std::mt19937_64 rng(24);
  std::normal_distribution<double> normal;
  constexpr int kDraws = 200;
  int covered_fixed = 0, covered_floating = 0, covered_profile = 0, covered_tau_c = 0, draws = 0;
  for (int i = 0; i < kDraws; ++i) {
    Eigen::VectorXd z(gm.d.v.size());
    for (Eigen::Index j = 0; j < z.size(); ++j) z(j) = normal(rng);
    Design d = gm.d;
    d.v = gm.d.v + lower * z;
    const auto chi2_at = [&](double x) {
      d.a.col(kTermCount) = gauss_markov_column(gm.ms, kTau0, std::exp(x));
      return gls(d, SlowGm::kMask, sigma).chi2;
    };
    const GoldenMinimum best =
        golden_section_minimum(chi2_at, std::log(gm.tau_c_s / 4), std::log(gm.tau_c_s * 4), 40);
    d.a.col(kTermCount) = gauss_markov_column(gm.ms, kTau0, std::exp(best.x));
    const Gls g = gls(d, SlowGm::kMask, sigma);
    if (!(g.theta(kTermCount) > 0)) continue;
    ++draws;
    const double value = std::sqrt(g.theta(kTermCount));
    const auto covers = [&](const AddedCovariance& c) {
      const double edf = 2 * g.theta(kTermCount) * g.theta(kTermCount) / c.theta(1, 1);
      const Interval ci = chi_squared_interval(value, edf, 0.95);
      return ci.low <= gm.sigma && gm.sigma <= ci.high;
    };
    {
      const ProfileInterval p = gauss_markov_sigma2_profile(
          d, SlowGm::kMask, sigma, gm.ms, kTau0, 0, std::exp(best.x), 1.959964 * 1.959964);
      covered_profile += p.low <= gm.sigma * gm.sigma && gm.sigma * gm.sigma <= p.high;
      const ProfileInterval t =
          gauss_markov_tau_c_profile(d, SlowGm::kMask, sigma, gm.ms, gm.samples + 1, kTau0, 0,
                                     std::exp(best.x), 1.959964 * 1.959964);
      covered_tau_c += t.low <= gm.tau_c_s && gm.tau_c_s <= t.high;
    }
    covered_fixed +=
        covers(added_term_covariance(d, g, sigma, gm.ms, gm.samples + 1, kTau0, {}, {}));
    covered_floating += covers(
        added_term_covariance(d, g, sigma, gm.ms, gm.samples + 1, kTau0, {std::exp(best.x)}, {}));
  }
  REQUIRE(draws == kDraws);
  const double fixed_rate = static_cast<double>(covered_fixed) / draws;
  const double floating_rate = static_cast<double>(covered_floating) / draws;
  MESSAGE("coverage fixed T_c ", fixed_rate, ", floating ", floating_rate, ", profile ",
          covered_profile, ", T_c ", covered_tau_c, " over ", draws, " draws");
  // 95 % nominal; 200 draws give a binomial sd of 1.5 %: 90 % is 3 sd below. The fixed-T_c
  // interval misses T_c's share (measured 54.5 %); the delta method on the floating variance
  // gets most of it (89 %: sigma^2 against ln T_c is far from linear at a 30 % sd), the profile
  // all of it (96.5 %; T_c 95 %).
  const double profile_rate = static_cast<double>(covered_profile) / draws;
  const double tau_c_rate = static_cast<double>(covered_tau_c) / draws;
  CHECK(profile_rate >= 0.90);
  CHECK(profile_rate <= 0.99);
  CHECK(tau_c_rate >= 0.90);
  CHECK(tau_c_rate <= 0.99);
  CHECK(floating_rate > fixed_rate + 0.2);
  CHECK(fixed_rate < 0.8);
}

namespace {

/// The phase-averaged Cov(C_a, C_b) of the cross terms C_m = sum_k ds_k dw_k / n_m by the direct
/// sum over the samples: C_m = sum_i w_i U^m_i / n_m with U^m_i = sum_k ds^m_k h^m(i - k), h^m the
/// second-difference kernel on the rate samples; Cov = sum_{i,i'} U^a_i U^b_i' r(i - i') /
/// (n_a n_b) for a noise of autocovariance r (support |i - i'| <= `lags`), averaged over the
/// phases 0 and pi/2 (U is linear in cos phi, sin phi: their mean is the average over phi).
double direct_cross_covariance(std::int64_t ma, std::int64_t mb, std::int64_t n_phase, double nu,
                               const std::vector<double>& r) {
  const std::int64_t samples = n_phase - 1;
  const auto u_of = [&](std::int64_t m, double phase) {
    std::vector<double> u(static_cast<std::size_t>(samples), 0.0);
    const std::int64_t n = n_phase - 2 * m;
    const auto y = [&](std::int64_t i) {
      return std::cos(2 * std::numbers::pi * nu * static_cast<double>(i) + phase);
    };
    // ds_k = (sum_{i=k+m}^{k+2m-1} y_i - sum_{i=k}^{k+m-1} y_i) / m, rate samples 0-based.
    double first = 0, second = 0;
    for (std::int64_t i = 0; i < m; ++i) first += y(i), second += y(i + m);
    for (std::int64_t k = 0; k < n; ++k) {
      const double ds = (second - first) / static_cast<double>(m);
      for (std::int64_t i = k; i < k + m; ++i)
        u[static_cast<std::size_t>(i)] -= ds / static_cast<double>(m);
      for (std::int64_t i = k + m; i < k + 2 * m; ++i)
        u[static_cast<std::size_t>(i)] += ds / static_cast<double>(m);
      first += y(k + m) - y(k);
      second += y(k + 2 * m) - y(k + m);
    }
    return u;
  };
  const auto lags = static_cast<std::int64_t>(r.size()) - 1;
  double sum = 0;
  for (const double phase : {0.0, std::numbers::pi / 2}) {
    const auto ua = u_of(ma, phase), ub = u_of(mb, phase);
    for (std::int64_t i = 0; i < samples; ++i) {
      for (std::int64_t l = -lags; l <= lags; ++l) {
        if (i + l < 0 || i + l >= samples) continue;
        sum += ua[static_cast<std::size_t>(i)] * ub[static_cast<std::size_t>(i + l)] *
               r[static_cast<std::size_t>(std::abs(l))];
      }
    }
  }
  return sum / 2 / static_cast<double>((n_phase - 2 * ma) * (n_phase - 2 * mb));
}

}  // namespace

TEST_CASE("the sinusoid's cross term of the OAVAR covariance matches the direct sum over samples") {
  // A unit-amplitude sinusoid of period 100 samples (its ADEV peaks near m = 37) on white noise
  // and on a Gauss-Markov noise of T_c = 5 samples, 2^14 samples.
  constexpr std::int64_t kPhase = (std::int64_t{1} << 14) + 1;
  const double f_hz = 0.01 / kTau0;
  const std::vector<std::int64_t> ms{4, 16, 32, 64, 128};
  SUBCASE("white noise") {
    TermVector theta = TermVector::Zero(kTermCount + 1);
    theta(1) = 2.0;  // N^2: per-sample variance N^2 / tau0
    theta(kTermCount) = 1.0;
    const Eigen::MatrixXd c = sinusoid_cross_covariance(ms, kPhase, kTau0, {}, f_hz, theta);
    const std::vector<double> r{theta(1) / kTau0};
    for (std::size_t a = 0; a < ms.size(); ++a) {
      for (std::size_t b = a; b < ms.size(); ++b) {
        const double direct = direct_cross_covariance(ms[a], ms[b], kPhase, 0.01, r);
        // The closed form counts min(n_a, n_b) pairs at every lag and a whole number of periods:
        // both off by ~(m_a + m_b) / n (1.6 % at m = 128) and by the part-period, ~1 / (n nu).
        CHECK(c(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)) ==
              doctest::Approx(direct).epsilon(0.03).scale(0));
      }
    }
  }
  SUBCASE("Gauss-Markov noise") {
    const double tc = 5 * kTau0, phi = std::exp(-kTau0 / tc);
    TermVector theta = TermVector::Zero(kTermCount + 2);
    theta(kTermCount) = 3.0;      // sigma^2
    theta(kTermCount + 1) = 1.0;  // A^2
    const Eigen::MatrixXd c = sinusoid_cross_covariance(ms, kPhase, kTau0, {tc}, f_hz, theta);
    std::vector<double> r;
    for (int l = 0; l <= 200; ++l)
      r.push_back(theta(kTermCount) * std::pow(phi, l));  // phi^200 ~ 4e-18
    for (std::size_t a = 0; a < ms.size(); ++a) {
      const double direct = direct_cross_covariance(ms[a], ms[a], kPhase, 0.01, r);
      // As above, plus the lags' support (~T_c) next to n.
      CHECK(c(static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(a)) ==
            doctest::Approx(direct).epsilon(0.03).scale(0));
    }
  }
}

TEST_CASE("a fit with added terms reports T_c and f intervals around its estimates") {
  // Exact curves as in test_fit_added_terms.cpp (2^20 samples at 100 Hz): the estimates are the
  // truth, and each interval holds its estimate and is not empty.
  constexpr std::int64_t kSamples = std::int64_t{1} << 20;
  const CurveSource source{kTau0, kSamples + 1, 0};
  SUBCASE("Gauss-Markov") {
    NoiseTerms truth;
    truth.white = 1e-4;
    truth.gauss_markov = {GaussMarkov{1e-4, 10.0}};
    const NoiseFit fit =
        fit_noise(test::exact_oadev_curve(truth, kSamples, kTau0), source, FitOptions{});
    REQUIRE(fit.joint);
    REQUIRE(fit.joint->gauss_markov.size() == 1);
    const auto& gm = fit.joint->gauss_markov.front();
    CHECK(gm.tau_c_ci_low_s < gm.tau_c_s);
    CHECK(gm.tau_c_ci_high_s > gm.tau_c_s);
    CHECK(gm.ci_low < gm.sigma);
    CHECK(gm.ci_high > gm.sigma);
  }
  SUBCASE("sinusoid") {
    NoiseTerms truth;
    truth.white = 1e-4;
    truth.sinusoid = Sinusoid{5e-4, 0.5, 0.0};
    const NoiseFit fit =
        fit_noise(test::exact_oadev_curve(truth, kSamples, kTau0), source, FitOptions{});
    REQUIRE(fit.joint);
    REQUIRE(fit.joint->sinusoid);
    const auto& s = *fit.joint->sinusoid;
    CHECK(s.frequency_ci_low_hz < s.frequency_hz);
    CHECK(s.frequency_ci_high_hz > s.frequency_hz);
    CHECK(s.ci_low < s.amplitude);
    CHECK(s.ci_high > s.amplitude);
  }
}
