// Simulator throughput (samples per second over all channels) and memory-bounded streaming:
// a 6-axis log with every term at 1 kHz, generated block by block and discarded. The issue's
// target is a 24 h log at >= 20 M samples/s in total; run with --benchmark_filter=Day for it.
#include <benchmark/benchmark.h>

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

void run(benchmark::State& state, std::int64_t samples) {
  const auto config = every_term(samples, static_cast<unsigned>(state.range(0)));
  std::vector<double> block(static_cast<std::size_t>(65536 * 6));
  for (auto _ : state) {
    sigmatau::Simulator sim(config);
    while (sim.next(block, 65536) > 0) benchmark::DoNotOptimize(block.data());
  }
  state.counters["samples_per_s"] = benchmark::Counter(
      static_cast<double>(samples * 6) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate);
}

void BM_SimulateTenMinutes(benchmark::State& state) { run(state, 600'000); }
void BM_SimulateDay(benchmark::State& state) { run(state, 86'400'000); }

}  // namespace

BENCHMARK(BM_SimulateTenMinutes)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SimulateDay)->Arg(2)->Iterations(1)->Unit(benchmark::kSecond);
BENCHMARK_MAIN();
