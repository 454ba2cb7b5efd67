// The calibration in bounded memory (calibrate_log.hpp): a CalibrationLog kept in memory or
// spilled to its temporary file gives the same result as the CalibrationInput of the same values,
// to the last bit (the JSON text compared whole), and the detector's noise floor is the exact 25th
// percentile of the window statistic also when it is found by histogram passes (more than 2^21
// windows) and when every statistic ties.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "sigmatau/calibrate.hpp"
#include "sigmatau/calibrate_log.hpp"
#include "sigmatau/simulate.hpp"
#include "calibration_input.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

constexpr double kDeg = std::numbers::pi / 180;

/// A MEMS pair with gain, cross-axis and offset errors, white noise only, on a multi-position
/// schedule of `positions` dwells of `dwell_s` at `rate_hz`.
SimulationConfig config(int positions, double dwell_s, double rate_hz, OutputKind kind) {
  SimulationConfig c;
  c.rate_hz = rate_hz;
  c.seed = 21;
  c.kind = kind;
  ErrorModel g, a;
  g.scale_factor = Eigen::Vector3d(4e-3, -6e-3, 2.5e-3);
  g.misalignment << 0, 3e-3, -2e-3, 1.5e-3, 0, 4e-3, -2.5e-3, 1e-3, 0;
  g.bias = Eigen::Vector3d(0.5, -0.3, 0.2) * kDeg;
  a.scale_factor = Eigen::Vector3d(-5e-3, 8e-3, 3e-3);
  a.bias = Eigen::Vector3d(0.3, -0.2, 0.25);
  for (int i = 0; i < 3; ++i) {
    g.noise[static_cast<std::size_t>(i)].white = 0.005 * kDeg;
    a.noise[static_cast<std::size_t>(i)].white = 100e-6 * 9.80665;
  }
  c.gyro = g;
  c.accel = a;
  c.schedule = calibration_schedule(positions, dwell_s, 90 * kDeg, 45 * kDeg);
  c.samples = static_cast<std::int64_t>(schedule_duration_s(*c.schedule) * c.rate_hz) + 1;
  return c;
}

/// The simulated log as a CalibrationInput, with a temperature column rising 0.5 mK per sample
/// when `temperature` (the values only need to be valid and to be carried along).
CalibrationInput simulate(const SimulationConfig& c, bool temperature) {
  CalibrationInput in = test::simulate_calibration_input(c);
  if (temperature)
    for (std::size_t i = 0; i < in.accel[0].size(); ++i)
      in.temperature_k.push_back(290 + 5e-4 * static_cast<double>(i));
  return in;
}

/// The same rows in a CalibrationLog with `memory_bytes` of memory.
void fill(CalibrationLog& log, const CalibrationInput& in) {
  std::vector<double> row;
  for (std::size_t i = 0; i < in.accel[0].size(); ++i) {
    row.clear();
    for (const auto& a : in.accel) row.push_back(a[i]);
    if (log.has_gyro())
      for (const auto& g : in.gyro) row.push_back(g[i]);
    if (log.has_temperature()) row.push_back(in.temperature_k[i]);
    log.append(row);
  }
}

/// The detector's statistic over the whole log, written out plainly (calibrate.hpp: the sum over
/// the axes of each centred window's variance, from running sums centred on the first value).
std::vector<double> window_statistics(const std::array<std::vector<double>, 3>& x, std::int64_t w,
                                      double factor) {
  const auto n = static_cast<std::int64_t>(x[0].size());
  const std::int64_t h = (w - 1) / 2;
  std::vector<double> s(static_cast<std::size_t>(n - 2 * h), 0.0);
  const double len = static_cast<double>(w);
  for (const auto& axis : x) {
    std::vector<double> s1(static_cast<std::size_t>(n + 1), 0.0), s2(s1);
    const double c = axis[0] * factor;
    for (std::int64_t i = 0; i < n; ++i) {
      const double d = axis[static_cast<std::size_t>(i)] * factor - c;
      s1[static_cast<std::size_t>(i + 1)] = s1[static_cast<std::size_t>(i)] + d;
      s2[static_cast<std::size_t>(i + 1)] = s2[static_cast<std::size_t>(i)] + d * d;
    }
    for (std::int64_t i = h; i + h < n; ++i) {
      const auto a = static_cast<std::size_t>(i - h), b = static_cast<std::size_t>(i + h + 1);
      const double m = (s1[b] - s1[a]) / len;
      s[static_cast<std::size_t>(i - h)] +=
          std::max(0.0, ((s2[b] - s2[a]) - len * m * m) / (len - 1));
    }
  }
  return s;
}

double quarter(std::vector<double> v) {
  const auto k = static_cast<std::size_t>(0.25 * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace

TEST_CASE("a calibration log in memory or in its temporary file calibrates like the input") {
  for (const OutputKind kind : {OutputKind::rate, OutputKind::increment}) {
    for (const bool temperature : {false, true}) {
      CAPTURE(temperature);
      const CalibrationInput in = simulate(config(16, 8.0, 100, kind), temperature);
      CalibrationOptions o;
      o.latitude_rad = 45 * kDeg;
      o.gravity = normal_gravity(*o.latitude_rad);
      const std::string expected = calibration_json(calibrate(in, o));  // steps in memory
      // 1 GiB keeps the 1.5 MB log in memory; 1 byte sends every row, and every rotation step
      // of the gyroscope fit, to a temporary file.
      for (const std::int64_t memory : {std::int64_t{1} << 30, std::int64_t{1}}) {
        o.rotation_memory_bytes = memory;
        CalibrationLog log(true, temperature, memory);
        fill(log, in);
        CHECK(log.rows() == static_cast<std::int64_t>(in.accel[0].size()));
        CHECK(log.spilled() == (memory == 1));
        CHECK(calibration_json(calibrate(log, in.rate_hz, in.increments, o)) == expected);
      }
    }
  }
}

TEST_CASE("a calibration log reads back any range of rows as appended") {
  // Rows cross the in-memory pieces (65536 rows) and the file's reads; values are row * 10 + c.
  const std::int64_t rows = 3 * CalibrationLog::kPieceRows + 17;
  for (const std::int64_t memory : {std::int64_t{1} << 30, std::int64_t{1}}) {
    CalibrationLog log(false, true, memory);
    std::vector<double> values;
    for (std::int64_t r = 0; r < rows; ++r)
      for (int c = 0; c < 4; ++c) values.push_back(static_cast<double>(r * 10 + c));
    log.append(values);
    REQUIRE(log.rows() == rows);
    for (const auto& [begin, end] : std::vector<std::pair<std::int64_t, std::int64_t>>{
             {0, rows}, {65535, 65537}, {rows - 1, rows}, {100, 100}}) {
      std::int64_t next = begin, wrong = 0;
      log.read(begin, end, [&](std::int64_t first, std::int64_t n, const double* v) {
        if (first != next) ++wrong;
        for (std::int64_t r = 0; r < n; ++r)
          for (int c = 0; c < 4; ++c)
            if (v[r * 4 + c] != static_cast<double>((first + r) * 10 + c)) ++wrong;
        next = first + n;
      });
      CHECK(wrong == 0);
      CHECK(next == end);
    }
  }
}

TEST_CASE("the noise floor is the exact 25th percentile above 2^21 windows") {
  // 16 dwells of 1400 s at 100 Hz: 2.25 million windows, beyond the 2^21 that are selected in
  // one pass, so the floors come from histogram passes over the bit patterns.
  const CalibrationInput in = simulate(config(16, 1400.0, 100, OutputKind::rate), false);
  CalibrationOptions o;
  const StaticDetection d = detect_static_intervals(in, o);
  REQUIRE(static_cast<std::int64_t>(in.accel[0].size()) - d.window_samples + 1 > (1 << 21));
  CHECK(d.accel_floor == quarter(window_statistics(in.accel, d.window_samples, 1)));
  CHECK(d.gyro_floor == quarter(window_statistics(in.gyro, d.window_samples, 1)));
  CHECK(d.intervals.size() == 16);
  // The same log spilled to a file: the same whole calibration.
  o.latitude_rad = 45 * kDeg;
  o.gravity = normal_gravity(*o.latitude_rad);
  o.rotation_memory_bytes = 1;
  CalibrationLog log(true, false, 1);
  fill(log, in);
  CHECK(calibration_json(calibrate(log, in.rate_hz, false, o)) ==
        calibration_json(calibrate(in, o)));
}

TEST_CASE("a floor where every window statistic ties is found bit by bit") {
  // A constant accelerometer over 2.2 million samples: every statistic is 0, no histogram pass
  // narrows the group below 2^21, and the value comes out once all 64 bits are fixed.
  const std::size_t n = 2'200'000;
  CalibrationInput in;
  in.rate_hz = 100;
  in.accel = {std::vector<double>(n, 0.1), std::vector<double>(n, -0.2),
              std::vector<double>(n, 9.8)};
  const StaticDetection d = detect_static_intervals(in, CalibrationOptions{});
  CHECK(d.accel_floor == 0.0);
  REQUIRE(d.intervals.size() == 1);
  const std::int64_t h = (d.window_samples - 1) / 2;
  CHECK(d.intervals[0].first == h);
  CHECK(d.intervals[0].last == static_cast<std::int64_t>(n) - 1 - h);
}
