// Simulator throughput (samples per second over all channels, wall clock) for a 6-axis log with
// every term at 1 kHz:
//  - BM_Generate: generated block by block and discarded (bounded memory); the target is
//    the 24 h log (BM_Generate/86400000/...) at >= 20 M samples/s in total.
//  - BM_Write: write_simulation to a file (csv, f32, f64) under the system temp directory,
//    removed afterwards; sidecar included.
// Run: build/bench/bench_simulate --benchmark_filter=Generate/86400000 (about a minute), or
// --benchmark_filter=Write --benchmark_repetitions=3.
//
// The statistical check (issue 4, "a statistical check in bench/"): `bench_simulate --stats
// [SEEDS]` (default 100) simulates, for each term alone and for the sum of all, SEEDS seeds x 3
// axes of 2^16 samples at 100 Hz, computes the OADEV at every octave tau (allan.hpp) and counts
// how often the exact theoretical AVAR (sampled_avar) lies outside the estimate's 99 % chi-squared
// interval (Greenhall's EDF for the term's power law; for Gauss-Markov and the sum, the smallest
// EDF over alpha = 2, 0, -1, -2, which widens the interval). A correct simulator gives about 1 %
// for the single power laws and less for the conservative EDF; the table prints, per term, the
// fraction over all taus and the largest fraction at one tau with its binomial standard error.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "sigmatau/allan.hpp"
#include "sigmatau/confidence.hpp"
#include "sigmatau/phase_series.hpp"
#include "sigmatau/simulate.hpp"

namespace {

sigmatau::SimulationConfig every_term(std::int64_t samples, unsigned threads) {
  sigmatau::NoiseTerms t;
  t.white = 1e-3;
  t.quantization = 2e-6;
  t.bias_instability = 3e-5;
  t.rate_random_walk = 2e-5;
  t.gauss_markov = {sigmatau::GaussMarkov{5e-5, 2.0}};
  t.rate_ramp = 1e-7;
  t.sinusoid = sigmatau::Sinusoid{2e-5, 1.3, 0.4};
  sigmatau::SimulationConfig c;
  c.rate_hz = 1000;
  c.samples = samples;
  sigmatau::ErrorModel m;
  m.noise = {t, t, t};
  c.gyro = m;
  c.accel = m;
  c.threads = threads;
  return c;
}

/// Args: samples per channel, threads.
void BM_Generate(benchmark::State& state) {
  const std::int64_t samples = state.range(0);
  const auto config = every_term(samples, static_cast<unsigned>(state.range(1)));
  std::vector<double> block(static_cast<std::size_t>(65536 * 6));
  for (auto _ : state) {
    sigmatau::Simulator sim(config);
    while (sim.next(block, 65536) > 0) benchmark::DoNotOptimize(block.data());
  }
  state.counters["samples_per_s"] = benchmark::Counter(
      static_cast<double>(samples * 6) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate);
}

/// Args: format (0 csv, 1 f32, 2 f64), threads; one hour at 1 kHz.
void BM_Write(benchmark::State& state) {
  constexpr std::int64_t kSamples = 3'600'000;
  const auto format = static_cast<sigmatau::SampleFormat>(state.range(0));
  const auto config = every_term(kSamples, static_cast<unsigned>(state.range(1)));
  const auto path = std::filesystem::temp_directory_path() / "sigmatau_bench_simulate.out";
  for (auto _ : state) sigmatau::write_simulation(config, path, format, true);
  std::filesystem::remove(path);
  std::filesystem::remove(path.string() + ".json");
  state.counters["samples_per_s"] = benchmark::Counter(
      static_cast<double>(kSamples * 6) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate);
}

struct StatsCase {
  const char* name;
  sigmatau::NoiseTerms terms;
  std::vector<int> alphas;  // power laws whose smallest Greenhall EDF is used
};

int run_stats(int seeds) {
  using namespace sigmatau;
  constexpr std::int64_t kSamples = std::int64_t{1} << 16;
  constexpr double kRate = 100;
  std::vector<StatsCase> cases(6);
  cases[0] = {"white N", {}, {0}};
  cases[0].terms.white = 1e-3;
  cases[1] = {"quantization Q", {}, {2}};
  cases[1].terms.quantization = 1e-6;
  cases[2] = {"flicker B", {}, {-1}};
  cases[2].terms.bias_instability = 2e-5;
  cases[3] = {"random walk K", {}, {-2}};
  cases[3].terms.rate_random_walk = 1e-5;
  cases[4] = {"Gauss-Markov", {}, {2, 0, -1, -2}};
  cases[4].terms.gauss_markov = {GaussMarkov{1e-4, 5.0}};
  cases[5] = {"all terms", {}, {2, 0, -1, -2}};
  auto& all = cases[5].terms;
  all.white = 1e-3;
  all.quantization = 2e-6;
  all.bias_instability = 3e-5;
  all.rate_random_walk = 2e-5;
  all.gauss_markov = {GaussMarkov{5e-5, 2.0}};
  all.rate_ramp = 1e-7;
  all.sinusoid = Sinusoid{2e-5, 1.3, 0.4};
  std::vector<std::int64_t> ms;
  for (std::int64_t m = 1; 4 * m <= kSamples; m *= 2) ms.push_back(m);
  std::printf("| term | realizations | taus | outside 99%% (all taus) | worst tau: outside "
              "(binomial s.e.) |\n|---|---|---|---|---|\n");
  for (const auto& c : cases) {
    SimulationConfig config;
    config.rate_hz = kRate;
    config.samples = kSamples;
    ErrorModel model;
    model.noise = {c.terms, c.terms, c.terms};
    config.gyro = model;
    const Sampling sampling = sampling_of(config);
    std::vector<double> edf(ms.size()), theory(ms.size());
    for (std::size_t i = 0; i < ms.size(); ++i) {
      edf[i] = 1e300;
      for (int alpha : c.alphas)
        edf[i] = std::min(edf[i], equivalent_dof(Statistic::oadev, alpha, ms[i], kSamples + 1));
      theory[i] = sampled_avar(c.terms, ms[i], sampling);
    }
    std::vector<int> outside(ms.size(), 0);
    std::vector<double> sum(ms.size(), 0.0), sum_sq(ms.size(), 0.0);  // of estimate / theory
    std::vector<double> rows(static_cast<std::size_t>(kSamples * 3)), channel(static_cast<std::size_t>(kSamples));
    for (int seed = 1; seed <= seeds; ++seed) {
      config.seed = static_cast<std::uint64_t>(seed);
      Simulator sim(config);
      sim.next(rows, kSamples);
      for (int axis = 0; axis < 3; ++axis) {
        for (std::int64_t k = 0; k < kSamples; ++k) channel[k] = rows[static_cast<std::size_t>(3 * k + axis)];
        const auto points = compute_deviation(PhaseSeries::from_rate(channel, 1 / kRate),
                                              Statistic::oadev, ms);
        for (std::size_t i = 0; i < ms.size(); ++i) {
          const Interval ci = chi_squared_interval(points[i].dev, edf[i], 0.99);
          const double truth = std::sqrt(theory[i]);
          if (truth < ci.low || truth > ci.high) ++outside[i];
          const double ratio = points[i].dev * points[i].dev / theory[i];
          sum[i] += ratio;
          sum_sq[i] += ratio * ratio;
        }
      }
    }
    const double r = 3.0 * seeds;
    int total = 0;
    std::size_t worst = 0;
    for (std::size_t i = 0; i < ms.size(); ++i) {
      total += outside[i];
      if (outside[i] > outside[worst]) worst = i;
    }
    const double p = outside[worst] / r;
    // At the worst tau: the mean of estimate / theory (1 when unbiased) and the EDF implied by
    // the spread of the estimates, 2 mean^2 / variance, beside the EDF used for the interval.
    const double mean = sum[worst] / r;
    const double var = (sum_sq[worst] - r * mean * mean) / (r - 1);
    std::printf("| %s | %.0f | %zu | %.2f %% | m = %lld: %.2f %% (+-%.2f %%), mean ratio %.4f, "
                "EDF used %.4g, from the spread %.4g |\n",
                c.name, r, ms.size(), 100.0 * total / (r * static_cast<double>(ms.size())),
                static_cast<long long>(ms[worst]), 100 * p, 100 * std::sqrt(0.01 * 0.99 / r),
                mean, edf[worst], 2 * mean * mean / var);
  }
  return 0;
}

}  // namespace

BENCHMARK(BM_Generate)
    ->Args({600'000, 1})
    ->Args({600'000, 2})
    ->Args({86'400'000, 2})
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kSecond);
BENCHMARK(BM_Write)
    ->ArgsProduct({{0, 1, 2}, {2}})
    ->Iterations(1)
    ->UseRealTime()
    ->Unit(benchmark::kSecond);
int main(int argc, char** argv) {
  if (argc >= 2 && std::strcmp(argv[1], "--stats") == 0)
    return run_stats(argc >= 3 ? std::max(1, std::atoi(argv[2])) : 100);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
