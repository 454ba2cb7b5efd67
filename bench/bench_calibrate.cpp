// The calibration seed study (issue 8): over many seeds of a simulated MEMS multi-position log
// (18 orientations, 15 s dwells, 90 deg/s rotations, 100 Hz, white noise ARW 0.005 deg/s/sqrt(Hz)
// and VRW 100 ug/sqrt(Hz)), for every identifiable s_i and m_ij of both triads:
//   coverage: the fraction of seeds with |estimate - truth| <= 3 reported standard errors
//             (requirement >= 95 %),
//   se/spread: the mean reported standard error over the standard deviation of the estimates
//             across seeds (requirement within 20 % of 1),
//   bias/sem: the mean error over the standard error of that mean (|value| > 3: a bias the
//             seeds resolve).
// The biases of both triads too: the gyro's is fitted with the Earth rate, whose horizontal part
// the schedule's headings project onto the body axes (at 45 deg latitude, 10.6 deg/h).
// Usage: bench_calibrate [SEEDS] (default 200) -- then the timing benchmark of one calibration.
#include <benchmark/benchmark.h>

#include <Eigen/QR>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include "sigmatau/calibrate.hpp"
#include "sigmatau/simulate.hpp"

using namespace sigmatau;

namespace {

constexpr double kDeg = std::numbers::pi / 180;
constexpr double kLatitude = 45 * kDeg;

SimulationConfig config(std::uint64_t seed) {
  SimulationConfig c;
  c.rate_hz = 100;
  c.seed = seed;
  ErrorModel g, a;
  g.scale_factor = Eigen::Vector3d(4e-3, -6e-3, 2.5e-3);
  g.misalignment << 0, 3e-3, -2e-3, 1.5e-3, 0, 4e-3, -2.5e-3, 1e-3, 0;
  g.bias = Eigen::Vector3d(0.5, -0.3, 0.2) * kDeg;
  a.scale_factor = Eigen::Vector3d(-5e-3, 8e-3, 3e-3);
  a.misalignment << 0, 2e-3, -1e-3, 3e-3, 0, -2e-3, 1e-3, 4e-3, 0;
  a.bias = Eigen::Vector3d(0.3, -0.2, 0.25);
  for (auto& n : g.noise) n.white = 0.005 * kDeg;
  for (auto& n : a.noise) n.white = 100e-6 * 9.80665;
  c.gyro = g;
  c.accel = a;
  c.schedule = calibration_schedule(18, 15.0, 90 * kDeg, kLatitude);
  c.samples = static_cast<std::int64_t>(schedule_duration_s(*c.schedule) * c.rate_hz) + 1;
  return c;
}

CalibrationInput input(const SimulationConfig& c) {
  Simulator sim(c);
  std::vector<double> all(static_cast<std::size_t>(c.samples * 6));
  sim.next(all, c.samples);
  CalibrationInput in;
  in.rate_hz = c.rate_hz;
  for (std::int64_t k = 0; k < c.samples; ++k)
    for (int ch = 0; ch < 6; ++ch)
      (ch < 3 ? in.gyro : in.accel)[static_cast<std::size_t>(ch % 3)].push_back(
          all[static_cast<std::size_t>(k * 6 + ch)]);
  return in;
}

CalibrationOptions options() {
  CalibrationOptions o;
  o.gravity = normal_gravity(kLatitude);
  o.latitude_rad = kLatitude;
  return o;
}

void seed_study(int seeds) {
  const SimulationConfig c0 = config(1);
  // Identifiable truth: A = L Q (L lower triangular), gyro G Q^T.
  const Eigen::Matrix3d a = Eigen::Matrix3d::Identity() + c0.accel->error_matrix();
  const Eigen::HouseholderQR<Eigen::Matrix3d> qr(a.transpose());
  Eigen::Matrix3d q1 = qr.householderQ();
  Eigen::Matrix3d r1 = qr.matrixQR().triangularView<Eigen::Upper>();
  const Eigen::Vector3d s = r1.diagonal().cwiseSign();
  const Eigen::Matrix3d l = (s.asDiagonal() * r1).transpose();
  const Eigen::Matrix3d q = (q1 * s.asDiagonal()).transpose();
  const Eigen::Matrix3d g = (Eigen::Matrix3d::Identity() + c0.gyro->error_matrix()) * q.transpose();
  struct Stat {
    std::string name;
    double truth;
    std::vector<double> est, se;
  };
  std::vector<Stat> stats;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j <= i; ++j)
      stats.push_back({std::string("accel A") + "xyz"[i] + "xyz"[j], l(i, j), {}, {}});
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      stats.push_back({std::string("gyro  G") + "xyz"[i] + "xyz"[j], g(i, j), {}, {}});
  // The biases are in each sensor's own reading axes: the simulated b, whatever the frame.
  for (int i = 0; i < 3; ++i) stats.push_back({std::string("accel b") + "xyz"[i], c0.accel->bias[i], {}, {}});
  for (int i = 0; i < 3; ++i) stats.push_back({std::string("gyro  b") + "xyz"[i], c0.gyro->bias[i], {}, {}});
  int failed = 0;
  for (int seed = 1; seed <= seeds; ++seed) {
    try {
      const CalibrationResult r = calibrate(input(config(static_cast<std::uint64_t>(seed))), options());
      std::size_t k = 0;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j <= i; ++j, ++k) {
          stats[k].est.push_back(r.accel.matrix(i, j));
          stats[k].se.push_back(r.accel.matrix_se(i, j));
        }
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j, ++k) {
          stats[k].est.push_back(r.gyro->matrix(i, j));
          stats[k].se.push_back(r.gyro->matrix_se(i, j));
        }
      for (const auto* triad : {&r.accel, &*r.gyro})
        for (int i = 0; i < 3; ++i, ++k) {
          stats[k].est.push_back(triad->bias[static_cast<std::size_t>(i)].value);
          stats[k].se.push_back(triad->bias[static_cast<std::size_t>(i)].standard_error);
        }
    } catch (const std::exception& e) {
      ++failed;
      std::printf("seed %d refused: %s\n", seed, e.what());
    }
  }
  std::printf("seed study: %d seeds (%d refused)\n", seeds, failed);
  std::printf("%-10s %14s %14s %14s %12s %10s %9s\n", "parameter", "truth", "mean est", "mean se",
              "within 3se", "se/spread", "bias/sem");
  for (const auto& st : stats) {
    const auto n = static_cast<double>(st.est.size());
    double mean = 0, mse = 0, inside = 0;
    for (std::size_t k = 0; k < st.est.size(); ++k) {
      mean += st.est[k] / n;
      mse += st.se[k] / n;
      inside += std::abs(st.est[k] - st.truth) <= 3 * st.se[k] ? 1.0 / n : 0.0;
    }
    double var = 0;
    for (double e : st.est) var += (e - mean) * (e - mean) / (n - 1);
    std::printf("%-10s %14.8f %14.8f %14.3e %11.1f%% %10.3f %+9.2f\n", st.name.c_str(), st.truth, mean,
                mse, 100 * inside, mse / std::sqrt(var), (mean - st.truth) / std::sqrt(var / n));
  }
}

void BM_calibrate(benchmark::State& state) {
  const CalibrationInput in = input(config(1));
  for (auto _ : state) benchmark::DoNotOptimize(calibrate(in, options()));
  state.counters["samples/s"] = benchmark::Counter(
      static_cast<double>(in.accel[0].size()) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate);
}
BENCHMARK(BM_calibrate)->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  int seeds = 200;
  if (argc > 1 && argv[1][0] != '-') {
    seeds = std::atoi(argv[1]);
    --argc;
    ++argv;
  }
  seed_study(seeds);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
