// Data checks on constructed channels: saturation and stuck runs at known rows, clean noise
// (continuous and quantized) left alone, unit mix-ups named.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <span>
#include <vector>

#include "sigmatau/data_checks.hpp"
#include "sigmatau/error.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

using test::white;

/// Quantized to integer counts (an i16 sensor), clipped at +-limit like an ADC.
std::vector<double> counts(std::vector<double> x, double limit) {
  for (auto& v : x) v = std::clamp(std::round(v), -limit, limit);
  return x;
}

constexpr double kG = 9.80665;

}  // namespace

TEST_CASE("clean noise, continuous and quantized at 1 LSB, raises no run warning") {
  CHECK(check_runs(white(100000, 0.0, 1.0, 1), "x").empty());
  // sigma = 1 LSB: the most frequent code has probability ~0.38 per sample, runs of 50 have
  // probability ~1e-21, and the extremes (about +-4.5 sigma) are hit a few times, not in a row.
  CHECK(check_runs(counts(white(100000, 0.0, 1.0, 2), 32767), "x").empty());
}

TEST_CASE("a clipped stretch is saturation at the right extreme, row and length") {
  auto x = counts(white(10000, 0.0, 100.0, 3), 32767);
  for (std::size_t i = 2000; i < 2120; ++i) x[i] = 32767;  // clipped: 120 rows at the maximum
  for (std::size_t i = 7000; i < 7007; ++i) x[i] = 32767;  // a second, shorter clip
  const auto w = check_saturation(x, "gyro_z");
  REQUIRE(w.size() == 1);
  CHECK(w[0].kind == DataWarningKind::saturation);
  CHECK(w[0].value == 32767);
  CHECK(w[0].runs == 2);
  CHECK(w[0].first_row == 2000);
  CHECK(w[0].first_rows == 120);
  CHECK(w[0].longest_row == 2000);
  CHECK(w[0].rows_flagged == 127);
  CHECK(w[0].message.find("gyro_z") != std::string::npos);
  CHECK(w[0].message.find("maximum 32767") != std::string::npos);
  CHECK(w[0].message.find("row 2000") != std::string::npos);
  // 4 rows at the minimum is below the threshold of 5.
  for (std::size_t i = 5000; i < 5004; ++i) x[i] = -32768;
  CHECK(check_saturation(x, "gyro_z").size() == 1);
  x[5004] = -32768;
  const auto both = check_saturation(x, "gyro_z");
  REQUIRE(both.size() == 2);
  CHECK(both[0].value == -32768);
  CHECK(both[0].first_row == 5000);
  CHECK(both[0].first_rows == 5);
}

TEST_CASE("a stuck stretch in the middle of the range is flagged, a shorter one is not") {
  auto x = white(10000, 0.0, 1.0, 4);
  for (std::size_t i = 3000; i < 3049; ++i) x[i] = 0.25;  // 49 rows: one short of 50
  CHECK_FALSE(check_stuck(x, "acc_x").has_value());
  x[3049] = 0.25;
  const auto w = check_stuck(x, "acc_x");
  REQUIRE(w.has_value());
  CHECK(w->kind == DataWarningKind::stuck);
  CHECK(w->first_row == 3000);
  CHECK(w->first_rows == 50);
  CHECK(w->runs == 1);
  CHECK(w->value == 0.25);
  CHECK(check_saturation(x, "acc_x").empty());  // 0.25 is not an extreme
  // Thresholds can be changed, never below 2.
  CHECK(check_stuck(x, "acc_x", {.stuck_min_run = 51}) == std::nullopt);
  CHECK_THROWS_AS(check_stuck(x, "acc_x", {.stuck_min_run = 1}), Error);
}

TEST_CASE("NaN never forms a run; a constant channel is stuck, not saturated") {
  std::vector<double> nan(100, std::nan(""));
  CHECK(check_runs(nan, "x").empty());
  std::vector<double> constant(100, 3.0);
  CHECK(check_saturation(constant, "x").empty());
  const auto w = check_stuck(constant, "x");
  REQUIRE(w.has_value());
  CHECK(w->first_rows == 100);
}

TEST_CASE("a static gyro logged in deg/s but declared rad/s is named deg/s") {
  // Bias 0.5, -0.3, 1.2 deg/s, noise 0.05 deg/s: written as numbers in deg/s.
  const auto gx = white(5000, 0.5, 0.05, 5);
  const auto gy = white(5000, -0.3, 0.05, 6);
  const auto gz = white(5000, 1.2, 0.05, 7);
  const std::vector<std::string> names{"gx", "gy", "gz"};
  // Declared rad/s: to_si = 1, SI values = the numbers (mean |w| ~ 1.33 "rad/s").
  const auto w = check_gyro_unit({gx, gy, gz}, names, "rad/s", 1.0);
  REQUIRE(w.has_value());
  CHECK(w->kind == DataWarningKind::unit);
  CHECK(w->likely_unit == "deg/s");
  CHECK(w->message.find("deg/s") != std::string::npos);
  CHECK(w->channel == "gx+gy+gz");
  // Declared deg/s correctly: the same numbers are plausible.
  const double deg = std::numbers::pi / 180.0;
  std::vector<std::vector<double>> si{gx, gy, gz};
  for (auto& a : si) {
    for (auto& v : a) v *= deg;
  }
  CHECK_FALSE(check_gyro_unit({si[0], si[1], si[2]}, names, "deg/s", deg).has_value());
  // Raw i16 counts (mean ~ 300 LSB) declared deg/s: 5.2 rad/s, and deg/h would make it 1.5e-3
  // rad/s; mrad/s (nearer deg/s in factor) already gives 0.3 rad/s, plausible.
  const auto raw = white(5000, 300.0, 5.0, 8);
  std::vector<double> raw_si(raw);
  for (auto& v : raw_si) v *= deg;
  const auto r = check_gyro_unit({raw_si}, {"gz"}, "deg/s", deg);
  REQUIRE(r.has_value());
  CHECK(r->likely_unit == "mrad/s");
  CHECK_THROWS_AS(check_gyro_unit({}, {}, "rad/s", 1.0), Error);
  CHECK_THROWS_AS(check_gyro_unit({gx}, {"gx"}, "rad/s", std::nan("")), Error);
}

TEST_CASE("an accelerometer in g declared m/s^2 (and the reverse) is named") {
  // Tilted static triad: 0.1, -0.2, 0.97 g plus 1 mg noise, written in g.
  const auto ax = white(5000, 0.1, 1e-3, 9);
  const auto ay = white(5000, -0.2, 1e-3, 10);
  const auto az = white(5000, 0.97, 1e-3, 11);
  const std::vector<std::string> names{"ax", "ay", "az"};
  const auto w = check_accel_unit({ax, ay, az}, names, "m/s^2", 1.0);
  REQUIRE(w.has_value());
  CHECK(w->likely_unit == "g");
  std::vector<std::vector<double>> si{ax, ay, az};
  for (auto& a : si) {
    for (auto& v : a) v *= kG;
  }
  CHECK_FALSE(check_accel_unit({si[0], si[1], si[2]}, names, "g", kG).has_value());
  // Numbers in m/s^2 (~9.9) declared g: 97 m/s^2 in SI; m/s^2 explains them.
  std::vector<std::vector<double>> declared_g = si;
  for (auto& a : declared_g) {
    for (auto& v : a) v *= kG;
  }
  const auto r =
      check_accel_unit({declared_g[0], declared_g[1], declared_g[2]}, names, "g", kG);
  REQUIRE(r.has_value());
  CHECK(r->likely_unit == "m/s^2");
  CHECK_THROWS_AS(check_accel_unit({ax, ay}, {"ax", "ay"}, "g", kG), Error);
}

namespace {

/// What a run warning must hold, found the plain way: one front-to-back min / max scan of the
/// finite values, then every maximal run of equal values of >= min_run rows.
struct ExpectedRuns {
  double value = 0;
  std::int64_t runs = 0, first_row = -1, first_rows = 0, longest_row = -1, longest_rows = 0,
               rows_flagged = 0;
};

ExpectedRuns expected_runs(const std::vector<double>& x, std::int64_t min_run,
                           bool (*keep)(double v, double lo, double hi), bool stuck) {
  double lo = INFINITY, hi = -INFINITY;
  for (const double v : x) {
    if (!std::isfinite(v)) continue;
    if (v < lo) lo = v;
    if (v > hi) hi = v;
  }
  ExpectedRuns e;
  e.value = stuck ? 0.0 : (keep(lo, lo, hi) ? lo : hi);
  for (std::size_t i = 0; i < x.size();) {
    std::size_t j = i + 1;
    while (j < x.size() && x[j] == x[i]) ++j;
    const auto n = static_cast<std::int64_t>(j - i);
    if (n >= min_run && keep(x[i], lo, hi)) {
      if (stuck && (e.runs == 0 || n > e.longest_rows)) e.value = x[i];
      if (e.runs == 0) e.first_row = static_cast<std::int64_t>(i), e.first_rows = n;
      if (n > e.longest_rows) e.longest_row = static_cast<std::int64_t>(i), e.longest_rows = n;
      ++e.runs;
      e.rows_flagged += n;
    }
    i = j;
  }
  return e;
}

void check_same(const DataWarning& w, const ExpectedRuns& e) {
  CHECK(w.runs == e.runs);
  CHECK(w.first_row == e.first_row);
  CHECK(w.first_rows == e.first_rows);
  CHECK(w.longest_row == e.longest_row);
  CHECK(w.longest_rows == e.longest_rows);
  CHECK(w.rows_flagged == e.rows_flagged);
  CHECK(w.value == e.value);
  CHECK(std::signbit(w.value) == std::signbit(e.value));  // -0.0 and +0.0 print differently
}

}  // namespace

TEST_CASE("check_runs' single pass finds what the plain scans find: extremes, zeros, non-finite") {
  // The extremes come from four interleaved lanes and the runs of both checks from one pass:
  // on channels whose extremes are -0.0 / +0.0 (equal, but printed apart: the first seen is
  // kept), with infinities and NaN beside them, and lengths that are no multiple of four.
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 24; ++trial) {
    const std::size_t n = 997 + static_cast<std::size_t>(trial) * 13;
    std::vector<double> x = counts(white(n, 0.0, 2.0, 100 + trial), 3);
    if (trial % 3 == 1) {  // the minimum is zero: -0.0 and +0.0, the first one varying
      for (auto& v : x) v = std::abs(v);
      const std::size_t a = rng() % n, b = rng() % n;
      x[std::min(a, b)] = trial % 2 ? -0.0 : 0.0;
      for (std::size_t i = 0; i < n; ++i) if (x[i] == 0 && rng() % 2) x[i] = -0.0;
    }
    if (trial % 3 == 2) {  // the maximum is zero
      for (auto& v : x) v = -std::abs(v);
      for (std::size_t i = 0; i < n; ++i) if (x[i] == 0 && rng() % 3 == 0) x[i] = -0.0;
    }
    if (trial % 4 == 0) x[rng() % n] = INFINITY, x[rng() % n] = -INFINITY;
    if (trial % 5 == 0) x[rng() % n] = std::nan("");
    const DataCheckOptions options{.stuck_min_run = trial % 2 ? 6 : 50,
                                   .saturation_min_run = trial % 2 ? 9 : 5};
    const auto runs = check_runs(x, "c", options);
    auto expected = check_saturation(x, "c", options);
    if (auto w = check_stuck(x, "c", options)) expected.push_back(*w);
    REQUIRE(runs.size() == expected.size());
    for (std::size_t i = 0; i < runs.size(); ++i) {
      CHECK(runs[i].kind == expected[i].kind);
      CHECK(runs[i].message == expected[i].message);
      if (runs[i].kind == DataWarningKind::stuck) {
        check_same(runs[i], expected_runs(x, options.stuck_min_run,
                                          [](double, double, double) { return true; }, true));
      } else if (runs[i].message.find("minimum") != std::string::npos) {
        check_same(runs[i], expected_runs(x, options.saturation_min_run,
                                          [](double v, double lo, double) { return v == lo; },
                                          false));
      } else {
        check_same(runs[i], expected_runs(x, options.saturation_min_run,
                                          [](double v, double, double hi) { return v == hi; },
                                          false));
      }
    }
  }
}
