// The outlier check (data_checks.hpp, check_outliers): its false alarms on healthy simulated
// logs, what it finds on the real IMU logs, and its cost. Prints markdown
// (bench/results_outliers.md holds a run).
//
//   bench_outliers [--samples N] [--blocks B] [--imu DIR]
//
// 1. Simulated gyro triads (Simulator, 100 Hz, N samples in all, default 1e8): white noise;
//    white noise under a rate random walk whose step per sample equals the white noise's sigma
//    (the walk wanders ~64 sigma over a block); a pure random walk; white noise of 0.5 LSB
//    through a real quantizer. Counts beyond 5, 6, 7, 8 robust sigma and the largest seen.
// 2. The expected false alarms per 1e8 Gaussian samples at k = 6, 7, 8: over B blocks (default
//    20000) of 4096 N(0, 1) values, the mean of P(|Z - m| > k s) for the block's own m and s
//    (outlier_scale), which counts what 1e8 samples cannot show (1e-15 per sample).
// 3. The real logs under DIR (default ../shared/data/imu: run from the source tree): counts
// beyond 4..10 sigma with the q90 scale (the default) and
//    with the MAD (scale_quantile 0.5), and the largest.
// 4. Cost: check_outliers on 1e7 values, median of 7 runs of this thread's CPU time, against
//    one pass summing them.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "bench_stats.hpp"
#include "sigmatau/data_checks.hpp"
#include "sigmatau/log_reader.hpp"
#include "sigmatau/simulate.hpp"

namespace {

using namespace sigmatau;

constexpr double kThresholds[] = {5, 6, 7, 8};

/// Outlier checkers at every threshold of kThresholds on one channel.
struct Ladder {
  std::vector<OutlierChecker> checkers;
  explicit Ladder(OutlierOptions options = {}) {
    for (const double k : kThresholds) {
      options.threshold_sigma = k;
      checkers.emplace_back("c", options);
    }
  }
};

void false_alarms(std::int64_t samples) {
  std::printf(
      "## False alarms on simulated healthy gyro triads (100 Hz, %.3g samples each row)\n\n",
      static_cast<double>(samples));
  std::printf(
      "| log | > 5 sigma | > 6 | > 7 | > 8 | largest [sigma] |\n|---|---|---|---|---|---|\n");
  struct Case {
    const char* name;
    double white, walk, quantizer;
  };
  // White 1e-3 rad/s/sqrt(Hz): 1e-2 rad/s per sample at 100 Hz. A rate random walk K gives a
  // step of K sqrt(tau0) = 0.1 K per sample: K = 0.1 equals the white sample. A quantizer step
  // on the angle of 2e-4 rad: the white noise's angle increment (1e-4 rad) is 0.5 LSB.
  const Case cases[] = {{"white noise", 1e-3, 0, 0},
                        {"white + random walk (step = white sigma)", 1e-3, 0.1, 0},
                        {"random walk only", 0, 0.1, 0},
                        {"white noise, 0.5 LSB, real quantizer", 1e-3, 0, 2e-4}};
  for (const Case& c : cases) {
    SimulationConfig config;
    config.rate_hz = 100;
    config.samples = samples / 3;
    config.seed = 17;
    NoiseTerms t;
    if (c.white > 0) t.white = c.white;
    if (c.walk > 0) t.rate_random_walk = c.walk;
    ErrorModel model;
    model.noise = {t, t, t};
    config.gyro = model;
    config.gyro_quantizer_step = c.quantizer;
    config.threads = 2;
    Simulator sim(config);
    std::vector<Ladder> ladders(3);
    OutlierOptions low;
    low.threshold_sigma = 3;
    std::vector<OutlierChecker> largest(3, OutlierChecker("c", low));
    constexpr std::int64_t kRows = 65536;
    std::vector<double> block(kRows * 3);
    std::vector<double> channel(kRows);
    std::int64_t rows = 0;
    while ((rows = sim.next(block, kRows)) > 0) {
      channel.resize(static_cast<std::size_t>(rows));
      for (int a = 0; a < 3; ++a) {
        for (std::int64_t i = 0; i < rows; ++i)
          channel[i] = block[static_cast<std::size_t>(i * 3 + a)];
        for (auto& checker : ladders[a].checkers) checker.add(channel);
        largest[a].add(channel);
      }
    }
    std::int64_t counts[std::size(kThresholds)] = {};
    double max_sigma = 0;
    for (int a = 0; a < 3; ++a) {
      for (std::size_t k = 0; k < std::size(kThresholds); ++k) {
        if (const auto w = ladders[a].checkers[k].finish()) counts[k] += w->runs;
      }
      if (const auto w = largest[a].finish()) max_sigma = std::max(max_sigma, w->largest_sigma);
    }
    char largest_text[32] = "< 3";  // the low checker flags from 3 sigma on
    if (max_sigma > 0) std::snprintf(largest_text, sizeof largest_text, "%.2f", max_sigma);
    std::printf("| %s | %lld | %lld | %lld | %lld | %s |\n", c.name,
                static_cast<long long>(counts[0]), static_cast<long long>(counts[1]),
                static_cast<long long>(counts[2]), static_cast<long long>(counts[3]), largest_text);
    std::fflush(stdout);
  }
  std::printf(
      "\nGaussian two-sided tail per 1e8 samples: %.3g beyond 5, %.3g beyond 6, %.3g beyond 7, "
      "%.3g beyond 8 sigma.\n\n",
      1e8 * std::erfc(5 / std::numbers::sqrt2), 1e8 * std::erfc(6 / std::numbers::sqrt2),
      1e8 * std::erfc(7 / std::numbers::sqrt2), 1e8 * std::erfc(8 / std::numbers::sqrt2));
}

void expected_false_alarms(std::int64_t blocks) {
  std::mt19937_64 rng(23);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> x(4096);
  double p[3] = {};
  const double ks[3] = {6, 7, 8};
  double s_sum = 0, s_sq = 0;
  for (std::int64_t b = 0; b < blocks; ++b) {
    for (auto& v : x) v = normal(rng);
    const OutlierScale s = outlier_scale(x);
    s_sum += s.sigma;
    s_sq += s.sigma * s.sigma;
    for (int i = 0; i < 3; ++i) {
      const double limit = ks[i] * s.sigma;
      p[i] += 0.5 * std::erfc((limit - s.median) / std::numbers::sqrt2) +
              0.5 * std::erfc((limit + s.median) / std::numbers::sqrt2);
    }
  }
  const double n = static_cast<double>(blocks);
  const double mean = s_sum / n;
  std::printf("## Expected false alarms per 1e8 Gaussian samples (%lld blocks of 4096)\n\n",
              static_cast<long long>(blocks));
  std::printf("Block sigma: mean %.4f, relative spread %.2f %%.\n\n", mean,
              100 * std::sqrt(s_sq / n - mean * mean) / mean);
  std::printf("| k | expected per 1e8 | Gaussian tail alone |\n|---|---|---|\n");
  for (int i = 0; i < 3; ++i) {
    std::printf("| %g | %.3g | %.3g |\n", ks[i], 1e8 * p[i] / n,
                1e8 * std::erfc(ks[i] / std::numbers::sqrt2));
  }
  std::printf("\n");
}

void real_logs(const std::filesystem::path& dir) {
  std::printf("## Real logs (%s)\n\n", dir.string().c_str());
  std::printf(
      "| log | channel | rows | scale | > 4 | > 5 | > 6 | > 7 | > 8 | > 10 | largest [sigma] at "
      "row |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n");
  const char* logs[] = {"adis16405_imudata/adis16405_imu1_100Hz.csv.gz",
                        "hipnuc_ch104/hipnuc_ch104_static_100Hz.csv.gz",
                        "xsens_mtig_cont_imu1/xsens_mtig_gyro_x_100Hz_contaminated.csv.gz"};
  for (const char* name : logs) {
    LogOptions options;
    options.path = (dir / name).string();
    Log log;
    try {
      log = read_log(options);
    } catch (const std::exception& e) {
      std::printf("| %s | (not read: %s) |\n", name, e.what());
      continue;
    }
    for (std::size_t c = 0; c < log.channels.size(); ++c) {
      for (const double q : {0.9, 0.5}) {
        std::printf("| %s | %s | %zu | %s |", std::filesystem::path(name).parent_path().c_str(),
                    log.channel_names[c].c_str(), log.channels[c].size(), q == 0.9 ? "q90" : "MAD");
        double largest = 0;
        std::int64_t row = -1;
        for (const double k : {4.0, 5.0, 6.0, 7.0, 8.0, 10.0}) {
          OutlierOptions o;
          o.threshold_sigma = k;
          o.scale_quantile = q;
          const auto w = check_outliers(log.channels[c], "c", o);
          std::printf(" %lld |", w ? static_cast<long long>(w->runs) : 0LL);
          if (w && k == 4.0) {
            largest = w->largest_sigma;
            row = w->longest_row;
          }
        }
        std::printf(" %.3g at %lld |\n", largest, static_cast<long long>(row));
      }
    }
  }
  std::printf("\n");
}

/// This thread's CPU time [ns] (the machine is shared: wall clock would count other work).
double cpu_ns() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return 1e9 * static_cast<double>(t.tv_sec) + static_cast<double>(t.tv_nsec);
}

void cost() {
  std::mt19937_64 rng(29);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> x(10000000);
  for (auto& v : x) v = normal(rng);
  std::vector<double> check_ns, sum_ns;
  for (int run = 0; run < 7; ++run) {
    const double t0 = cpu_ns();
    const auto w = check_outliers(x, "c");
    benchmark::DoNotOptimize(w);
    const double t1 = cpu_ns();
    double sum = 0;
    for (const double v : x) sum += v;
    benchmark::DoNotOptimize(sum);
    const double t2 = cpu_ns();
    const double n = static_cast<double>(x.size());
    check_ns.push_back((t1 - t0) / n);
    sum_ns.push_back((t2 - t1) / n);
  }
  std::printf("## Cost (1e7 values, median of 7 runs, thread CPU time)\n\n");
  std::printf(
      "check_outliers: %.2f ns per value; one summing pass over the same values: %.2f ns.\n",
      bench::median(check_ns), bench::median(sum_ns));
}

}  // namespace

int main(int argc, char** argv) {
  std::int64_t samples = 100000000;
  std::int64_t blocks = 20000;
  std::filesystem::path imu = "../shared/data/imu";  // run from the source tree
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--samples")) samples = std::stoll(argv[i + 1]);
    if (!std::strcmp(argv[i], "--blocks")) blocks = std::stoll(argv[i + 1]);
    if (!std::strcmp(argv[i], "--imu")) imu = argv[i + 1];
  }
  std::printf("# Outlier check (check_outliers: 4096-row blocks, q90 robust sigma, k = 8)\n\n");
  cost();
  std::printf("\n");
  expected_false_alarms(blocks);
  real_logs(imu);
  false_alarms(samples);
  return 0;
}
