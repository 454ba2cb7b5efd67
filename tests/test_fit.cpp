// Noise fit: exact OAVAR covariance, joint fit on exact curves and on seeded simulations,
// model selection, forced models, slope read-outs and bad inputs.
#include "sigmatau/fit.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <string>
#include <vector>

#include "sigmatau/allan_curve.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/simulate.hpp"
#include "exact_curve.hpp"
#include "test_support.hpp"

namespace {

using namespace sigmatau;

constexpr double kTau0 = 0.01;  // 100 Hz
/// 2^16 samples (11 min at 100 Hz): small enough that the covariance basis builds in well under
/// a second, long enough for 15 octave points.
constexpr std::int64_t kSamples = std::int64_t{1} << 16;

/// An exact theoretical OADEV curve (sampled_avar) at the octave factors of a log of kSamples.
AllanCurve exact_curve(const NoiseTerms& truth, std::int64_t flicker_taps = 0) {
  return test::exact_oadev_curve(truth, kSamples, kTau0, flicker_taps);
}

/// Rate samples of one axis of a simulated gyro.
std::vector<double> simulate_axis(const NoiseTerms& truth, std::uint64_t seed,
                                  std::int64_t samples = kSamples) {
  SimulationConfig c;
  c.rate_hz = 1 / kTau0;
  c.samples = samples;
  c.seed = seed;
  ErrorModel m;
  m.noise = {truth, truth, truth};
  c.gyro = m;
  Simulator sim(c);
  std::vector<double> block(static_cast<std::size_t>(samples * 3));
  sim.next(block, samples);
  std::vector<double> x(static_cast<std::size_t>(samples));
  for (std::int64_t i = 0; i < samples; ++i) x[static_cast<std::size_t>(i)] = block[static_cast<std::size_t>(3 * i)];
  return x;
}

NoiseTerms nbk() {
  // MEMS-like, scaled so that N, B and K each dominate part of an 11-minute curve.
  NoiseTerms t;
  t.white = 4e-4;
  t.bias_instability = 3e-4;
  t.rate_random_walk = 1e-4;
  return t;
}

}  // namespace

TEST_CASE("white noise OAVAR covariance at m = 1 matches the closed form sigma^4 (3n - 1) / n^2") {
  // d_k = y_{k+1} - y_k has c(0) = 2 s2, c(+-1) = -s2 (s2 = N^2 / tau0 per sample), so
  // Var = (1 / (2 n^2)) [n 4 s2^2 + 2 (n - 1) s2^2] = s2^2 (3n - 1) / n^2 with n = N - 2.
  NoiseTerms t;
  t.white = 2e-3;
  const std::int64_t n_phase = 1001;
  const std::vector<std::int64_t> m{1};
  const Eigen::MatrixXd cov = oavar_covariance(t, m, n_phase, kTau0);
  const double s2 = 2e-3 * 2e-3 / kTau0;
  const double n = n_phase - 2;
  // 1e-10: the FFT evaluates a trigonometric polynomial exactly up to rounding.
  SIGMATAU_CHECK_REL(cov(0, 0), s2 * s2 * (3 * n - 1) / (n * n), 1e-10);
}

TEST_CASE("quantization OAVAR variance at m = 1 includes the uniform error's fourth cumulant") {
  // d_k = (e_k - 2 e_{k+1} + e_{k+2}) / tau0 with e uniform, variance Q^2, fourth cumulant
  // -1.2 Q^4. In units of Q^2 / tau0^2: c(0) = 6, c(+-1) = -4, c(+-2) = 1, and the kurtosis
  // overlaps sum_i g_k(i)^2 g_{k+L}(i)^2 are 18, 8, 1 for |L| = 0, 1, 2. With n terms
  // Var(s2) = (1 / (4 n^2)) sum_L (n - |L|) [2 c(L)^2 - 1.2 S(L)].
  NoiseTerms t;
  t.quantization = 3e-5;
  const std::int64_t n_phase = 2001;
  const std::vector<std::int64_t> m{1};
  const Eigen::MatrixXd cov = oavar_covariance(t, m, n_phase, kTau0);
  const double n = n_phase - 2;
  const double c[3] = {6, -4, 1}, s[3] = {18, 8, 1};
  double sum = 0;
  for (int lag = -2; lag <= 2; ++lag) {
    const int l = std::abs(lag);
    sum += (n - l) * (2 * c[l] * c[l] - 1.2 * s[l]);
  }
  const double q2 = 3e-5 * 3e-5 / (kTau0 * kTau0);
  // 1e-10: both sides are exact sums; only rounding differs.
  SIGMATAU_CHECK_REL(cov(0, 0), q2 * q2 * sum / (4 * n * n), 1e-10);
}

TEST_CASE("quantization OAVAR variance agrees with a Monte Carlo of the simulator's uniform error") {
  NoiseTerms t;
  t.quantization = 3e-5;
  const std::int64_t samples = 4096;
  const std::vector<std::int64_t> m{1, 2, 16};
  const Eigen::MatrixXd cov = oavar_covariance(t, m, samples + 1, kTau0);
  constexpr int kRuns = 400;
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(3), sq = Eigen::VectorXd::Zero(3);
  for (int r = 0; r < kRuns; ++r) {
    const auto x = simulate_axis(t, 5000 + static_cast<std::uint64_t>(r), samples);
    const auto pts = compute_deviation(PhaseSeries::from_rate(x, kTau0), Statistic::oadev, m);
    for (int j = 0; j < 3; ++j) {
      const double e = pts[static_cast<std::size_t>(j)].dev * pts[static_cast<std::size_t>(j)].dev;
      mean(j) += e / kRuns;
      sq(j) += e * e / kRuns;
    }
  }
  for (int j = 0; j < 3; ++j) {
    const double sample_var = (sq(j) - mean(j) * mean(j)) * kRuns / (kRuns - 1);
    INFO("m = " << m[static_cast<std::size_t>(j)] << " sample " << sample_var << " model " << cov(j, j));
    // These estimates average thousands of terms, so they are near Gaussian and the sample
    // variance of 400 runs has a relative standard error of sqrt(2 / 399) = 7 %; 20 % is three
    // of them. The Gaussian-only model is 1.3-1.4x larger here and fails this check.
    SIGMATAU_CHECK_REL(sample_var, cov(j, j), 0.20);
  }
}

TEST_CASE("OAVAR covariance across taus agrees with a Monte Carlo of the simulator") {
  NoiseTerms t = nbk();
  const std::int64_t samples = 4096;
  const std::vector<std::int64_t> m{1, 8, 64, 512};
  const Eigen::MatrixXd cov = oavar_covariance(t, m, samples + 1, kTau0);
  constexpr int kRuns = 400;
  std::vector<Eigen::VectorXd> v;
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(4);
  for (int r = 0; r < kRuns; ++r) {
    const auto x = simulate_axis(t, 1000 + static_cast<std::uint64_t>(r), samples);
    const auto pts = compute_deviation(PhaseSeries::from_rate(x, kTau0), Statistic::oadev, m);
    Eigen::VectorXd e(4);
    for (int j = 0; j < 4; ++j) e(j) = pts[static_cast<std::size_t>(j)].dev * pts[static_cast<std::size_t>(j)].dev;
    mean += e / kRuns;
    v.push_back(e);
  }
  Eigen::MatrixXd sample = Eigen::MatrixXd::Zero(4, 4);
  for (const auto& e : v) sample += (e - mean) * (e - mean).transpose() / (kRuns - 1);
  for (int a = 0; a < 4; ++a) {
    // Relative standard error of a sample variance from R runs is sqrt(2 / (R - 1)) = 7 % for
    // Gaussian estimates; the few-EDF points are chi-squared-like (kurtosis up to ~3x), so
    // 25 % is about 3.5 standard errors.
    SIGMATAU_CHECK_REL(sample(a, a), cov(a, a), 0.25);
    for (int b = a + 1; b < 4; ++b) {
      const double model_corr = cov(a, b) / std::sqrt(cov(a, a) * cov(b, b));
      const double sample_corr = sample(a, b) / std::sqrt(sample(a, a) * sample(b, b));
      INFO("pair " << a << "," << b << " model " << model_corr << " sample " << sample_corr);
      // Standard error of a sample correlation ~ (1 - r^2) / sqrt(R) <= 0.05; 0.15 is 3 of them.
      CHECK(std::abs(model_corr - sample_corr) < 0.15);
    }
  }
}

TEST_CASE("fitting an exact theoretical curve returns its parameters to 1e-6") {
  const CurveSource source{kTau0, kSamples + 1, 0};
  SUBCASE("N, B, K selected by BIC") {
    const NoiseFit f = fit_noise(exact_curve(nbk()), source, FitOptions{});
    REQUIRE(f.joint);
    CHECK(f.joint->model_terms == std::vector<NoiseTerm>{NoiseTerm::white, NoiseTerm::bias_instability,
                                                         NoiseTerm::rate_random_walk});
    // 1e-6: the residual of an exact curve is zero, so only rounding in the solve remains.
    SIGMATAU_CHECK_REL(f.joint->parameter(NoiseTerm::white).value, *nbk().white, 1e-6);
    SIGMATAU_CHECK_REL(f.joint->parameter(NoiseTerm::bias_instability).value, *nbk().bias_instability, 1e-6);
    SIGMATAU_CHECK_REL(f.joint->parameter(NoiseTerm::rate_random_walk).value, *nbk().rate_random_walk, 1e-6);
  }
  SUBCASE("all five terms forced") {
    NoiseTerms t = nbk();
    t.quantization = 3e-6;
    t.rate_ramp = 2e-6;
    FitOptions o;
    o.terms = parse_fit_terms("Q,N,B,K,R");
    const NoiseFit f = fit_noise(exact_curve(t), source, o);
    SIGMATAU_CHECK_REL(f.joint->parameter(NoiseTerm::quantization).value, *t.quantization, 1e-6);
    SIGMATAU_CHECK_REL(f.joint->parameter(NoiseTerm::white).value, *t.white, 1e-6);
    SIGMATAU_CHECK_REL(f.joint->parameter(NoiseTerm::bias_instability).value, *t.bias_instability, 1e-6);
    SIGMATAU_CHECK_REL(f.joint->parameter(NoiseTerm::rate_random_walk).value, *t.rate_random_walk, 1e-6);
    SIGMATAU_CHECK_REL(f.joint->parameter(NoiseTerm::rate_ramp).value, *t.rate_ramp, 1e-6);
  }
}

TEST_CASE("the joint fit's intervals on a seeded simulation contain the truth") {
  // 99.9 % intervals: each misses the truth with probability 1e-3 if they are right, so three
  // parameters on two seeds fail by chance with probability < 0.6 %; the seeds are fixed.
  const NoiseTerms t = nbk();
  FitOptions o;
  o.confidence_level = 0.999;
  o.terms = parse_fit_terms("N,B,K");
  o.method = FitMethod::both;
  for (const std::uint64_t seed : {11u, 12u}) {
    const auto x = simulate_axis(t, seed);
    const auto series = PhaseSeries::from_rate(x, kTau0);
    const auto curve = compute_allan_curve(series, Statistic::oadev, TauSpec{}, 0.683);
    const NoiseFit f = fit_noise(curve, CurveSource{kTau0, series.size(), 0}, o);
    for (const NoiseTerm term : {NoiseTerm::white, NoiseTerm::bias_instability, NoiseTerm::rate_random_walk}) {
      const auto& p = f.joint->parameter(term);
      const double truth = term == NoiseTerm::white ? *t.white
                           : term == NoiseTerm::bias_instability ? *t.bias_instability
                                                                 : *t.rate_random_walk;
      INFO("seed " << seed << " " << term_symbol(term) << ": " << p.ci_low << " <= " << truth
                   << " <= " << p.ci_high << " (value " << p.value << ")");
      CHECK(p.ci_low <= truth);
      CHECK(truth <= p.ci_high);
    }
    REQUIRE(f.slopes);
    CHECK(f.slopes->parameter(NoiseTerm::white).in_model);
  }
}

TEST_CASE("model selection keeps only the terms a clear case supports") {
  SUBCASE("white noise only: N, with Q, B, K, R as upper bounds") {
    NoiseTerms t;
    t.white = 1e-3;
    const auto x = simulate_axis(t, 5);
    const auto series = PhaseSeries::from_rate(x, kTau0);
    const auto curve = compute_allan_curve(series, Statistic::oadev, TauSpec{}, 0.683);
    const NoiseFit f = fit_noise(curve, CurveSource{kTau0, series.size(), 0}, FitOptions{});
    CHECK(f.joint->model_terms == std::vector<NoiseTerm>{NoiseTerm::white});
    for (const auto& p : f.joint->parameters) {
      if (p.term == NoiseTerm::white) continue;
      CHECK_FALSE(p.in_model);
      CHECK(p.upper_bound > 0);
      CHECK(std::isfinite(p.upper_bound));
    }
    // A white-noise B below its bound: the bound is at least the ADEV floor of what was seen.
    CHECK(f.joint->parameter(NoiseTerm::bias_instability).upper_bound > 0);
  }
  SUBCASE("white noise and a strong random walk: N and K") {
    NoiseTerms t;
    t.white = 1e-3;
    t.rate_random_walk = 1e-3;
    const auto x = simulate_axis(t, 6);
    const auto series = PhaseSeries::from_rate(x, kTau0);
    const auto curve = compute_allan_curve(series, Statistic::oadev, TauSpec{}, 0.683);
    const NoiseFit f = fit_noise(curve, CurveSource{kTau0, series.size(), 0}, FitOptions{});
    CHECK(f.joint->model_terms ==
          std::vector<NoiseTerm>{NoiseTerm::white, NoiseTerm::rate_random_walk});
  }
}

TEST_CASE("upper bounds of terms left out cover the truth: variance under the bound") {
  // A model forced to leave out a random walk that is present: the bound on K must still
  // contain the truth. Weighted by the covariance of the model without K, the large-tau points
  // look far more precise than they are and the bound lands below the truth; with the variance
  // under the bound itself (test inversion) it covers. 99 % bounds, four fixed seeds: with
  // right bounds all four cover with probability 0.99^4 = 96 %.
  const NoiseTerms t = nbk();
  FitOptions o;
  o.confidence_level = 0.99;
  o.terms = parse_fit_terms("N,B");
  for (const std::uint64_t seed : {21u, 22u, 23u, 24u}) {
    const auto x = simulate_axis(t, seed);
    const auto series = PhaseSeries::from_rate(x, kTau0);
    const auto curve = compute_allan_curve(series, Statistic::oadev, TauSpec{}, 0.683);
    const NoiseFit f = fit_noise(curve, CurveSource{kTau0, series.size(), 0}, o);
    const auto& k = f.joint->parameter(NoiseTerm::rate_random_walk);
    INFO("seed " << seed << ": K bound " << k.upper_bound << ", truth " << *t.rate_random_walk);
    CHECK_FALSE(k.in_model);
    CHECK(*t.rate_random_walk <= k.upper_bound);
  }
}

TEST_CASE("model selection finds N, B, K on seeded simulations where all three are visible") {
  // nbk() on 11 min: K crosses the flicker floor near 4 s, so K dominates the last 7 octaves
  // and is far more significant than in the issue's 2 h MEMS profile. Six fixed seeds.
  for (const std::uint64_t seed : {31u, 32u, 33u, 34u, 35u, 36u}) {
    const auto x = simulate_axis(nbk(), seed);
    const auto series = PhaseSeries::from_rate(x, kTau0);
    const auto curve = compute_allan_curve(series, Statistic::oadev, TauSpec{}, 0.683);
    const NoiseFit f = fit_noise(curve, CurveSource{kTau0, series.size(), 0}, FitOptions{});
    INFO("seed " << seed);
    CHECK(f.joint->model_terms == std::vector<NoiseTerm>{NoiseTerm::white, NoiseTerm::bias_instability,
                                                         NoiseTerm::rate_random_walk});
  }
}

TEST_CASE("--terms forces the model even where the data do not support a term") {
  NoiseTerms t;
  t.white = 1e-3;
  FitOptions o;
  o.terms = parse_fit_terms("K,N,B");  // any order; reported in Q N B K R order
  const NoiseFit f = fit_noise(exact_curve(t), CurveSource{kTau0, kSamples + 1, 0}, o);
  CHECK(f.joint->model_terms == std::vector<NoiseTerm>{NoiseTerm::white, NoiseTerm::bias_instability,
                                                       NoiseTerm::rate_random_walk});
  SIGMATAU_CHECK_REL(f.joint->parameter(NoiseTerm::white).value, 1e-3, 1e-6);
  // Absent from the truth: fitted as 0 (non-negative), bounded above.
  CHECK(f.joint->parameter(NoiseTerm::rate_random_walk).value == 0);
  CHECK(f.joint->parameter(NoiseTerm::rate_random_walk).ci_high > 0);
}

TEST_CASE("slope read-outs of an exact white + random-walk curve") {
  NoiseTerms t;
  t.white = 1e-3;
  t.rate_random_walk = 1e-3;
  AllanCurve curve = exact_curve(t);
  // Identified noise as a clean curve would be: white below the crossing, random walk above.
  const double crossing = 3 * 1e-3 * 1e-3 / (1e-3 * 1e-3);  // N^2/tau = K^2 tau/3 at tau = 3 s
  for (auto& p : curve.points) p.confidence.noise.alpha = p.value.tau_s < crossing / 8 ? 0 : (p.value.tau_s > crossing * 8 ? -2 : -1);
  FitOptions o;
  o.method = FitMethod::slopes;
  const NoiseFit f = fit_noise(curve, CurveSource{kTau0, kSamples + 1, 0}, o);
  REQUIRE(f.slopes);
  // Far from the crossing the other term adds < 1/8 of the variance: N within 7 % (sqrt(1+1/8)),
  // K within 7 % too (and the discrete K^2 tau0^2/(6 tau) correction is negligible there).
  SIGMATAU_CHECK_REL(f.slopes->parameter(NoiseTerm::white).value, 1e-3, 0.07);
  SIGMATAU_CHECK_REL(f.slopes->parameter(NoiseTerm::rate_random_walk).value, 1e-3, 0.07);
  CHECK_FALSE(f.slopes->parameter(NoiseTerm::quantization).in_model);
}

TEST_CASE("a slope line is read over one run of points: a stray identification is not on it") {
  NoiseTerms t;
  t.white = 1e-3;
  t.rate_random_walk = 1e-3;
  AllanCurve curve = exact_curve(t);
  // As in the clean case above (white below crossing/8, random walk above 8 x crossing), but
  // the third point (tau = 0.04 s, white noise 5000x the random walk's AVAR) called random walk,
  // as noise identification can call a point of another region.
  const double crossing = 3.0;
  for (auto& p : curve.points) p.confidence.noise.alpha = p.value.tau_s < crossing / 8 ? 0 : (p.value.tau_s > crossing * 8 ? -2 : -1);
  REQUIRE(curve.points.size() > 3);
  curve.points[2].confidence.noise.alpha = -2;
  FitOptions o;
  o.method = FitMethod::slopes;
  const NoiseFit f = fit_noise(curve, CurveSource{kTau0, kSamples + 1, 0}, o);
  // K from its own run at the end: within 7 % as above. Read with the stray point (the one with
  // by far the largest EDF), K came out 43x too large.
  SIGMATAU_CHECK_REL(f.slopes->parameter(NoiseTerm::rate_random_walk).value, 1e-3, 0.07);
  SIGMATAU_CHECK_REL(f.slopes->parameter(NoiseTerm::white).value, 1e-3, 0.07);

  SUBCASE("two runs of one point each: K is read at the end of the curve, where it lives") {
    for (auto& p : curve.points) p.confidence.noise.alpha = p.value.tau_s < crossing / 8 ? 0 : -1;
    curve.points[2].confidence.noise.alpha = -2;
    curve.points.back().confidence.noise.alpha = -2;
    const NoiseFit g = fit_noise(curve, CurveSource{kTau0, kSamples + 1, 0}, o);
    SIGMATAU_CHECK_REL(g.slopes->parameter(NoiseTerm::rate_random_walk).value, 1e-3, 0.07);
  }
  SUBCASE("a white-PM point mid-curve is not quantization: Q's region starts at the first tau") {
    curve.points[6].confidence.noise.alpha = 2;  // 0.64 s, in the white-noise region
    const NoiseFit g = fit_noise(curve, CurveSource{kTau0, kSamples + 1, 0}, o);
    CHECK_FALSE(g.slopes->parameter(NoiseTerm::quantization).in_model);
    // ... while the same identification at the first points is Q's run.
    curve.points[0].confidence.noise.alpha = 2;
    curve.points[1].confidence.noise.alpha = 2;
    const NoiseFit h = fit_noise(curve, CurveSource{kTau0, kSamples + 1, 0}, o);
    CHECK(h.slopes->parameter(NoiseTerm::quantization).in_model);
  }
}

TEST_CASE("bad inputs are clear errors") {
  const CurveSource source{kTau0, kSamples + 1, 0};
  SUBCASE("too few taus") {
    AllanCurve c = exact_curve(nbk());
    c.points.resize(3);
    CHECK_THROWS_WITH_AS(fit_noise(c, source, FitOptions{}), doctest::Contains("need at least"), Error);
  }
  SUBCASE("all NaN") {
    AllanCurve c = exact_curve(nbk());
    for (auto& p : c.points) p.value.dev = std::nan("");
    CHECK_THROWS_WITH_AS(fit_noise(c, source, FitOptions{}), doctest::Contains("0 usable"), Error);
  }
  SUBCASE("not an OADEV curve") {
    AllanCurve c = exact_curve(nbk());
    c.statistic = Statistic::mdev;
    CHECK_THROWS_WITH_AS(fit_noise(c, source, FitOptions{}), doctest::Contains("oadev"), Error);
  }
  SUBCASE("tau does not match the sample rate") {
    CHECK_THROWS_WITH_AS(fit_noise(exact_curve(nbk()), CurveSource{0.02, kSamples + 1, 0}, FitOptions{}),
                         doctest::Contains("sample rate"), Error);
  }
  SUBCASE("bad --terms, --method, --ci") {
    CHECK_THROWS_WITH_AS(parse_fit_terms("N,X"), doctest::Contains("\"X\""), Error);
    CHECK_THROWS_WITH_AS(parse_fit_terms("N,N"), doctest::Contains("repeated"), Error);
    CHECK_THROWS_AS(parse_fit_method("best"), Error);
    FitOptions o;
    o.confidence_level = std::nan("");
    CHECK_THROWS_WITH_AS(fit_noise(exact_curve(nbk()), source, o), doctest::Contains("--ci"), Error);
  }
}

TEST_CASE("goodness of fit: a curve no model describes is flagged, and --tau-min mends it") {
  const CurveSource source{kTau0, kSamples + 1, 0};
  // A sensor that low-pass filters its output: the first three points 20 % below N^2 / tau.
  AllanCurve filtered = exact_curve(nbk());
  for (std::size_t j = 0; j < 3; ++j) filtered.points[j].value.dev *= 0.8;
  // The IEEE terms alone (no added terms, no taus left out: fit_added_terms.cpp, fit.cpp).
  FitOptions ieee_only;
  ieee_only.added_terms = false;
  const NoiseFit bad = fit_noise(filtered, source, ieee_only);
  REQUIRE(bad.joint);
  CHECK(bad.joint->p_value < kMisfitPValue);
  // The fit bends toward the filtered points, so the furthest is among them or next to them.
  CHECK(bad.joint->misfit_tau_s <= filtered.points[3].value.tau_s);
  CHECK(misfit_warning(*bad.joint, "gx").find("gx: no model") == 0);
  CHECK(misfit_warning(*bad.joint, "gx").find("filters its output") != std::string::npos);
  CHECK(bad.joint->misfit_at_shortest_taus);

  SUBCASE("a bump mid-curve is something outside the model, not the sensor's filter") {
    AllanCurve bump = exact_curve(nbk());
    bump.points[8].value.dev *= 1.3;  // 2.56 s: a Gauss-Markov or sinusoid's hump
    const NoiseFit f = fit_noise(bump, source, ieee_only);
    CHECK(f.joint->p_value < kMisfitPValue);
    CHECK_FALSE(f.joint->misfit_at_shortest_taus);
    CHECK(misfit_warning(*f.joint, "gx").find("Something outside Q, N, B, K, R") != std::string::npos);
  }

  SUBCASE("by default the filtered taus are described: left out, or a short Gauss-Markov") {
    // A first-order filter's output is a Gauss-Markov process of short T_c: the fit leaves out
    // the point it cannot describe and states the rest with such a term (or leaves them all out).
    const NoiseFit mended = fit_noise(filtered, source, FitOptions{});
    REQUIRE(mended.joint);
    INFO("left out " << mended.joint->left_out_taus_s.size() << ", p = " << mended.joint->p_value
                     << ", GM terms " << mended.joint->gauss_markov.size());
    REQUIRE_FALSE(mended.joint->left_out_taus_s.empty());
    CHECK(mended.joint->left_out_taus_s.front() == doctest::Approx(kTau0));
    CHECK(mended.joint->p_value > kMisfitPValue);
    CHECK_FALSE(left_out_warning(*mended.joint, "gx").empty());
    // The curve is described (p above; nothing it reports contradicts it). B alone is not
    // pinned: on an 11-minute curve a Gauss-Markov term and flicker trade parts of the floor.
    CHECK(mended.joint->contradictions.empty());
  }

  FitOptions from_fourth;
  from_fourth.tau_min_s = filtered.points[3].value.tau_s;
  const NoiseFit good = fit_noise(filtered, source, from_fourth);
  CHECK(good.joint->points == bad.joint->points - 3);
  CHECK(good.joint->p_value > 0.5);  // an exact curve from there on: chi-squared ~ 0
  CHECK(misfit_warning(*good.joint, "gx").empty());
  // 1e-6 as for any exact curve: the filtered points no longer enter.
  SIGMATAU_CHECK_REL(good.joint->parameter(NoiseTerm::bias_instability).value,
                     *nbk().bias_instability, 1e-6);

  FitOptions too_narrow;
  too_narrow.tau_min_s = filtered.points[filtered.points.size() - 3].value.tau_s;
  CHECK_THROWS_WITH_AS(fit_noise(filtered, source, too_narrow), doctest::Contains("in the tau range"),
                       Error);
}

TEST_CASE("goodness of fit: p values of curves the model describes are not small") {
  // 12 simulated N, B, K channels: the p value is ~uniform, so its median lies in [0.1, 0.9]
  // (outside with probability < 1e-3) and at most one is below 1e-3 (two: probability ~7e-5).
  std::vector<double> p;
  int flagged = 0;
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    const auto x = simulate_axis(nbk(), seed);
    const auto series = PhaseSeries::from_rate(x, kTau0);
    const AllanCurve curve = compute_allan_curve(series, Statistic::oadev, TauSpec{}, 0.683);
    const NoiseFit f = fit_noise(curve, CurveSource{kTau0, series.size(), 0}, FitOptions{});
    p.push_back(f.joint->p_value);
    flagged += f.joint->p_value < kMisfitPValue;
  }
  std::sort(p.begin(), p.end());
  const double median = 0.5 * (p[5] + p[6]);
  INFO("median p " << median);
  CHECK(median > 0.1);
  CHECK(median < 0.9);
  CHECK(flagged <= 1);
}
