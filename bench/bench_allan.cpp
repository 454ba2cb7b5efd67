// Speed of the exact Allan-family estimators: building the double-double phase, and each
// statistic at octave factors (Stable32 stop ratios), single-threaded. The counter
// "ns/sample/tau" is wall time divided by (samples x factors): the cost of one term.
// Error is measured in tests/test_allan_precision.cpp (exact references), not here.
//
// The overlapping estimators (OADEV, OHDEV, TOTDEV) sweep over a compact copy of the phase
// (8 bytes a point) that the series builds on first use and keeps. BM_octave rows build it before
// timing (steady state: the sweep alone). "..._cold" rows drop it before every call, so each call
// pays for building it in fresh pages: the cost of the first statistic computed on a new series.
// BM_samples_to_oadev times the whole in-memory path from samples: the double-double phase
// (PhaseSeries::from_rate, 16 bytes a point in fresh pages) and OADEV at octave taus (sweep copy
// included), as `sigmatau adev` does after reading the log (without intervals).
// Wall time ("Time") counts the time other processes held the cores on a shared machine; "CPU"
// is this thread's user + system time (system: the kernel zeroing fresh pages), the fairer
// figure there.
// Run: bench_allan --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cstdint>
#include <map>
#include <memory>
#include <random>
#include <vector>

#include "sigmatau/allan.hpp"
#include "sigmatau/phase_series.hpp"
#include "sigmatau/taus.hpp"

using namespace sigmatau;

namespace {

/// White noise on an offset, like a gyro axis at rest (the values do not change the speed).
const std::vector<double>& samples(std::int64_t n) {
  static std::map<std::int64_t, std::unique_ptr<std::vector<double>>> cache;
  auto& slot = cache[n];
  if (!slot) {
    slot = std::make_unique<std::vector<double>>(static_cast<std::size_t>(n));
    std::mt19937_64 rng(42);
    std::normal_distribution<double> g(0.0, 1e-3);
    for (auto& v : *slot) v = 0.02 + g(rng);
  }
  return *slot;
}

const PhaseSeries& series(std::int64_t n) {
  static std::map<std::int64_t, std::unique_ptr<PhaseSeries>> cache;
  auto& slot = cache[n];
  if (!slot) slot = std::make_unique<PhaseSeries>(PhaseSeries::from_rate(samples(n), 0.01));
  return *slot;
}

void BM_from_rate(benchmark::State& state) {
  const auto& y = samples(state.range(0));
  for (auto _ : state) {
    auto s = PhaseSeries::from_rate(y, 0.01);
    benchmark::DoNotOptimize(s.hi().data());
  }
  state.counters["ns/sample"] = benchmark::Counter(
      static_cast<double>(state.range(0)) * 1e-9,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void octave(benchmark::State& state, Statistic statistic, bool cold) {
  const auto& s = series(state.range(0));
  const auto m = averaging_factors(TauSpec{}, statistic, s.size(), s.tau0_s());
  if (!cold) benchmark::DoNotOptimize(compute_deviation(s, statistic, m).data());  // the copy
  for (auto _ : state) {
    if (cold) s.drop_sweep_cache();
    auto points = compute_deviation(s, statistic, m);
    benchmark::DoNotOptimize(points.data());
  }
  state.counters["taus"] = static_cast<double>(m.size());
  state.counters["ns/sample/tau"] = benchmark::Counter(
      static_cast<double>(state.range(0)) * static_cast<double>(m.size()) * 1e-9,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_octave(benchmark::State& state, Statistic statistic) { octave(state, statistic, false); }

void BM_samples_to_oadev(benchmark::State& state) {
  const auto& y = samples(state.range(0));
  for (auto _ : state) {
    const auto s = PhaseSeries::from_rate(y, 0.01);
    const auto m = averaging_factors(TauSpec{}, Statistic::oadev, s.size(), s.tau0_s());
    auto points = compute_deviation(s, Statistic::oadev, m);
    benchmark::DoNotOptimize(points.data());
  }
  state.counters["ns/sample"] = benchmark::Counter(
      static_cast<double>(state.range(0)) * 1e-9,
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
void BM_octave_cold(benchmark::State& state, Statistic statistic) { octave(state, statistic, true); }

}  // namespace

BENCHMARK(BM_from_rate)->Arg(10'000'000)->Arg(100'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_octave, oadev, Statistic::oadev)
    ->Arg(1'000'000)->Arg(10'000'000)->Arg(100'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_octave_cold, oadev, Statistic::oadev)
    ->Arg(1'000'000)->Arg(10'000'000)->Arg(100'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_samples_to_oadev)->Arg(10'000'000)->Arg(100'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_octave, adev, Statistic::adev)->Arg(10'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_octave, mdev, Statistic::mdev)->Arg(10'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_octave, hdev, Statistic::hdev)->Arg(10'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_octave, ohdev, Statistic::ohdev)->Arg(10'000'000)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_octave, totdev, Statistic::totdev)->Arg(10'000'000)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
