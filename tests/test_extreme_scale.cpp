// Finite but extreme samples (issue 28): values of order 1e-200 gave OADEV exactly 0 (their
// squares underflow; 5e-5 off already at 1e-160), and from about 1e155 up the squares overflow
// ("deviation must be finite and >= 0, got -nan"). Logs beyond about 1e-100..1e100 are now
// computed divided by a power of two and the deviations multiplied back; a PSD, whose values are
// squares of the samples, is refused with the supported range where it is not a double.
//
// Tolerance 1e-12 (relative), and why: the scaled logs are the unit-scale values times a decimal
// factor, which rounds each value by up to 2^-53 relative; a deviation is a root mean square of
// differences of such values, so it moves by about that much (measured: below 1e-15). Noise types
// and EDFs, which depend on ratios only, must be equal.
#include <cmath>
#include <string>
#include <vector>

#include "sigmatau/allan_curve.hpp"
#include "sigmatau/allan_out_of_core.hpp"
#include "sigmatau/allan_segments.hpp"
#include "sigmatau/allan_stream.hpp"
#include "sigmatau/fit.hpp"
#include "sigmatau/psd.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

constexpr double kRtol = 1e-12;
constexpr double kScales[] = {1e-200, 1e-160, 1e155, 1e300};

std::vector<double> times(std::vector<double> v, double scale) {
  for (double& x : v) x *= scale;
  return v;
}

TauSpec octave() {
  TauSpec taus;
  taus.kind = TauSpec::Kind::octave;
  return taus;
}

void check_scaled(const AllanCurve& unit, const AllanCurve& scaled, double scale) {
  REQUIRE(unit.points.size() == scaled.points.size());
  REQUIRE(!unit.points.empty());
  for (std::size_t i = 0; i < unit.points.size(); ++i) {
    const CurvePoint& a = unit.points[i];
    const CurvePoint& b = scaled.points[i];
    CAPTURE(a.value.m);
    CHECK(a.value.m == b.value.m);
    CHECK(a.value.n_terms == b.value.n_terms);
    CHECK(a.confidence.noise.alpha == b.confidence.noise.alpha);
    CHECK(a.confidence.edf == b.confidence.edf);
    SIGMATAU_CHECK_REL(b.value.dev / scale, a.value.dev, kRtol);
    SIGMATAU_CHECK_REL(b.confidence.interval.low / scale, a.confidence.interval.low, kRtol);
    SIGMATAU_CHECK_REL(b.confidence.interval.high / scale, a.confidence.interval.high, kRtol);
  }
}

}  // namespace

TEST_CASE("deviations of extreme but finite samples are the unit-scale ones times the scale") {
  const std::vector<double> y = test::white(4096, 0.25, 1.0, 7);
  for (const DataKind kind : {DataKind::rate, DataKind::phase}) {
    const PhaseSeries unit_series = PhaseSeries::from_samples(y, kind, 0.01);
    for (const double scale : kScales) {
      CAPTURE(to_string(kind));
      CAPTURE(scale);
      const PhaseSeries series = PhaseSeries::from_samples(times(y, scale), kind, 0.01);
      CHECK(std::isfinite(series.mean_rate()));
      for (const Statistic statistic :
           {Statistic::adev, Statistic::oadev, Statistic::mdev, Statistic::tdev, Statistic::hdev,
            Statistic::ohdev, Statistic::totdev}) {
        CAPTURE(to_string(statistic));
        const AllanCurve unit = compute_allan_curve(unit_series, statistic, octave(), 0.683);
        check_scaled(unit, compute_allan_curve(series, statistic, octave(), 0.683), scale);
        // The out-of-core identification reads the same (scaled) phase.
        check_scaled(unit,
                     compute_allan_curve_bounded(series, statistic, octave(), 0.683,
                                                 spilled_storage()),
                     scale);
      }
      if (kind == DataKind::rate) {
        SIGMATAU_CHECK_REL(series.mean_rate() / scale, unit_series.mean_rate(), kRtol);
      }
    }
  }
}

TEST_CASE("ordinary magnitudes are held unscaled: 1e-100 and 1e100 give the scaled results") {
  // The scale is 1 from about 1.1e-100 to 8.7e99 (phase_store.hpp), so these logs take the
  // unscaled path; their results are still the unit-scale ones times the factor.
  const std::vector<double> y = test::white(2048, 0.0, 1.0, 11);
  const PhaseSeries unit_series = PhaseSeries::from_rate(y, 1.0);
  for (const double scale : {1e-99, 1e99}) {
    CAPTURE(scale);
    const AllanCurve unit = compute_allan_curve(unit_series, Statistic::oadev, octave(), 0.683);
    check_scaled(unit,
                 compute_allan_curve(PhaseSeries::from_rate(times(y, scale), 1.0),
                                     Statistic::oadev, octave(), 0.683),
                 scale);
  }
}

TEST_CASE("segmented curves of extreme samples pool without overflow") {
  const std::vector<double> a = test::white(3000, 0.0, 1.0, 3);
  const std::vector<double> b = test::white(2000, 0.0, 1.0, 4);
  const std::vector<PhaseSeries> unit{PhaseSeries::from_rate(a, 1.0), PhaseSeries::from_rate(b, 1.0)};
  for (const double scale : kScales) {
    CAPTURE(scale);
    const std::vector<PhaseSeries> scaled{PhaseSeries::from_rate(times(a, scale), 1.0),
                                          PhaseSeries::from_rate(times(b, scale), 1.0)};
    for (const Statistic statistic : {Statistic::oadev, Statistic::totdev}) {
      check_scaled(compute_segmented_allan_curve(unit, statistic, octave(), 0.683),
                   compute_segmented_allan_curve(scaled, statistic, octave(), 0.683), scale);
    }
  }
}

TEST_CASE("the stream mode on extreme samples gives the unit-scale curves times the scale") {
  const std::vector<double> y = test::white(20000, 0.5, 1.0, 5);
  StreamSettings settings;
  settings.statistics = {Statistic::adev, Statistic::oadev, Statistic::mdev, Statistic::hdev};
  settings.taus = octave();
  const auto curves = [&](const std::vector<double>& values) {
    AllanStream stream(DataKind::rate, 0.01, settings);
    stream.add(values);
    return stream.curves(0.683);
  };
  const auto unit = curves(y);
  for (const double scale : kScales) {
    CAPTURE(scale);
    const auto scaled = curves(times(y, scale));
    REQUIRE(scaled.size() == unit.size());
    for (std::size_t s = 0; s < unit.size(); ++s) check_scaled(unit[s], scaled[s], scale);
  }
}

TEST_CASE("a PSD of extreme samples is the scaled one where a double holds it, else refused") {
  const std::vector<double> y = test::white(8192, 0.0, 1.0, 9);
  WelchOptions options;
  options.segment_length = 1024;
  const PsdCurve unit = welch_psd(y, 100.0, options);
  // A PSD of order 1e200 and 1e-200 unit^2/Hz is representable: scaled exactly as the squares.
  for (const double scale : {1e-100, 1e100}) {
    CAPTURE(scale);
    const PsdCurve scaled = welch_psd(times(y, scale), 100.0, options);
    REQUIRE(scaled.psd.size() == unit.psd.size());
    for (std::size_t k = 1; k < unit.psd.size(); ++k) {
      // Relative error of a square: twice that of the values (see the file comment).
      SIGMATAU_CHECK_REL(scaled.psd[k] / scale / scale, unit.psd[k], 2 * kRtol);
    }
  }
  // Squares of 1e-160 .. 1e300 are not doubles (or only subnormal ones): a clear error instead of
  // zeros, infinities or a PSD that lost its digits.
  for (const double scale : kScales) {
    CAPTURE(scale);
    try {
      (void)welch_psd(times(y, scale), 100.0, options);
      FAIL("no error for a PSD out of range");
    } catch (const Error& e) {
      CHECK(std::string(e.what()).find("beyond the range of a double") != std::string::npos);
    }
  }
}

TEST_CASE("the noise fit of extreme samples gives the unit-scale model with its terms scaled") {
  // The fit works with fourth powers of the deviations: before, 1e100 kept a wrong model and
  // 1e-100 ended in "AVAR covariance is not positive definite".
  const std::vector<double> y = test::white(20000, 0.0, 1.0, 13);
  const CurveSource source{0.01, 20001, 0};
  FitOptions options;
  options.method = FitMethod::both;
  const auto fit = [&](double scale) {
    const PhaseSeries series = PhaseSeries::from_rate(times(y, scale), 0.01);
    return fit_noise(compute_allan_curve(series, Statistic::oadev, octave(), 0.683), source,
                     options);
  };
  const NoiseFit unit = fit(1.0);
  for (const double scale : {1e-200, 1e-100, 1e100, 1e300}) {
    CAPTURE(scale);
    const NoiseFit scaled = fit(scale);
    for (const auto* pair : {&unit.joint, &unit.slopes}) {
      const std::optional<ChannelFit>& a = *pair;
      const std::optional<ChannelFit>& b = pair == &unit.joint ? scaled.joint : scaled.slopes;
      REQUIRE(a.has_value());
      REQUIRE(b.has_value());
      CHECK(a->model_terms == b->model_terms);
      for (std::size_t k = 0; k < a->parameters.size(); ++k) {
        const ParameterEstimate& p = a->parameters[k];
        const ParameterEstimate& q = b->parameters[k];
        CHECK(p.in_model == q.in_model);
        SIGMATAU_CHECK_REL(q.upper_bound / scale, p.upper_bound, kRtol);
        if (p.in_model) SIGMATAU_CHECK_REL(q.value / scale, p.value, kRtol);
      }
    }
  }
}

TEST_CASE("curve read-outs standing in for a rejected fit scale with extreme samples too") {
  // White noise plus a sinusoid of 4x its standard deviation, period 2000 samples: the bump no
  // term describes gets the joint fit rejected or contradicted, so NoiseFit::readings stand in.
  std::vector<double> y = test::white(40000, 0.0, 1.0, 19);
  for (std::size_t i = 0; i < y.size(); ++i)
    y[i] += 4.0 * std::sin(2.0 * 3.141592653589793 * static_cast<double>(i) / 2000.0);
  const CurveSource source{0.01, 40001, 0};
  FitOptions options;
  const auto fit = [&](double scale) {
    const PhaseSeries series = PhaseSeries::from_rate(times(y, scale), 0.01);
    return fit_noise(compute_allan_curve(series, Statistic::oadev, octave(), 0.683), source,
                     options);
  };
  const NoiseFit unit = fit(1.0);
  REQUIRE(unit.readings.has_value());
  for (const double scale : {1e-200, 1e300}) {
    CAPTURE(scale);
    const NoiseFit scaled = fit(scale);
    REQUIRE(scaled.readings.has_value());
    CHECK(scaled.readings_reason == unit.readings_reason);
    REQUIRE(scaled.readings->parameters.size() == unit.readings->parameters.size());
    for (std::size_t k = 0; k < unit.readings->parameters.size(); ++k) {
      const ParameterEstimate& p = unit.readings->parameters[k];
      const ParameterEstimate& q = scaled.readings->parameters[k];
      if (p.in_model) SIGMATAU_CHECK_REL(q.value / scale, p.value, kRtol);
    }
    REQUIRE(scaled.joint.has_value());
    REQUIRE(scaled.joint->contradictions.size() == unit.joint->contradictions.size());
    for (std::size_t k = 0; k < unit.joint->contradictions.size(); ++k) {
      SIGMATAU_CHECK_REL(scaled.joint->contradictions[k].reported / scale,
                         unit.joint->contradictions[k].reported, kRtol);
      SIGMATAU_CHECK_REL(scaled.joint->contradictions[k].curve / scale,
                         unit.joint->contradictions[k].curve, kRtol);
    }
  }
}

TEST_CASE("a deviation beyond the largest double is an Error naming the statistic and tau") {
  // Phase points of 1e300 s one nanosecond apart: OADEV of order 1e309, not a double. The
  // message said "deviation must be finite and >= 0, got inf".
  std::vector<double> x = test::white(100, 0.0, 1.0, 17);
  x = times(x, 1e300);
  const PhaseSeries series = PhaseSeries::from_phase(x, 1e-9);
  CHECK_THROWS_WITH_AS(compute_allan_curve(series, Statistic::oadev, octave(), 0.683),
                       doctest::Contains("oadev at tau = 1e-09 s is beyond the largest double"),
                       Error);
}
