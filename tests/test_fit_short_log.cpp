// What the fit reports beside its terms: the curve's own minimum with B (review F #6), where
// each kept term carries the curve, and the short-log warning on a K kept where the curve shows
// no floor (review F #2); the display unit of each term (review G #4).
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "sigmatau/allan_curve.hpp"
#include "sigmatau/display_units.hpp"
#include "sigmatau/fit.hpp"
#include "sigmatau/units.hpp"
#include "exact_curve.hpp"
#include "test_support.hpp"

namespace {

using namespace sigmatau;

constexpr double kTau0 = 0.01;  // 100 Hz
/// 2^16 samples (11 min at 100 Hz): 15 octave points, a quick covariance basis.
constexpr std::int64_t kSamples = std::int64_t{1} << 16;

NoiseFit fit_exact(const NoiseTerms& truth, FitMethod method) {
  const AllanCurve curve = test::exact_oadev_curve(truth, kSamples, kTau0);
  FitOptions options;
  options.method = method;
  return fit_noise(curve, CurveSource{kTau0, kSamples + 1, 0}, options);
}

/// Scaled so that N, B and K each carry part of an 11-minute curve: N up to ~0.25 s (N^2 / tau
/// above the floor (0.664 B)^2 = 4e-8), B's floor up to ~30 s, K (AVAR K^2 tau / 3) beyond.
NoiseTerms nbk() {
  NoiseTerms t;
  t.white = 1e-4;
  t.bias_instability = 3e-4;
  t.rate_random_walk = 6e-5;
  return t;
}

/// White noise and a rate random walk, no flicker: the curve falls and rises with no floor.
/// K^2 tau / 3 passes N^2 / tau at tau = sqrt(3) N / K: 28 s for `k` = 2.5e-5 (K carries the
/// last three octave points, 40.96-163.84 s, as on a short log), 6.9 s for 1e-4 (five points).
NoiseTerms nk(double k) {
  NoiseTerms t;
  t.white = 4e-4;
  t.rate_random_walk = k;
  return t;
}

}  // namespace

TEST_CASE("a default ParameterEstimate has NaN for what does not apply, as documented") {
  const ParameterEstimate p;
  CHECK(std::isnan(p.tau_min_s));
  CHECK(std::isnan(p.adev_min));
  CHECK(std::isnan(p.edf));
  CHECK(p.leading_points == 0);
}

TEST_CASE("B carries the curve's own minimum (value and tau), for both methods") {
  const AllanCurve curve = test::exact_oadev_curve(nbk(), kSamples, kTau0);
  double dev_min = INFINITY, tau_min = 0;
  for (const auto& p : curve.points) {
    if (p.value.dev < dev_min) {
      dev_min = p.value.dev;
      tau_min = p.value.tau_s;
    }
  }
  const NoiseFit fit = fit_exact(nbk(), FitMethod::both);
  for (const ChannelFit* f : {&*fit.joint, &*fit.slopes}) {
    const auto& b = f->parameter(NoiseTerm::bias_instability);
    CHECK(b.adev_min == dev_min);  // copied from the curve, not computed
    CHECK(b.tau_min_s == tau_min);
    // Only B has them.
    CHECK(std::isnan(f->parameter(NoiseTerm::white).adev_min));
    CHECK(std::isnan(f->parameter(NoiseTerm::rate_random_walk).tau_min_s));
  }
  // The minimum is the data's, not the model's floor: 0.664 B from the fit differs from it on a
  // curve where N and K still add at the minimum.
  const auto& b = fit.joint->parameter(NoiseTerm::bias_instability);
  CHECK(b.adev_min > kFlickerFloorFactor * b.value);
}

TEST_CASE("leading_points: each kept term carries a distinct part of the curve") {
  const NoiseFit fit = fit_exact(nbk(), FitMethod::joint);
  const ChannelFit& j = *fit.joint;
  REQUIRE(j.model_terms.size() == 3);
  int total = 0;
  for (const auto term : j.model_terms) {
    const int lead = j.parameter(term).leading_points;
    CHECK(lead >= 1);
    total += lead;
  }
  // At most every point is carried by one term (a point where none exceeds the rest is none's).
  CHECK(total <= j.points);
  CHECK(j.parameter(NoiseTerm::quantization).leading_points == 0);  // not in the model
}

TEST_CASE("a K kept from the last taus where the curve shows no floor is warned about") {
  const NoiseFit without = fit_exact(nk(2.5e-5), FitMethod::joint);
  const auto& k = without.joint->parameter(NoiseTerm::rate_random_walk);
  REQUIRE(k.in_model);
  REQUIRE_FALSE(without.joint->parameter(NoiseTerm::bias_instability).in_model);
  CHECK(k.leading_points <= kShortLogRisePoints);
  CHECK(rise_without_floor(*without.joint));
  const std::string w = short_log_warning(*without.joint, "gx");
  CHECK(w.find("gx: K is kept where the curve shows no bias-instability floor") == 0);
  CHECK(w.find("bench/results_fit_short_logs.md") != std::string::npos);

  // With a floor it is not.
  const NoiseFit with = fit_exact(nbk(), FitMethod::joint);
  REQUIRE(with.joint->parameter(NoiseTerm::rate_random_walk).in_model);
  CHECK_FALSE(rise_without_floor(*with.joint));
  CHECK(short_log_warning(*with.joint, "gx").empty());

  // Nor is a rise over more than kShortLogRisePoints taus: a K shown by the log's own slope (the
  // 2 h consumer accelerometer of bench_fit_accuracy hides its floor between N and K).
  const NoiseFit long_rise = fit_exact(nk(1e-4), FitMethod::joint);
  REQUIRE(long_rise.joint->parameter(NoiseTerm::rate_random_walk).in_model);
  CHECK(long_rise.joint->parameter(NoiseTerm::rate_random_walk).leading_points > kShortLogRisePoints);
  CHECK_FALSE(rise_without_floor(*long_rise.joint));
  CHECK(short_log_warning(*long_rise.joint, "gx").empty());

  // The slope read-outs are not judged by this rule (no leading points of their own model).
  const NoiseFit slopes = fit_exact(nk(2.5e-5), FitMethod::slopes);
  CHECK(short_log_warning(*slopes.slopes, "gx").empty());
}

TEST_CASE("display units: one spelling per term and sensor, each convertible from SI") {
  CHECK(display_unit(NoiseTerm::rate_ramp, Sensor::gyro) == "deg/h^2");
  CHECK(display_unit(NoiseTerm::rate_random_walk, Sensor::accel) == "m/s^3/sqrt(Hz)");
  CHECK(display_unit(NoiseTerm::rate_ramp, Sensor::accel) == "m/s^3");
  CHECK(display_unit(NoiseTerm::white, Sensor::gyro) == "deg/sqrt(h)");
  CHECK(display_unit(NoiseTerm::bias_instability, Sensor::accel) == "ug");
  const std::pair<NoiseTerm, const char*> kSi[] = {
      {NoiseTerm::quantization, "rad"},          {NoiseTerm::white, "rad/s/sqrt(Hz)"},
      {NoiseTerm::bias_instability, "rad/s"},    {NoiseTerm::rate_random_walk, "rad/s^2/sqrt(Hz)"},
      {NoiseTerm::rate_ramp, "rad/s^2"}};
  for (const auto& [term, si] : kSi) {
    // Throws when the dimensions differ: the display unit measures the same quantity.
    CHECK(convert(1.0, si, std::string(display_unit(term, Sensor::gyro))) > 0);
  }
  const std::pair<NoiseTerm, const char*> kSiAccel[] = {
      {NoiseTerm::quantization, "m/s"},          {NoiseTerm::white, "m/s^2/sqrt(Hz)"},
      {NoiseTerm::bias_instability, "m/s^2"},    {NoiseTerm::rate_random_walk, "m/s^3/sqrt(Hz)"},
      {NoiseTerm::rate_ramp, "m/s^3"}};
  for (const auto& [term, si] : kSiAccel) {
    CHECK(convert(1.0, si, std::string(display_unit(term, Sensor::accel))) > 0);
  }
}
