// The one-pass lag-1 ACF identification (acf_first_steps) against the exact one
// (identify_noise_with, long double on each averaged series): where the pass decides, it must
// decide exactly as the exact identification, for every statistic.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "../lib/src/noise_identification.hpp"  // internal interface under test
#include "sigmatau/allan_curve.hpp"
#include "sigmatau/phase_series.hpp"
#include "sigmatau/taus.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

/// Unit Gaussian noise (test_support.hpp's generator).
std::vector<double> white(std::size_t n, std::uint64_t seed) {
  return test::white(n, 0.0, 1.0, seed);
}

std::vector<double> cumulative(const std::vector<double>& v) {
  std::vector<double> out(v.size());
  double acc = 0;
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = acc += v[i];
  return out;
}

std::vector<std::int64_t> octaves(std::int64_t n) {
  std::vector<std::int64_t> m;
  for (std::int64_t f = 1; f < n / 2; f *= 2) m.push_back(f);
  return m;
}

/// Counts the factors the pass decided; every decision must equal the exact one for each
/// statistic (the clamping differs between them).
int check_against_exact(const PhaseSeries& series) {
  const std::vector<std::int64_t> m = octaves(series.size());
  const auto quick = detail::acf_first_steps(series, m);
  REQUIRE(quick.size() == m.size());
  int decided = 0;
  for (std::size_t t = 0; t < m.size(); ++t) {
    const std::int64_t points = detail::averaged_series_points(series, m[t]);
    if (points < detail::kMinAcfPoints) {
      CHECK_FALSE(quick[t].has_value());
      continue;
    }
    if (!quick[t]) continue;
    ++decided;
    std::vector<double> scratch(static_cast<std::size_t>(points));
    for (Statistic s : {Statistic::oadev, Statistic::mdev, Statistic::hdev, Statistic::ohdev,
                        Statistic::totdev}) {
      CAPTURE(m[t]);
      CAPTURE(to_string(s));
      const NoiseIdentification exact =
          detail::identify_noise_with(series, s, m[t], scratch.data());
      const NoiseIdentification fast = detail::acf_identification(*quick[t], s);
      CHECK(fast.alpha == exact.alpha);
      CHECK(fast.method == exact.method);
    }
  }
  return decided;
}

}  // namespace

TEST_CASE("the one-pass ACF identification decides as the exact one on white and random-walk FM") {
  constexpr std::size_t kSamples = 1 << 17;
  const auto w = white(kSamples, 31);
  // White FM: r1 ~ 0 at every factor, far from any boundary: every factor with >= 30 points
  // is decided by the pass (the speed of the exact path rests on it).
  const PhaseSeries white_fm = PhaseSeries::from_rate(w, 0.01);
  int all = 0;  // factors with >= 30 points
  for (const std::int64_t f : octaves(white_fm.size())) {
    all += detail::averaged_series_points(white_fm, f) >= detail::kMinAcfPoints ? 1 : 0;
  }
  CHECK(check_against_exact(white_fm) >= all - 2);
  // Random-walk FM: r1 ~ 1, one difference makes it white; decided after that difference.
  const PhaseSeries rw_fm = PhaseSeries::from_rate(cumulative(w), 0.01);
  CHECK(check_against_exact(rw_fm) >= all - 3);
  // White plus random-walk FM (the type changes along the curve).
  std::vector<double> mixed = cumulative(w);
  const auto w2 = white(kSamples, 32);
  for (std::size_t i = 0; i < mixed.size(); ++i) mixed[i] = w2[i] + 3e-3 * mixed[i];
  check_against_exact(PhaseSeries::from_rate(mixed, 0.01));
}

TEST_CASE("the one-pass ACF identification decides as the exact one on phase input") {
  constexpr std::size_t kSamples = 1 << 16;
  const auto w = white(kSamples, 41);
  check_against_exact(PhaseSeries::from_phase(w, 1.0));              // white PM
  check_against_exact(PhaseSeries::from_phase(cumulative(w), 1.0));  // white FM
  // A frequency offset 1e6 times the noise: the differenced series sits far from 0, where the
  // long double mean's rounding matters; the pass must then leave it or agree.
  std::vector<double> drift = cumulative(w);
  for (std::size_t i = 0; i < drift.size(); ++i) drift[i] += 1e6 * static_cast<double>(i);
  check_against_exact(PhaseSeries::from_phase(drift, 1.0));
}

TEST_CASE("the one-pass ACF identification leaves constant series to the exact one, and agrees "
          "with it on extreme ones") {
  const std::vector<double> constant(5000, 2.5);
  const PhaseSeries flat = PhaseSeries::from_rate(constant, 1.0);
  for (const auto& alpha : detail::acf_first_steps(flat, octaves(flat.size()))) {
    CHECK_FALSE(alpha.has_value());
  }
  // Samples whose squares leave the normal range (1e200^2 overflows, 1e-200^2 underflows) are
  // held divided by a power of two (phase_store.hpp value_scale_for), so the pass sees ordinary
  // values: where it decides, it must agree with the exact path, as on the unscaled series.
  for (const double scale : {1e200, 1e-200}) {
    CAPTURE(scale);
    auto w = white(5000, 51);
    for (double& v : w) v *= scale;
    const PhaseSeries series = PhaseSeries::from_rate(w, 1.0);
    CHECK(check_against_exact(series) >= 0);
    const PhaseSeries unit = PhaseSeries::from_rate(white(5000, 51), 1.0);
    CHECK(detail::acf_first_steps(series, octaves(series.size())) ==
          detail::acf_first_steps(unit, octaves(unit.size())));
  }
}

TEST_CASE("curves with the identification pass on a spare thread equal the one-thread curves") {
  // compute_allan_curves runs acf_first_steps beside the sweep when there are fewer curves than
  // threads, once per channel for all its statistics, and keeps the OADEV sums with the phase
  // for TOTDEV's interior (either may come first): every point (deviation, alpha, method, EDF,
  // interval) must equal that of the statistic computed alone on a series of its own (nothing
  // shared with the other statistics).
  const auto y = white(200000, 77);
  const std::vector<Statistic> stats = {Statistic::oadev, Statistic::mdev, Statistic::totdev,
                                        Statistic::ohdev};
  const TauSpec taus = parse_tau_spec("octave");
  for (const unsigned threads : {1u, 3u, 8u}) {
    const PhaseSeries series = PhaseSeries::from_rate(y, 0.01);
    const auto curves = compute_allan_curves({series}, stats, taus, 0.683, threads);
    REQUIRE(curves.size() == 1);
    for (std::size_t s = 0; s < stats.size(); ++s) {
      INFO("threads " << threads << ", " << to_string(stats[s]));
      const PhaseSeries alone = PhaseSeries::from_rate(y, 0.01);
      const AllanCurve serial = compute_allan_curve(alone, stats[s], taus, 0.683);
      const AllanCurve& c = curves[0][s];
      REQUIRE(c.points.size() == serial.points.size());
      for (std::size_t i = 0; i < c.points.size(); ++i) {
        const CurvePoint& a = c.points[i];
        const CurvePoint& b = serial.points[i];
        CHECK(a.value.m == b.value.m);
        CHECK(a.value.dev == b.value.dev);
        CHECK(a.confidence.noise.alpha == b.confidence.noise.alpha);
        CHECK(a.confidence.noise.method == b.confidence.noise.method);
        CHECK(a.confidence.edf == b.confidence.edf);
        CHECK(a.confidence.interval.low == b.confidence.interval.low);
        CHECK(a.confidence.interval.high == b.confidence.interval.high);
      }
    }
  }
}
