// PhaseSeries::recycle: the samples' memory handed back becomes the sweep copy (no fresh
// pages), and the deviations are the same to the last bit (issue 25).
#include <doctest/doctest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "../lib/src/allan_sums.hpp"  // internal interface under test
#include "sigmatau/allan.hpp"
#include "sigmatau/phase_series.hpp"

using namespace sigmatau;

namespace {
std::vector<double> noise(std::size_t n) {
  std::mt19937_64 rng(77);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> v(n);
  double walk = 0;
  for (double& x : v) x = normal(rng) + (walk += 1e-3 * normal(rng));
  return v;
}
}  // namespace

TEST_CASE("a recycled sample buffer holds the sweep copy and changes no deviation") {
  constexpr std::size_t kSamples = 100000;  // factors from 4096 on use the sweep copy
  const std::vector<double> y = noise(kSamples);
  const PhaseSeries fresh = PhaseSeries::from_rate(y, 0.01);
  std::vector<double> memory = y;
  memory.reserve(kSamples + 1);  // the phase has one point more than the samples
  const double* given = memory.data();
  const PhaseSeries reused = PhaseSeries::from_rate(y, 0.01);
  reused.recycle(std::move(memory));
  const std::vector<std::int64_t> m = {1, 16, 4096, 8192, 16384};
  const auto a = compute_deviation(fresh, Statistic::oadev, m);
  const auto b = compute_deviation(reused, Statistic::oadev, m);
  REQUIRE(a.size() == b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    CAPTURE(a[i].m);
    CHECK(a[i].dev == b[i].dev);  // bit for bit: the same operations on the same values
  }
  CHECK(detail::compact_phase(reused)->offset.data() == given);
  CHECK(detail::compact_phase(fresh)->offset.data() != given);
}

TEST_CASE("memory too small for the phase is not kept") {
  const std::vector<double> y = noise(20000);
  const PhaseSeries series = PhaseSeries::from_rate(y, 1.0);
  std::vector<double> small(y);  // capacity 20000 < 20001 points
  small.shrink_to_fit();
  const double* given = small.data();
  series.recycle(std::move(small));
  CHECK(detail::compact_phase(series)->offset.data() != given);
}
