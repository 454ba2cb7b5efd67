// Simulator throughput (samples per second over all channels, wall clock) for a 6-axis log with
// every term at 1 kHz:
//  - BM_Generate: generated block by block and discarded (bounded memory); the target is
//    the 24 h log (BM_Generate/86400000/...) at >= 20 M samples/s in total.
//  - BM_Write: write_simulation to a file (csv, f32, f64) under the system temp directory,
//    removed afterwards; sidecar included.
// Run: build/bench/bench_simulate --benchmark_filter=Generate/86400000 (about a minute), or
// --benchmark_filter=Write --benchmark_repetitions=3.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <vector>

#include "sigmatau/simulate.hpp"

namespace {

sigmatau::SimulationConfig every_term(std::int64_t samples, unsigned threads) {
  sigmatau::NoiseTerms t;
  t.white = 1e-3;
  t.quantization = 2e-6;
  t.bias_instability = 3e-5;
  t.rate_random_walk = 2e-5;
  t.gauss_markov = sigmatau::GaussMarkov{5e-5, 2.0};
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
BENCHMARK_MAIN();
