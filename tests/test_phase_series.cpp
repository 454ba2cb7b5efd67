// PhaseSeries: integration with the mean removed, double-double storage, window sums accurate to
// about one ulp of the window sum whatever the offset or the size of the phase, input checks.
// Exact references are computed in __float128 (113-bit significand, arithmetic from libgcc):
// the test inputs are chosen so that every reference sum is exactly representable there.
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "sigmatau/error.hpp"
#include "sigmatau/phase_series.hpp"
#include "test_support.hpp"

using namespace sigmatau;
using test::rel;

namespace {

__extension__ typedef __float128 Quad;

/// Unit in the last place of |v| (v != 0), as the ulp of the double nearest to v.
double ulp(double v) { return std::ldexp(1.0, std::ilogb(v) - 52); }

/// |computed - exact| in units of the ulp of the exact value rounded to double.
double ulps_off(double computed, Quad exact) {
  const double e = static_cast<double>(exact);
  if (e == 0.0) return computed == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
  const Quad diff = static_cast<Quad>(computed) - exact;
  return std::abs(static_cast<double>(diff)) / ulp(e);
}

/// A window sum is (hi difference, rounded) + (lo difference, rounded), then rounded: at most
/// about 1.5 ulp of the result plus ~2^-104 of the phase itself. 2 ulps is the bound we promise.
constexpr double kWindowUlps = 2.0;

/// Checks window_sum(k, m) against sum_{i=k+1}^{k+m} (y_i - ybar) computed exactly, for the
/// given factors and a spread of start points.
void check_window_sums(const PhaseSeries& series, const std::vector<double>& y,
                       std::initializer_list<std::int64_t> factors) {
  const double ybar = series.mean_rate();
  std::vector<Quad> x(y.size() + 1, 0);
  for (std::size_t i = 0; i < y.size(); ++i) x[i + 1] = x[i] + (static_cast<Quad>(y[i]) - ybar);
  double worst = 0.0;
  for (const std::int64_t m : factors) {
    for (std::int64_t k = 0; k + m < series.size(); k += 1 + series.size() / 997) {
      worst = std::max(worst, ulps_off(series.window_sum(k, m), x[k + m] - x[k]));
    }
  }
  INFO("worst window sum error: " << worst << " ulp");
  CHECK(worst <= kWindowUlps);
}

}  // namespace

TEST_CASE("rate samples become N = M + 1 phase points starting at exactly 0") {
  const std::vector<double> y = {3.0, 5.0, 1.0, 7.0};  // mean 4: x = 0 -1 0 -3 0
  const auto series = PhaseSeries::from_rate(y, 0.5);
  REQUIRE(series.size() == 5);
  CHECK(series.kind() == DataKind::rate);
  CHECK(series.tau0_s() == 0.5);
  CHECK(series.mean_rate() == 4.0);
  const double expected[] = {0, -1, 0, -3, 0};
  for (int k = 0; k < 5; ++k) CHECK(series.x(k) == expected[k]);
  CHECK(series.hi()[0] == 0.0);
  CHECK(series.lo()[0] == 0.0);
  CHECK(series.window_sum(1, 2) == -2.0);
  // Rate: a phase difference over m samples is m times a mean rate.
  CHECK(series.rate_scale(4) == 0.25);
}

TEST_CASE("increments and phase use the sample interval in rate_scale and mean_rate") {
  const std::vector<double> v = {3.0, 5.0, 1.0, 7.0};
  const auto inc = PhaseSeries::from_increments(v, 0.5);
  CHECK(inc.kind() == DataKind::increment);
  CHECK(inc.size() == 5);
  CHECK(inc.mean_rate() == 8.0);  // 4 per sample of 0.5 s
  CHECK(inc.rate_scale(4) == 0.5);  // 1 / (4 * 0.5 s)
  const auto ph = PhaseSeries::from_phase(v, 0.5);
  CHECK(ph.kind() == DataKind::phase);
  CHECK(ph.size() == 4);
  CHECK(ph.mean_rate() == 0.0);
  CHECK(ph.x(0) == 0.0);
  CHECK(ph.x(3) == 4.0);
  CHECK(ph.rate_scale(4) == 0.5);
  CHECK(PhaseSeries::from_samples(v, DataKind::phase, 0.5).size() == 4);
  CHECK(PhaseSeries::from_samples(v, DataKind::increment, 0.5).kind() == DataKind::increment);
}

TEST_CASE("the mean of a constant record is the constant itself, so the phase is exactly 0") {
  for (const double level : {0.1, -3.3e-7, 1e6 + 0.1, 6.02e23, 5e-324}) {
    const std::vector<double> y(12345, level);
    const auto series = PhaseSeries::from_rate(y, 1.0);
    CHECK(series.mean_rate() == level);
    for (std::int64_t k = 0; k < series.size(); ++k) {
      REQUIRE(series.hi()[k] == 0.0);
      REQUIRE(series.lo()[k] == 0.0);
    }
  }
}

TEST_CASE("the removed mean is accurate for data with a large offset") {
  // y = 1e9 + u, u uniform in [-1, 1): the mean is computed from exact differences to y_0, so it
  // is within a few ulps of 1e9 (ulp 1.2e-7) of the exact mean.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> y(100000);
  for (auto& v : y) v = 1e9 + u(rng);
  Quad sum = 0;
  for (const double v : y) sum += v;
  const double exact_mean = static_cast<double>(sum / static_cast<Quad>(y.size()));
  const auto series = PhaseSeries::from_rate(y, 1.0);
  CHECK(std::abs(series.mean_rate() - exact_mean) <= 2 * ulp(exact_mean));
}

TEST_CASE("window sums are accurate to about one ulp of the sum, whatever the offset") {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g(0.0, 1.0);
  SUBCASE("white noise on an offset of 1e6 times its amplitude") {
    std::vector<double> y(200000);
    for (auto& v : y) v = 1e6 + g(rng);
    check_window_sums(PhaseSeries::from_rate(y, 0.01), y, {1, 2, 7, 1000, 65536});
  }
  SUBCASE("rate random walk (the phase grows like N^1.5)") {
    std::vector<double> y(200000);
    double w = 0.0;
    for (auto& v : y) v = (w += g(rng));
    check_window_sums(PhaseSeries::from_rate(y, 0.01), y, {1, 3, 100, 50000});
  }
  SUBCASE("small values far from 1 (1e-12 rad per sample)") {
    std::vector<double> y(100000);
    for (auto& v : y) v = 1e-12 * (5.0 + g(rng));
    // tau0 = 1 s so that mean_rate() is the removed mean increment itself.
    check_window_sums(PhaseSeries::from_increments(y, 1.0), y, {1, 64, 4096});
  }
}

TEST_CASE("the double-double phase is normalised: |lo| <= ulp(hi) / 2") {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> y(100000);
  double w = 0.0;
  for (auto& v : y) v = 1e3 + (w += g(rng));
  const auto series = PhaseSeries::from_rate(y, 1.0);
  for (std::int64_t k = 1; k < series.size(); ++k) {
    const double hi = series.hi()[k];
    const double lo = series.lo()[k];
    if (hi == 0.0) {
      REQUIRE(lo == 0.0);
    } else {
      REQUIRE(std::abs(lo) <= 0.5 * ulp(hi));
    }
  }
}

TEST_CASE("phase input is stored as exactly x - x_0") {
  // Clock phase ~ 7.6e-7 s with 1e-11 s noise (like the Cs 5071A record) and an unnormalised
  // phase ramp: x - x_0 is not a double, but hi + lo holds it exactly.
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> x(50000);
  for (std::size_t k = 0; k < x.size(); ++k) {
    x[k] = 7.6e-7 + 1e-11 * g(rng) + 3.1e-13 * static_cast<double>(k);
  }
  const auto series = PhaseSeries::from_phase(x, 1.0);
  for (std::size_t k = 0; k < x.size(); ++k) {
    const Quad stored = static_cast<Quad>(series.hi()[k]) + series.lo()[k];
    REQUIRE(stored == static_cast<Quad>(x[k]) - static_cast<Quad>(x[0]));
  }
}

TEST_CASE("a non-finite sample is an Error naming its 0-based index") {
  std::vector<double> y(100, 1.0);
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(),
                           std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity()}) {
    y[37] = bad;
    for (const DataKind kind : {DataKind::rate, DataKind::increment, DataKind::phase}) {
      CHECK_THROWS_WITH_AS(PhaseSeries::from_samples(y, kind, 1.0),
                           doctest::Contains("sample 37 (0-based) is not finite"), Error);
    }
  }
  y[37] = 1.0;
  y[0] = std::numeric_limits<double>::quiet_NaN();
  for (const DataKind kind : {DataKind::rate, DataKind::increment, DataKind::phase}) {
    CHECK_THROWS_WITH_AS(PhaseSeries::from_samples(y, kind, 1.0),
                         doctest::Contains("sample 0 (0-based)"), Error);
  }
  // Finite rate samples whose sum overflows are refused, not turned into NaN.
  const std::vector<double> huge = {1e308, -1e308, 1e308};
  CHECK_THROWS_WITH_AS(PhaseSeries::from_rate(huge, 1.0), doctest::Contains("too large"), Error);
  // Phase points are held divided by a power of two (issue 28): their differences no longer
  // overflow (x_1 - x_0 = -2e308 is held as -2e308 / 2^1023).
  const auto phase = PhaseSeries::from_phase(huge, 1.0);
  CHECK(phase.x(1) == -2 * (1e308 / 0x1p1023));
}

TEST_CASE("a sample interval that is not a finite number > 0 is an Error") {
  const std::vector<double> y(10, 1.0);
  for (const double tau0 : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(),
                            std::numeric_limits<double>::infinity()}) {
    for (const DataKind kind : {DataKind::rate, DataKind::increment, DataKind::phase}) {
      CHECK_THROWS_WITH_AS(PhaseSeries::from_samples(y, kind, tau0),
                           doctest::Contains("sample interval"), Error);
    }
  }
}

TEST_CASE("data kinds parse and print, and anything else is an Error") {
  for (const DataKind kind : {DataKind::rate, DataKind::increment, DataKind::phase}) {
    CHECK(parse_data_kind(to_string(kind)) == kind);
  }
  for (const char* bad : {"", "frequency", "Rate", "phase "}) {
    CHECK_THROWS_WITH_AS(parse_data_kind(bad), doctest::Contains("rate, increment or phase"), Error);
  }
}
