// The overlapping sweep (lib/src/allan_sweep.cpp) computes runs of octave factors together:
// fused kernels that share the phase points of neighbouring factors, and for factors from 4096
// on, chains that walk the compact phase m0 points at a time. The modified sums (MDEV, TDEV;
// lib/src/allan_sums.cpp) run up to eight factors in lock step, one per vector lane, and finish
// each factor's last blocks alone. Each factor's sum must be the
// same, bit for bit, as when that factor is computed alone (one-factor kernels, block sweep):
// same terms, same lanes, same order of additions. Any difference is a bug, so the comparisons
// are exact.
#include <cstdint>
#include <random>
#include <vector>

#include "sigmatau/allan.hpp"
#include "sigmatau/phase_series.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

/// White noise plus a random walk on a large offset: the compact phase's base blocks then carry
/// large, different values, so the base part of each difference is far from zero.
std::vector<double> gyro_like(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> y(n);
  double walk = 0.0;
  for (auto& v : y) {
    walk += 1e-3 * g(rng);
    v = 1e3 + 1e-2 * g(rng) + walk;
  }
  return y;
}

/// Every factor of `m` computed together, then each on its own: equal bit for bit.
void check_alone_equals_together(const PhaseSeries& series, Statistic statistic,
                                 const std::vector<std::int64_t>& m) {
  const auto together = compute_deviation(series, statistic, m);
  REQUIRE(together.size() == m.size());
  for (std::size_t i = 0; i < m.size(); ++i) {
    const std::int64_t one[1] = {m[i]};
    const auto alone = compute_deviation(series, statistic, one);
    REQUIRE(alone.size() == 1);
    INFO(to_string(statistic) << " m = " << m[i]);
    CHECK(alone[0].n_terms == together[i].n_terms);
    CHECK(alone[0].dev == together[i].dev);  // exact: same operations in the same order
    CHECK(together[i].dev > 0.0);
  }
}

}  // namespace

TEST_CASE("octave runs swept together equal each factor swept alone, bit for bit") {
  // N - 2m and N - 3m are not multiples of the 2048-term blocks, so every factor ends in a
  // partial block (computed outside the fused kernels) at a different place.
  const std::size_t n = 300001;
  const PhaseSeries series = PhaseSeries::from_rate(gyro_like(n, 7), 0.01);
  std::vector<std::int64_t> octave;
  for (std::int64_t m = 1; m <= 65536; m *= 2) octave.push_back(m);
  // 1..2048: two fused groups on the double-double phase; 4096..65536: one chain group.
  check_alone_equals_together(series, Statistic::oadev, octave);
  check_alone_equals_together(series, Statistic::ohdev, octave);
  check_alone_equals_together(series, Statistic::totdev, octave);
}

TEST_CASE("mixed factor lists: octave runs, non-octave factors and runs broken by gaps") {
  const PhaseSeries series = PhaseSeries::from_samples(gyro_like(200003, 11), DataKind::increment, 0.001);
  // 3 and 6 double (a fused pair); 5000 is not a multiple of the base block (block sweep with
  // cuts); 12288 and 24576 (3 x 4096, doubling: a chain of two); 40000 alone.
  const std::vector<std::int64_t> m = {1, 3, 6, 7, 64, 128, 5000, 12288, 24576, 40000};
  check_alone_equals_together(series, Statistic::oadev, m);
  check_alone_equals_together(series, Statistic::ohdev, m);
}

TEST_CASE("modified sums in lock step equal each factor alone, bit for bit") {
  // 17 octave factors: two groups of eight in lock step and one alone; N - 3m + 1 is not a
  // multiple of the 1024-step blocks, so each factor leaves the lock step at a different block
  // (its lane then idles) and ends in a partial block of its own.
  const PhaseSeries series = PhaseSeries::from_rate(gyro_like(300001, 5), 0.01);
  std::vector<std::int64_t> octave;
  for (std::int64_t m = 1; m <= 65536; m *= 2) octave.push_back(m);
  check_alone_equals_together(series, Statistic::mdev, octave);
  check_alone_equals_together(series, Statistic::tdev, octave);
  // Non-octave factors; the second group of four has 3003, 1005, 6 and 3 terms (two full
  // blocks, then none).
  const std::vector<std::int64_t> mixed = {1, 3, 7, 1000, 33333, 66666, 99000, 99666, 99999,
                                           100000, 2, 5};
  check_alone_equals_together(series, Statistic::mdev, mixed);
  // Shared among threads (groups of factors on each): the same bits.
  for (const unsigned threads : {2u, 3u}) {
    const auto one = compute_deviation(series, Statistic::mdev, octave, 1);
    const auto shared = compute_deviation(series, Statistic::mdev, octave, threads);
    REQUIRE(shared.size() == one.size());
    for (std::size_t i = 0; i < one.size(); ++i) {
      INFO("threads = " << threads << ", m = " << one[i].m);
      CHECK(shared[i].dev == one[i].dev);
    }
  }
}

TEST_CASE("factor order does not change any value") {
  const PhaseSeries series = PhaseSeries::from_rate(gyro_like(100003, 3), 1.0);
  const std::vector<std::int64_t> ascending = {1, 2, 4, 8, 4096, 8192, 16384};
  const std::vector<std::int64_t> shuffled = {8192, 2, 16384, 1, 4096, 8, 4};
  const auto a = compute_deviation(series, Statistic::oadev, ascending);
  const auto b = compute_deviation(series, Statistic::oadev, shuffled);
  REQUIRE(a.size() == ascending.size());
  REQUIRE(b.size() == shuffled.size());
  for (std::size_t i = 0; i < shuffled.size(); ++i) {
    std::size_t j = 0;
    while (ascending[j] != shuffled[i]) ++j;
    INFO("m = " << shuffled[i]);
    CHECK(b[i].dev == a[j].dev);
  }
}
