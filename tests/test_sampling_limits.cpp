// The accepted rates and times (sampling_limits.hpp, issue 28): the checks refuse what is
// outside with the field named, and inside, up to both ends, the results scale exactly with the
// rate (a rate of 1e80 Hz gave noise terms of 0 with NaN intervals and p = nan before).
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "sigmatau/allan_curve.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/fit.hpp"
#include "sigmatau/phase_series.hpp"
#include "sigmatau/psd.hpp"
#include "sigmatau/sampling_limits.hpp"
#include "test_support.hpp"

using namespace sigmatau;
using sigmatau::test::rel;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<double> white(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<double> x(n);
  for (double& v : x) v = noise(rng);
  return x;
}

/// The joint fit's N of `x` read at `rate_hz`, times sqrt(rate_hz): the same number at every
/// rate, since the deviations are the same numbers and only the taus scale.
double scaled_n(const std::vector<double>& x, double rate_hz) {
  const auto series = PhaseSeries::from_rate(x, 1 / rate_hz);
  const auto curve = compute_allan_curve(series, Statistic::oadev, TauSpec{}, 0.683);
  const NoiseFit f = fit_noise(curve, CurveSource{1 / rate_hz, series.size(), 0}, FitOptions{});
  REQUIRE(f.joint);
  CHECK(std::isfinite(f.joint->p_value));
  const ParameterEstimate& n = f.joint->parameter(NoiseTerm::white);
  REQUIRE(n.in_model);
  CHECK(std::isfinite(n.ci_low));
  CHECK(std::isfinite(n.ci_high));
  return n.value * std::sqrt(rate_hz);
}

/// The PSD's noise density of `x` read at `rate_hz` over the band 0.01 to 0.4 of the rate,
/// times sqrt(rate_hz) (the level is 2 sigma^2 / f_s, so N = sigma / sqrt(f_s)). The band is
/// given: the automatic band's log bins are aligned to absolute decades of Hz, so it may pick
/// other bins at another rate.
double scaled_density(const std::vector<double>& x, double rate_hz) {
  const PsdCurve psd = welch_psd(x, rate_hz, WelchOptions{});
  const NoiseDensity n = noise_density(psd, std::make_pair(0.01 * rate_hz, 0.4 * rate_hz));
  CHECK(std::isfinite(n.ci_low));
  CHECK(std::isfinite(n.ci_high));
  return n.value * std::sqrt(rate_hz);
}

}  // namespace

TEST_CASE("rates, intervals and times outside the accepted ranges are refused, naming the field") {
  for (const double bad : {0.0, -1.0, 1e-10, 1e13, 1e80, kInf, kNaN}) {
    INFO("rate " << bad);
    CHECK_THROWS_WITH_AS(checked_rate_hz(bad, "rate_hz"),
                         doctest::Contains("rate_hz must be a rate from 1e-09 Hz to 1e+12 Hz"),
                         Error);
  }
  CHECK(checked_rate_hz(kMinRateHz, "rate_hz") == kMinRateHz);
  CHECK(checked_rate_hz(kMaxRateHz, "rate_hz") == kMaxRateHz);
  // The ends' intervals and rates are accepted both ways despite the rounding of 1 / x.
  CHECK_NOTHROW(checked_interval_s(1 / kMinRateHz, "tau0_s"));
  CHECK_NOTHROW(checked_interval_s(1 / kMaxRateHz, "tau0_s"));
  CHECK_NOTHROW(checked_rate_hz(1 / kMaxIntervalS, "rate_hz"));
  CHECK_NOTHROW(checked_rate_hz(1 / kMinTimeS, "rate_hz"));
  for (const double bad : {0.0, 1e-13, 1e10, 1e-80, kInf, kNaN}) {
    INFO("interval " << bad);
    CHECK_THROWS_WITH_AS(checked_interval_s(bad, "tau0_s"),
                         doctest::Contains("tau0_s must be a sample interval from 1e-12 s to 1e+09 s"),
                         Error);
  }
  CHECK(checked_interval_s(1e-12, "tau0_s") == 1e-12);
  CHECK(checked_interval_s(1e9, "tau0_s") == 1e9);
  for (const double bad : {0.0, 1e-300, 1e19, 1e300, kInf, kNaN}) {
    INFO("time " << bad);
    CHECK_THROWS_WITH_AS(checked_time_s(bad, "t_ref_s"),
                         doctest::Contains("t_ref_s must be a time from 1e-12 s to 1e+18 s"), Error);
  }
}

TEST_CASE("a time is turned into samples only while the count fits: 2^53 at most") {
  CHECK(checked_samples(10, 100, "trim_s") == 1000);
  CHECK(checked_samples(0, 100, "trim_s") == 0);
  CHECK(checked_samples(kMaxSampleCount / 1e6, 1e6, "trim_s") == std::int64_t{1} << 53);
  // 1e300 s became -2^63 samples (llround out of range) before: a negative trim.
  CHECK_THROWS_WITH_AS(checked_samples(1e300, 100, "trim_s"),
                       doctest::Contains("trim_s: 1e+300 s at 100 Hz is 1e+302 samples, more than "
                                         "any log holds"),
                       Error);
  CHECK_THROWS_AS(checked_samples(-1, 100, "trim_s"), Error);
  CHECK_THROWS_AS(checked_samples(kNaN, 100, "trim_s"), Error);
}

TEST_CASE("the noise fit and the PSD scale exactly with the rate up to both ends of the range") {
  const std::vector<double> x = white(20000, 3);
  const double n1 = scaled_n(x, 1.0);
  const double d1 = scaled_density(x, 1.0);
  for (const double rate : {kMinRateHz, 1e-3, 1e3, kMaxRateHz}) {
    INFO("rate " << rate << " Hz");
    // The taus are m / rate, each rounded once, so fit and PSD see the same numbers to an ulp;
    // measured: within 7e-16 of the rate-1 values at every rate here. 1e-9 leaves room for
    // another compiler's rounding and still fails on any real scaling error.
    CHECK(scaled_n(x, rate) == rel(n1, 1e-9));
    CHECK(scaled_density(x, rate) == rel(d1, 1e-9));
  }
  // Beyond the range the same fit reads N = 0 with NaN intervals (the design's tau^-2 squared
  // underflows): the reason for the limit, kept visible here.
  CHECK_THROWS_AS(PhaseSeries::from_rate(x, 1e-80), Error);
}
