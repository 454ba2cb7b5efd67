// A user truth series (simulate.hpp, TruthSeries): interpolation and interval means against hand
// values, the linear error model applied to it (noise-free exactly, with noise in the mean within
// its standard error), reading it from a CSV, and bad series.
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>

#include "sigmatau/error.hpp"
#include "sigmatau/simulate.hpp"
#include "test_support.hpp"

using namespace sigmatau;
using sigmatau::test::rel;

namespace {

std::vector<double> run(const SimulationConfig& c, std::int64_t block) {
  Simulator sim(c);
  std::vector<double> all(static_cast<std::size_t>(c.samples * sim.channels()));
  for (std::int64_t done = 0; done < c.samples;) {
    const std::int64_t rows =
        sim.next(std::span<double>(all).subspan(static_cast<std::size_t>(done * sim.channels())),
                 std::min(block, c.samples - done));
    REQUIRE(rows > 0);
    done += rows;
  }
  return all;
}

/// Gyro x: 0 at t = 0, 2 at t = 1, -2 at t = 3 [rad/s]; y and z twice and minus x; accel 10 x.
std::shared_ptr<TruthSeries> small_series() {
  auto s = std::make_shared<TruthSeries>();
  s->t_s = {0.0, 1.0, 3.0};
  for (double x : {0.0, 2.0, -2.0}) {
    s->angular_rate.emplace_back(x, 2 * x, -x);
    s->specific_force.emplace_back(10 * x, 0, 9.8);
  }
  return s;
}

/// A log-length series: rows every 0.37 s (not on the sample grid), a slow swing of the rates and
/// a tilt of gravity, in SI.
std::shared_ptr<TruthSeries> swinging_series(double duration_s) {
  auto s = std::make_shared<TruthSeries>();
  for (double t = -0.5; t <= duration_s + 1; t += 0.37) {
    s->t_s.push_back(t);
    s->angular_rate.emplace_back(0.3 * std::sin(0.2 * t), -0.1 + 0.01 * t, 0.05 * std::cos(t));
    const double tilt = 0.3 * std::sin(0.05 * t);
    s->specific_force.emplace_back(9.8 * std::sin(tilt), 0.1, -9.8 * std::cos(tilt));
  }
  s->source = "test";
  return s;
}

/// The test's own linear interpolation of one component (independent of the library's cursor).
double interpolate(const TruthSeries& s, bool gyro, int axis, double t) {
  const auto& v = gyro ? s.angular_rate : s.specific_force;
  if (t <= s.t_s.front()) return v.front()[axis];
  if (t >= s.t_s.back()) return v.back()[axis];
  std::size_t i = 0;
  while (s.t_s[i + 1] <= t) ++i;
  const double w = (t - s.t_s[i]) / (s.t_s[i + 1] - s.t_s[i]);
  return (1 - w) * v[i][axis] + w * v[i + 1][axis];
}

ErrorModel error_model(double white) {
  ErrorModel m;
  m.scale_factor = Eigen::Vector3d(2e-3, -1e-3, 5e-4);
  m.misalignment << 0, 1e-3, -2e-3, 5e-4, 0, 1e-3, -1e-3, 2e-3, 0;
  m.bias = Eigen::Vector3d(1e-3, -2e-3, 3e-3);
  if (white > 0)
    for (auto& t : m.noise) t.white = white;
  return m;
}

/// Row `axis` of (I + T) x + b for the model's T and b (written out, not error_matrix()).
double expected_output(const ErrorModel& m, const Eigen::Vector3d& x, int axis) {
  double y = (1 + m.scale_factor[axis]) * x[axis] + m.bias[axis];
  for (int j = 0; j < 3; ++j)
    if (j != axis) y += m.misalignment(axis, j) * x[j];
  return y;
}

}  // namespace

TEST_CASE("truth series: linear between rows, held outside, exact interval means") {
  const auto s = small_series();
  // Hand values of the piecewise-linear gyro x (0 -> 2 on [0, 1], 2 -> -2 on [1, 3]); 1e-15:
  // a few roundings of numbers of order 1.
  CHECK(truth_at(*s, 0.5).angular_rate[0] == rel(1.0, 1e-15));
  CHECK(std::abs(truth_at(*s, 2.0).angular_rate[0]) < 1e-15);
  CHECK(truth_at(*s, -1.0).angular_rate[1] == 0.0);         // held first row
  CHECK(truth_at(*s, 5.0).angular_rate[2] == 2.0);          // held last row: -x = 2
  CHECK(truth_at(*s, 1.0).specific_force[0] == rel(20.0, 1e-15));
  // Means: [0.5, 2]: trapezoids 0.5 (1 + 2)/2 + 1 (2 + 0)/2 = 1.75 over 1.5;
  // [2.5, 4]: 0.5 (-1 - 2)/2 + 1 (-2) = -2.75 over 1.5; [-1, 0]: held 0; [-1, 0.5]: 0.25 / 1.5.
  CHECK(truth_mean(*s, 0.5, 2.0).angular_rate[0] == rel(1.75 / 1.5, 1e-15));
  CHECK(truth_mean(*s, 2.5, 4.0).angular_rate[0] == rel(-2.75 / 1.5, 1e-15));
  CHECK(truth_mean(*s, -1.0, 0.0).angular_rate[0] == 0.0);
  CHECK(truth_mean(*s, -1.0, 0.5).angular_rate[0] == rel(0.25 / 1.5, 1e-15));
  CHECK(truth_mean(*s, 0.25, 0.25).angular_rate[0] == rel(0.5, 1e-15));
}

TEST_CASE("a truth series drives the error model: noise-free output is (I + T) x(t) + b") {
  SimulationConfig c;
  c.rate_hz = 50;
  c.samples = 1000;  // 20 s; the rows span [-0.5, 21.2] s
  c.truth_series = swinging_series(20);
  c.gyro = error_model(0);
  c.accel = error_model(0);
  const auto rate = run(c, 333);
  const auto& s = *c.truth_series;
  double worst = 0;
  for (std::int64_t k = 0; k < c.samples; ++k) {
    const double t = static_cast<double>(k) / c.rate_hz;
    for (int ch = 0; ch < 6; ++ch) {
      const bool gyro = ch < 3;
      const Eigen::Vector3d x(interpolate(s, gyro, 0, t), interpolate(s, gyro, 1, t),
                              interpolate(s, gyro, 2, t));
      const double expected = expected_output(gyro ? *c.gyro : *c.accel, x, ch % 3);
      worst = std::max(worst, std::abs(rate[static_cast<std::size_t>(6 * k + ch)] - expected));
    }
  }
  // Values up to ~10 m/s^2: a few roundings, 1e-13 absolute.
  CHECK(worst < 1e-13);
  // Increments: tau0 times the mean over the interval. The series is linear inside a row
  // interval, so where [t, t + tau0] holds no row the mean is the value at the midpoint.
  c.kind = OutputKind::increment;
  const auto inc = run(c, 4096);
  const double tau0 = 1 / c.rate_hz;
  int compared = 0;
  for (std::int64_t k = 0; k < c.samples; ++k) {
    const double t = static_cast<double>(k) * tau0;
    const auto row = std::upper_bound(s.t_s.begin(), s.t_s.end(), t);
    if (row != s.t_s.end() && *row < t + tau0) continue;  // a row inside the interval
    const Eigen::Vector3d x(interpolate(s, true, 0, t + tau0 / 2),
                            interpolate(s, true, 1, t + tau0 / 2),
                            interpolate(s, true, 2, t + tau0 / 2));
    // 0.3 rad/s x 0.02 s: values ~6e-3 rad, rounding 1e-16 relative; 1e-15 absolute.
    CHECK(std::abs(inc[static_cast<std::size_t>(6 * k)] - tau0 * expected_output(*c.gyro, x, 0)) <
          1e-15);
    ++compared;
  }
  CHECK(compared > 900);
  // The same samples whatever the block size (the cursor only moves forward).
  c.kind = OutputKind::rate;
  const auto other = run(c, 7);
  CHECK(std::memcmp(other.data(), rate.data(), rate.size() * sizeof(double)) == 0);
}

TEST_CASE("with noise, the mean of the output recovers (I + T) x + b within its standard error") {
  SimulationConfig c;
  c.rate_hz = 200;
  c.samples = 200000;  // 1000 s
  c.seed = 17;
  c.truth_series = swinging_series(1000);
  const double n_gyro = 1e-3, n_accel = 2e-2;  // [rad/s/sqrt(Hz)], [m/s^2/sqrt(Hz)]
  c.gyro = error_model(n_gyro);
  c.accel = error_model(n_accel);
  const auto data = run(c, 65536);
  const auto& s = *c.truth_series;
  for (int ch = 0; ch < 6; ++ch) {
    const bool gyro = ch < 3;
    double mean = 0, expected = 0;
    for (std::int64_t k = 0; k < c.samples; ++k) {
      const double t = static_cast<double>(k) / c.rate_hz;
      const Eigen::Vector3d x(interpolate(s, gyro, 0, t), interpolate(s, gyro, 1, t),
                              interpolate(s, gyro, 2, t));
      mean += data[static_cast<std::size_t>(6 * k + ch)];
      expected += expected_output(gyro ? *c.gyro : *c.accel, x, ch % 3);
    }
    mean /= static_cast<double>(c.samples);
    expected /= static_cast<double>(c.samples);
    // White noise only: the mean's standard error is N sqrt(rate) / sqrt(samples); 5 standard
    // errors, two-sided false failure 5.7e-7 per channel (3.4e-6 for the six).
    const double se = (gyro ? n_gyro : n_accel) * std::sqrt(c.rate_hz / static_cast<double>(c.samples));
    INFO("channel " << ch << ": mean " << mean << ", expected " << expected << ", se " << se);
    CHECK(std::abs(mean - expected) <= 5 * se);
  }
}

TEST_CASE("read_truth_csv: units, columns and bad files") {
  const auto dir = std::filesystem::temp_directory_path() / "sigmatau_test_simulate_truth";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto path = dir / "truth.csv";
  {
    std::ofstream f(path);
    f << "t,ax,ay,az,gx,gy,gz\n0,0,0,-1,10,0,0\n0.5,0.5,0,-1,20,0,-5\n2,0,0,-1,0,0,0\n";
  }
  const TruthSeries s = read_truth_csv(path, true, true, std::numbers::pi / 180, 9.80665);
  REQUIRE(s.t_s.size() == 3);
  CHECK(s.t_s[1] == 0.5);
  // deg/s -> rad/s and g -> m/s^2: one multiplication each, exact to 1 ulp.
  CHECK(s.angular_rate[1][0] == rel(20 * std::numbers::pi / 180, 1e-16));
  CHECK(s.angular_rate[1][2] == rel(-5 * std::numbers::pi / 180, 1e-16));
  CHECK(s.specific_force[1][0] == rel(0.5 * 9.80665, 1e-16));
  CHECK(s.specific_force[0][2] == rel(-9.80665, 1e-16));
  const TruthSeries accel_only = read_truth_csv(path, false, true);
  CHECK(accel_only.angular_rate.empty());
  CHECK(accel_only.specific_force[1][0] == 0.5);
  {
    std::ofstream f(dir / "backwards.csv");
    f << "t,gx,gy,gz\n0,1,2,3\n1,1,2,3\n0.5,1,2,3\n";
  }
  CHECK_THROWS_WITH_AS(read_truth_csv(dir / "backwards.csv", true, false),
                       doctest::Contains("backwards.csv:4"), ParseError);
  CHECK_THROWS_AS(read_truth_csv(dir / "backwards.csv", false, true), Error);  // no ax, ay, az
  std::filesystem::remove_all(dir);
}

TEST_CASE("bad truth configurations are Errors, and the sidecar names the series") {
  SimulationConfig c;
  c.rate_hz = 10;
  c.samples = 10;
  c.gyro = error_model(1e-3);
  auto s = small_series();
  s->angular_rate.clear();
  c.truth_series = s;
  CHECK_THROWS_WITH_AS(Simulator{c}, doctest::Contains("no angular rate"), Error);
  s = small_series();
  s->t_s[2] = 1.0;  // not strictly increasing
  c.truth_series = s;
  CHECK_THROWS_WITH_AS(Simulator{c}, doctest::Contains("row 3"), Error);
  c.truth_series = small_series();
  c.schedule = calibration_schedule(6, 1.0, 1.0, 0.5);
  CHECK_THROWS_WITH_AS(Simulator{c}, doctest::Contains("use one of them"), Error);
  c.schedule.reset();
  const auto j = nlohmann::json::parse(simulation_sidecar_json(c));
  CHECK(j["truth_series"]["rows"] == 3);
  CHECK(j["truth_series"]["t_last_s"] == 3.0);
  CHECK_FALSE(j["gyro"].contains("expected_mean"));
}
