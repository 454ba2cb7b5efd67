// Exact out-of-core mode: the phase built in pieces (PhaseSeriesBuilder), kept in spilled
// (file-backed) storage, and the curves of compute_allan_curves_out_of_core must equal the
// in-memory path bit for bit: same code on the same numbers, so any difference is a bug.
// The spilled storage runs with a tiny resident budget (64 KiB), so the page watchdog drops the
// mappings while the estimators run and the long noise-identification series are spilled too.
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "sigmatau/allan.hpp"
#include "sigmatau/allan_curve.hpp"
#include "sigmatau/allan_out_of_core.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/phase_series.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

constexpr Statistic kAll[] = {Statistic::adev,  Statistic::oadev, Statistic::mdev,
                              Statistic::tdev,  Statistic::hdev,  Statistic::ohdev,
                              Statistic::totdev};

PhaseStorage tiny_spill() {
  PhaseStorage s;
  s.spill = true;
  s.resident_bytes = 64 << 10;
  return s;
}

/// White noise plus a random walk on a large offset (gyro-like, and hard for the phase).
std::vector<double> gyro_like(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> y(n);
  double walk = 0;
  for (auto& v : y) {
    walk += 1e-4 * g(rng);
    v = 1e3 + 1e-2 * g(rng) + walk;
  }
  return y;
}

bool same_bits(const std::vector<double>& a, std::span<const double> b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](double x, double y) {
           return std::memcmp(&x, &y, sizeof x) == 0;
         });
}

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

void check_same_curve(const AllanCurve& a, const AllanCurve& b) {
  REQUIRE(a.points.size() == b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    const auto& p = a.points[i];
    const auto& q = b.points[i];
    CAPTURE(p.value.m);
    CHECK(p.value.m == q.value.m);
    CHECK(p.value.n_terms == q.value.n_terms);
    CHECK(same_bits(p.value.dev, q.value.dev));
    CHECK(p.confidence.noise.alpha == q.confidence.noise.alpha);
    CHECK(p.confidence.noise.method == q.confidence.noise.method);
    CHECK(same_bits(p.confidence.edf, q.confidence.edf));
    CHECK(same_bits(p.confidence.interval.low, q.confidence.interval.low));
    CHECK(same_bits(p.confidence.interval.high, q.confidence.interval.high));
  }
}

}  // namespace

TEST_CASE("PhaseSeriesBuilder in pieces of any size equals from_samples bit for bit") {
  const auto y = gyro_like(100'003, 1);
  for (const DataKind kind : {DataKind::rate, DataKind::increment, DataKind::phase}) {
    CAPTURE(to_string(kind));
    const PhaseSeries whole = PhaseSeries::from_samples(y, kind, 0.01);
    // Odd piece sizes straddle the 4096-sample blocks of the mean and of the prefix.
    for (const std::size_t piece : {std::size_t{1}, std::size_t{7}, std::size_t{4095},
                                    std::size_t{4097}, std::size_t{65536}}) {
      CAPTURE(piece);
      PhaseSeriesBuilder builder(kind);
      for (std::size_t i = 0; i < y.size(); i += piece) {
        builder.scan(std::span(y).subspan(i, std::min(piece, y.size() - i)));
      }
      CHECK(builder.samples() == static_cast<std::int64_t>(y.size()));
      for (std::size_t i = 0; i < y.size(); i += 3 * piece) {
        builder.append(std::span(y).subspan(i, std::min(3 * piece, y.size() - i)));
      }
      const PhaseSeries built = builder.finish(0.01);
      CHECK(built.size() == whole.size());
      CHECK(same_bits(std::vector<double>(whole.hi().begin(), whole.hi().end()), built.hi()));
      CHECK(same_bits(std::vector<double>(whole.lo().begin(), whole.lo().end()), built.lo()));
      CHECK(same_bits(built.mean_rate(), whole.mean_rate()));
    }
  }
}

TEST_CASE("PhaseSeriesBuilder names the first non-finite sample across pieces") {
  std::vector<double> y(10'000, 1.0);
  y[5'000] = std::nan("");
  PhaseSeriesBuilder builder(DataKind::rate);
  builder.scan(std::span(y).first(4'000));
  CHECK_THROWS_WITH_AS(builder.scan(std::span(y).subspan(4'000)),
                       doctest::Contains("sample 5000 (0-based) is not finite"), Error);
}

TEST_CASE("PhaseSeriesBuilder refuses a second pass that differs in length") {
  const std::vector<double> y(1'000, 2.0);
  PhaseSeriesBuilder builder(DataKind::rate);
  builder.scan(y);
  builder.append(std::span(y).first(999));
  CHECK_THROWS_AS(builder.finish(1.0), Error);
  PhaseSeriesBuilder more(DataKind::rate);
  more.scan(std::span(y).first(10));
  CHECK_THROWS_AS(more.append(std::span(y).first(11)), Error);
}

TEST_CASE("spilled series give every statistic bit for bit as in memory") {
  for (const std::size_t n : {std::size_t{100'000}, std::size_t{1'000'000}}) {
    CAPTURE(n);
    const auto y = gyro_like(n, 2 + n);
    const PhaseSeries memory = PhaseSeries::from_rate(y, 0.01);
    const PhaseSeries spilled = PhaseSeries::from_rate(y, 0.01, tiny_spill());
    CHECK_FALSE(memory.spilled());
    REQUIRE(spilled.spilled());
    for (const Statistic s : kAll) {
      CAPTURE(to_string(s));
      // Octave factors reach n/4 here, so the compact sweep (factors >= 4096) is exercised.
      const auto m = averaging_factors(TauSpec{}, s, memory.size(), memory.tau0_s());
      const auto a = compute_deviation(memory, s, m);
      const auto b = compute_deviation(spilled, s, m);
      REQUIRE(a.size() == b.size());
      for (std::size_t i = 0; i < a.size(); ++i) {
        CHECK(a[i].n_terms == b[i].n_terms);
        CHECK(same_bits(a[i].dev, b[i].dev));
      }
      // And the full curve, with noise identification on spilled series (tiny budget).
      check_same_curve(compute_allan_curve(memory, s, TauSpec{}, 0.683),
                       compute_allan_curve_bounded(spilled, s, TauSpec{}, 0.683, tiny_spill()));
    }
  }
}

TEST_CASE("the kept sweep copy gives the same numbers as a fresh one") {
  const auto y = gyro_like(300'000, 3);
  const PhaseSeries series = PhaseSeries::from_rate(y, 0.01);
  const auto m = averaging_factors(TauSpec{}, Statistic::oadev, series.size(), series.tau0_s());
  const auto first = compute_deviation(series, Statistic::oadev, m);   // builds the copy
  const auto second = compute_deviation(series, Statistic::oadev, m);  // reuses it
  series.drop_sweep_cache();
  const auto third = compute_deviation(series, Statistic::oadev, m);   // builds it again
  REQUIRE(first.size() == second.size());
  REQUIRE(first.size() == third.size());
  for (std::size_t i = 0; i < first.size(); ++i) {
    CHECK(same_bits(first[i].dev, second[i].dev));
    CHECK(same_bits(first[i].dev, third[i].dev));
  }
}

TEST_CASE("compute_allan_curves_out_of_core on a binary file equals the in-memory curves") {
  constexpr std::size_t kRows = 200'000;
  constexpr int kChannels = 3;
  std::vector<std::vector<double>> channel;
  for (int c = 0; c < kChannels; ++c) channel.push_back(gyro_like(kRows, 10 + c));
  const auto path = std::filesystem::temp_directory_path() /
                    ("sigmatau_ooc_" + std::to_string(::getpid()) + ".f64");
  {
    std::ofstream out(path, std::ios::binary);
    for (std::size_t r = 0; r < kRows; ++r) {
      for (int c = 0; c < kChannels; ++c) out.write(reinterpret_cast<const char*>(&channel[c][r]), 8);
    }
  }
  LogOptions log;
  log.path = path.string();
  log.binary = BinaryFormat::f64;
  log.binary_channels = kChannels;
  const std::vector<Statistic> stats(std::begin(kAll), std::end(kAll));
  const double to_si = 0.5;  // exercises the unit conversion of both paths the same way
  for (const unsigned threads : {1u, 2u}) {
    CAPTURE(threads);
    OutOfCoreSettings settings;
    settings.storage = tiny_spill();
    settings.threads = threads;
    const auto result = compute_allan_curves_out_of_core(
        log, DataKind::rate, to_si, [](const TimingReport&) { return 100.0; }, stats, TauSpec{},
        0.683, settings);
    CHECK(result.samples == static_cast<std::int64_t>(kRows));
    CHECK(result.channel_names.size() == static_cast<std::size_t>(kChannels));
    std::vector<PhaseSeries> memory;
    for (auto v : channel) {
      for (double& x : v) x *= to_si;
      memory.push_back(PhaseSeries::from_rate(v, 0.01));
    }
    const auto expected = compute_allan_curves(memory, stats, TauSpec{}, 0.683, 1);
    REQUIRE(result.curves.size() == expected.size());
    for (std::size_t c = 0; c < expected.size(); ++c) {
      for (std::size_t s = 0; s < stats.size(); ++s) {
        CAPTURE(c);
        CAPTURE(to_string(stats[s]));
        check_same_curve(result.curves[c][s], expected[c][s]);
      }
    }
  }
  std::filesystem::remove(path);
}

TEST_CASE("out-of-core mode refuses stdin") {
  LogOptions log;
  log.path = "-";
  CHECK_THROWS_WITH_AS(compute_allan_curves_out_of_core(
                           log, DataKind::rate, 1.0, [](const TimingReport&) { return 1.0; },
                           {Statistic::oadev}, TauSpec{}, 0.683),
                       doctest::Contains("stream"), Error);
}
