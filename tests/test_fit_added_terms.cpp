// Terms real sensors add (issue 24): when no model of the five IEEE terms describes a curve,
// the joint fit adds Gauss-Markov terms and a sinusoid (fit_added_terms.cpp) with weights that
// include a relative model error (fit_model_error.cpp), and leaves out the shortest taus a
// sensor's filter bends. Checked on exact curves (each point the exact sampled AVAR of the
// truth, EDF N/m as a long log's): the truth is a model the fit can state, so the search must
// find it to the precision of its refinement, and a curve no model states must be said so.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "../../lib/src/fit_added_terms.hpp"  // internal interface under test
#include "exact_curve.hpp"
#include "sigmatau/allan_curve.hpp"
#include "sigmatau/fit.hpp"
#include "test_support.hpp"

namespace {

using namespace sigmatau;

constexpr double kTau0 = 0.01;  // 100 Hz
constexpr double kDegPerHour = 3.14159265358979323846 / 180 / 3600;  // rad/s
/// 2^20 samples (2.9 h at 100 Hz): 19 octave points, EDFs from 1e6 down, as the ADIS16405 log.
constexpr std::int64_t kSamples = std::int64_t{1} << 20;

NoiseFit fit_curve(const AllanCurve& curve) {
  return fit_noise(curve, CurveSource{kTau0, kSamples + 1, 0}, FitOptions{});
}

/// The largest |model / curve - 1| over the fitted points.
double largest_departure(const NoiseFit& fit, const AllanCurve& curve) {
  const std::vector<double> model =
      model_deviation(*fit.joint, curve, CurveSource{kTau0, kSamples + 1, 0}, FitOptions{});
  double worst = 0;
  for (std::size_t j = 0; j < curve.points.size(); ++j) {
    if (std::isfinite(model[j])) worst = std::max(worst, std::abs(model[j] / curve.points[j].value.dev - 1));
  }
  return worst;
}

}  // namespace

TEST_CASE("a Gauss-Markov bump no IEEE model describes is found at its correlation time") {
  // White noise with a GM bump peaking near 1.9 T_c = 19 s, above the white line there
  // (N^2 / tau = 1e-8 / 19 against the GM's ~0.34 sigma^2 = 3.4e-9 at its peak).
  NoiseTerms truth;
  truth.white = 1e-4;
  truth.gauss_markov = {GaussMarkov{1e-4, 10.0}};
  const AllanCurve curve = test::exact_oadev_curve(truth, kSamples, kTau0);
  const NoiseFit fit = fit_curve(curve);
  REQUIRE(fit.joint);
  REQUIRE(fit.joint->gauss_markov.size() >= 1);
  // The exact curve holds the truth: the refinement ends within 1e-5 of a quarter-octave grid
  // step, so T_c and sigma come back to well within 1 % (what remains: the NNLS and the
  // weights' convergence).
  const auto& gm = fit.joint->gauss_markov.back();
  CHECK(gm.tau_c_s == doctest::Approx(10.0).epsilon(0.01));
  CHECK(gm.sigma == doctest::Approx(1e-4).epsilon(0.01));
  CHECK(fit.joint->parameter(NoiseTerm::white).value == doctest::Approx(1e-4).epsilon(0.01));
  CHECK(largest_departure(fit, curve) < 1e-3);
  CHECK(fit.joint->p_value > kMisfitPValue);
  CHECK(fit.joint->contradictions.empty());
  CHECK_FALSE(fit.readings);
}

TEST_CASE("a sinusoid's narrow bump is found at its frequency") {
  // A 0.5 Hz vibration of 5e-4 (rate unit) on white noise: its ADEV bump near 0.74 s stands
  // 3x above the white line there.
  NoiseTerms truth;
  truth.white = 1e-4;
  truth.sinusoid = Sinusoid{5e-4, 0.5, 0.0};
  const AllanCurve curve = test::exact_oadev_curve(truth, kSamples, kTau0);
  const NoiseFit fit = fit_curve(curve);
  REQUIRE(fit.joint);
  REQUIRE(fit.joint->sinusoid);
  // As above: the truth is on the curve, the refinement ends far within 1 % of it.
  CHECK(fit.joint->sinusoid->frequency_hz == doctest::Approx(0.5).epsilon(0.01));
  CHECK(fit.joint->sinusoid->amplitude == doctest::Approx(5e-4).epsilon(0.01));
  CHECK(largest_departure(fit, curve) < 1e-3);
  CHECK(fit.joint->p_value > kMisfitPValue);
}

TEST_CASE("a curve the IEEE terms describe gets no added term and no model error") {
  NoiseTerms truth;
  truth.white = 1e-4;
  truth.bias_instability = 3e-5;
  truth.rate_random_walk = 1e-6;
  const NoiseFit fit = fit_curve(test::exact_oadev_curve(truth, kSamples, kTau0));
  REQUIRE(fit.joint);
  CHECK(fit.joint->gauss_markov.empty());
  CHECK_FALSE(fit.joint->sinusoid);
  CHECK(fit.joint->model_error == 0);
  CHECK(fit.joint->left_out_taus_s.empty());
}

TEST_CASE("a shortest tau bent away from every term is left out and said so") {
  // White noise whose first point stands 30 % above it, as a sensor's sampling can raise it: no
  // term raises m = 1 alone (quantization's 1/m^2 would raise m = 2 by a quarter as much), so
  // with EDF 1e6 there every model is rejected until that point is left out.
  NoiseTerms truth;
  truth.white = 1e-4;
  truth.rate_random_walk = 1e-6;
  AllanCurve curve = test::exact_oadev_curve(truth, kSamples, kTau0);
  curve.points.front().value.dev *= 1.3;
  const NoiseFit fit = fit_curve(curve);
  REQUIRE(fit.joint);
  REQUIRE(fit.joint->left_out_taus_s.size() == 1);
  CHECK(fit.joint->left_out_taus_s.front() == doctest::Approx(kTau0));
  CHECK(fit.joint->parameter(NoiseTerm::white).value == doctest::Approx(1e-4).epsilon(0.01));
  CHECK(largest_departure(fit, curve) < 1e-3);
  CHECK_FALSE(left_out_warning(*fit.joint, "gx").empty());
}

TEST_CASE("a vibration line, a filter and a slow rise are all found (the ADIS16405 accelerometer)") {
  // The model fitted to the ADIS16405 accel_x log (bench/results_fit_real.md) taken as the
  // truth: a sensor filter (GM of 10 ms), a 0.56 Hz vibration (its bump near 0.66 s), GMs of 2
  // and 20 s and a rate random walk. No IEEE model comes near it (model error 0.65). When each
  // addition was settled with the IEEE subset chosen under the previous model's weights only,
  // the search ended with no added term (model error 0.43, 74 % off); settled also with every
  // IEEE candidate (and the unneeded ones dropped after), it finds all but the 2 s GM.
  NoiseTerms truth;
  truth.rate_random_walk = 4.2e-4;
  truth.gauss_markov = {GaussMarkov{3.2e-2, 0.01}, GaussMarkov{2.2e-3, 2.0}, GaussMarkov{4.2e-3, 20.0}};
  truth.sinusoid = Sinusoid{9.4e-3, 0.56, 0.0};
  const AllanCurve curve = test::exact_oadev_curve(truth, kSamples, kTau0);
  const NoiseFit fit = fit_curve(curve);
  REQUIRE(fit.joint);
  CHECK(fit.joint->p_value > kMisfitPValue);
  REQUIRE(fit.joint->sinusoid);
  CHECK(fit.joint->sinusoid->frequency_hz == doctest::Approx(0.56).epsilon(0.01));
  REQUIRE_FALSE(fit.joint->gauss_markov.empty());
  // The filter's GM carries the shortest taus (EDF ~1e6): found to well within 5 %.
  CHECK(fit.joint->gauss_markov.front().tau_c_s == doctest::Approx(0.01).epsilon(0.05));
  // The 2 s GM's bump is small beside the vibration's and the 20 s one's: the fit may trade it
  // for B where the curve is flat. Measured: within 1.1 % up to 164 s (EDF >= 64), 4.2 % at
  // most beyond, where the estimates' own scatter (1 / sqrt(2 EDF): 12-35 %) is far larger.
  const std::vector<double> model =
      model_deviation(*fit.joint, curve, CurveSource{kTau0, kSamples + 1, 0}, FitOptions{});
  for (std::size_t j = 0; j < curve.points.size(); ++j) {
    if (!std::isfinite(model[j]) || curve.points[j].confidence.edf < 64) continue;
    CHECK(std::abs(model[j] / curve.points[j].value.dev - 1) < 0.02);
  }
  CHECK(largest_departure(fit, curve) < 0.05);
}

TEST_CASE("two additions at once are tried when no single one lowers the criterion") {
  // The curve of the case above with every tau kept (the search alone, without fit.cpp's
  // leaving out of short taus). One term at a time, the search reaches a 34 ms GM and the
  // sinusoid (model error 0.126), and then no single further GM lowers the criterion (each,
  // weighed alone, the IEEE terms trade away); two GMs at once (near 8 ms and 15 s) lower it by
  // 37, to model error 0.03 (measured). A model error below 0.05 is only reached with the pair.
  NoiseTerms truth;
  truth.rate_random_walk = 4.2e-4;
  truth.gauss_markov = {GaussMarkov{3.2e-2, 0.01}, GaussMarkov{2.2e-3, 2.0}, GaussMarkov{4.2e-3, 20.0}};
  truth.sinusoid = Sinusoid{9.4e-3, 0.56, 0.0};
  const AllanCurve curve = test::exact_oadev_curve(truth, kSamples, kTau0);
  const CurveSource source{kTau0, kSamples + 1, 0};
  std::vector<std::int64_t> ms;
  NoiseTerms ones;  // each term's AVAR at unit parameter
  ones.quantization = ones.white = ones.bias_instability = ones.rate_random_walk = ones.rate_ramp = 1.0;
  detail::Design d;
  d.a.resize(static_cast<Eigen::Index>(curve.points.size()), detail::kTermCount);
  d.v.resize(static_cast<Eigen::Index>(curve.points.size()));
  for (std::size_t j = 0; j < curve.points.size(); ++j) {
    const auto row = static_cast<Eigen::Index>(j);
    const std::int64_t m = curve.points[j].value.m;
    ms.push_back(m);
    d.v(row) = curve.points[j].value.dev * curve.points[j].value.dev;
    for (const NoiseTerm term : kFitTerms) {
      d.a(row, detail::term_index(term)) = sampled_avar(ones, term, m, Sampling{kTau0, 0, false});
    }
  }
  const auto basis = detail::covariance_basis(ms, source.n_phase_points, kTau0);
  const detail::Mask candidates = (1u << detail::kTermCount) - 1;
  const detail::Mask base = detail::select_model(d, candidates, *basis);
  const detail::ExtendedModel ext = detail::extend_with_added_terms(d, ms, source, base, candidates, basis);
  CHECK(ext.tau_c_s.size() == 3);
  REQUIRE(ext.sinusoid_hz);
  CHECK(*ext.sinusoid_hz == doctest::Approx(0.56).epsilon(0.05));
  CHECK(ext.kappa < 0.05);
}

TEST_CASE("a term the fit puts at 0 beside an added term is not listed in the model") {
  // White noise through a 20 ms first-order filter (a GM of a few tau0 carries the white level)
  // plus flicker: the search offers every IEEE candidate beside the GM, and N comes out at 0.
  // Listed, it read as a model N = 0 [0, bound] (bench/fit_added_terms_sim.py's filtered-white
  // profile, seeds 1-10: 6 of 10 wrong models were this); every listed term must carry a value.
  NoiseTerms truth;
  truth.gauss_markov = {GaussMarkov{45 * kDegPerHour, 0.02}};
  truth.bias_instability = 3 * kDegPerHour;
  const AllanCurve curve = test::exact_oadev_curve(truth, kSamples, kTau0);
  const NoiseFit fit = fit_curve(curve);
  REQUIRE(fit.joint);
  REQUIRE(fit.joint->gauss_markov.size() >= 1);
  for (const ParameterEstimate& p : fit.joint->parameters) {
    if (p.in_model) {
      CHECK(p.value > 0);
    } else {
      CHECK(p.upper_bound >= 0);
    }
  }
  CHECK_FALSE(fit.joint->parameter(NoiseTerm::white).in_model);
}
