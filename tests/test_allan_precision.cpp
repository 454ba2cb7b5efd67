// Precision: every statistic against an exact reference on inputs that are hard for floating
// point (a large offset, 1e8 samples, integer counts, float32 input, constant input, random
// walks, a ramp). The reference is written independently of the library, straight from the
// SP 1065 formulas on the un-centred phase: prefix sums are exact (int64 / __int128 for integer
// data, __float128 for data whose binary range fits its 113-bit significand), every difference
// is exact, and only the squares are summed in __float128 (relative error ~1e-30).
// __float128 arithmetic comes from libgcc; no libquadmath function is used.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "sigmatau/allan.hpp"
#include "sigmatau/phase_series.hpp"
#include "sigmatau/taus.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

__extension__ typedef __float128 Quad;
__extension__ typedef __int128 Int128;

/// Required agreement with the exact reference. The library's own error is ~1e-13 at most
/// (double-double phase, window sums to ~1 ulp, blocked sums); 1e-9 leaves room for the
/// condition of the data (differences much smaller than the window sums they come from) while
/// still failing for any real loss of precision, which shows up at 1e-6 or worse.
constexpr double kExact = 1e-9;

constexpr Statistic kAllStatistics[] = {Statistic::adev, Statistic::oadev, Statistic::mdev,
                                        Statistic::tdev, Statistic::hdev,  Statistic::ohdev,
                                        Statistic::totdev};

Quad to_quad(Int128 v) { return static_cast<Quad>(v); }
Quad to_quad(Quad v) { return v; }
Quad to_quad(std::int64_t v) { return static_cast<Quad>(v); }

/// Exact phase of the input, without removing the mean: P[0] = 0, P[k] = y_1 + ... + y_k for
/// rate input (unit: input x samples), P[k] = x[k] for phase input. T must hold it exactly.
template <typename T, typename Value>
std::vector<T> phase_of(const std::vector<Value>& v, bool rate) {
  std::vector<T> p;
  p.reserve(v.size() + 1);
  if (rate) p.push_back(T(0));
  T sum(0);
  for (const Value value : v) {
    if (rate) {
      sum += static_cast<T>(value);
      p.push_back(sum);
    } else {
      p.push_back(static_cast<T>(value));
    }
  }
  return p;
}

/// Deviation from the exact phase P (N points), straight from SP 1065. S is the type of the
/// second prefix used by MVAR (exact sums of P). `rate`: P in input x samples (scale 1/m),
/// otherwise in input units with scale 1/(m tau0).
template <typename T, typename S>
double reference_dev(const std::vector<T>& P, Statistic statistic, std::int64_t m, bool rate,
                     double tau0) {
  const std::int64_t N = static_cast<std::int64_t>(P.size());
  const std::int64_t n = term_count(statistic, m, N);
  REQUIRE(n > 0);
  Quad sum = 0;
  auto d2 = [&](std::int64_t i) { return P[i + 2 * m] - T(2) * P[i + m] + P[i]; };
  auto d3 = [&](std::int64_t i) { return P[i + 3 * m] - T(3) * P[i + 2 * m] + T(3) * P[i + m] - P[i]; };
  switch (statistic) {
    case Statistic::adev:
      for (std::int64_t k = 0; k < n; ++k) sum += to_quad(d2(k * m)) * to_quad(d2(k * m));
      break;
    case Statistic::oadev:
      for (std::int64_t i = 0; i < n; ++i) sum += to_quad(d2(i)) * to_quad(d2(i));
      break;
    case Statistic::hdev:
      for (std::int64_t k = 0; k < n; ++k) sum += to_quad(d3(k * m)) * to_quad(d3(k * m));
      break;
    case Statistic::ohdev:
      for (std::int64_t i = 0; i < n; ++i) sum += to_quad(d3(i)) * to_quad(d3(i));
      break;
    case Statistic::mdev:
    case Statistic::tdev: {
      // Q[k] = P[0] + ... + P[k-1]; sum_{i=j}^{j+m-1} P[i + c] = Q[j+c+m] - Q[j+c].
      std::vector<S> Q(P.size() + 1, S(0));
      for (std::size_t k = 0; k < P.size(); ++k) Q[k + 1] = Q[k] + static_cast<S>(P[k]);
      for (std::int64_t j = 0; j < n; ++j) {
        const S v = (Q[j + 3 * m] - Q[j + 2 * m]) - S(2) * (Q[j + 2 * m] - Q[j + m]) +
                    (Q[j + m] - Q[j]);
        sum += to_quad(v) * to_quad(v);
      }
      break;
    }
    case Statistic::totdev: {
      const std::int64_t L = N - 1;
      auto xs = [&](std::int64_t k) {
        if (k < 0) return T(2) * P[0] - P[-k];
        if (k > L) return T(2) * P[L] - P[2 * L - k];
        return P[k];
      };
      for (std::int64_t i = 1; i <= L - 1; ++i) {
        const T d = xs(i - m) - T(2) * xs(i) + xs(i + m);
        sum += to_quad(d) * to_quad(d);
      }
      break;
    }
  }
  const Quad md = m;
  const Quad scale2 = rate ? 1 / (md * md) : 1 / (md * md * tau0 * tau0);
  Quad var = sum / n * scale2;
  switch (statistic) {
    case Statistic::adev:
    case Statistic::oadev:
    case Statistic::totdev: var /= 2; break;
    case Statistic::hdev:
    case Statistic::ohdev: var /= 6; break;
    case Statistic::mdev: var /= 2 * md * md; break;
    case Statistic::tdev: var = var / (2 * md * md) * (md * tau0) * (md * tau0) / 3; break;
  }
  return std::sqrt(static_cast<double>(var));
}

/// Octave factors up to the Stable32 stop ratio.
std::vector<std::int64_t> octave(Statistic statistic, std::int64_t N) {
  return averaging_factors(TauSpec{}, statistic, N, 1.0);
}

/// Compares every statistic at every octave factor with the exact reference.
template <typename T, typename S>
void check_all(const PhaseSeries& series, const std::vector<T>& P, bool rate) {
  REQUIRE(static_cast<std::int64_t>(P.size()) == series.size());
  for (const Statistic statistic : kAllStatistics) {
    const auto m = octave(statistic, series.size());
    const auto points = compute_deviation(series, statistic, m);
    REQUIRE(points.size() == m.size());
    double worst = 0.0;
    for (const auto& p : points) {
      const double expected = reference_dev<T, S>(P, statistic, p.m, rate, series.tau0_s());
      INFO(to_string(statistic) << " m=" << p.m);
      CHECK(p.dev == test::rel(expected, kExact));
      worst = std::max(worst, std::abs(p.dev / expected - 1.0));
    }
    MESSAGE(to_string(statistic) << ": " << m.size() << " factors, worst relative error " << worst);
  }
}

}  // namespace

TEST_CASE("white noise on an offset of 1e6 times its amplitude") {
  // y = 1e6 + N(0, 1): every sample is a multiple of 2^-33 below 2^20, so the exact phase needs
  // at most 33 + 20 + 18 bits and its prefix 33 + 58 bits: exact in __float128.
  std::mt19937_64 rng(1);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> y(200000);
  for (auto& v : y) v = 1e6 + g(rng);
  const auto series = PhaseSeries::from_rate(y, 0.01);
  check_all<Quad, Quad>(series, phase_of<Quad>(y, true), true);
}

TEST_CASE("int16 counts (a 16-bit ADC near the top of its range)") {
  std::mt19937_64 rng(2);
  std::normal_distribution<double> g(0.0, 30.0);
  std::vector<std::int16_t> counts(1000000);
  for (auto& c : counts) c = static_cast<std::int16_t>(std::clamp(std::lround(30000 + g(rng)), 0L, 32767L));
  const std::vector<double> y(counts.begin(), counts.end());
  const auto series = PhaseSeries::from_rate(y, 1.0 / 400);
  check_all<std::int64_t, Int128>(series, phase_of<std::int64_t>(counts, true), true);
}

TEST_CASE("float32 input (an accelerometer axis near 1 g)") {
  // Floats in [8, 16) are multiples of 2^-20: the exact phase fits __float128 easily.
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g(0.0, 0.05);
  std::vector<float> f(200000);
  for (auto& v : f) v = static_cast<float>(9.81 + g(rng));
  const std::vector<double> y(f.begin(), f.end());
  const auto series = PhaseSeries::from_rate(y, 0.005);
  check_all<Quad, Quad>(series, phase_of<Quad>(f, true), true);
}

TEST_CASE("rate random walk: the phase grows like N^1.5 (1e6 samples)") {
  // Integer steps: the rate, the phase and its prefix are exact integers.
  std::mt19937_64 rng(4);
  std::uniform_int_distribution<int> step(-1000, 1000);
  std::vector<std::int64_t> y(1000000);
  std::int64_t w = 0;
  for (auto& v : y) v = (w += step(rng));
  const std::vector<double> yd(y.begin(), y.end());
  const auto series = PhaseSeries::from_rate(yd, 0.01);
  check_all<std::int64_t, Int128>(series, phase_of<std::int64_t>(y, true), true);
}

TEST_CASE("phase random walk on a 1e9 offset, as phase input (1e6 points)") {
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int> step(-1000, 1000);
  std::vector<std::int64_t> x(1000000);
  std::int64_t w = 1000000000;
  for (auto& v : x) v = (w += step(rng));
  const std::vector<double> xd(x.begin(), x.end());
  const auto series = PhaseSeries::from_phase(xd, 0.5);
  check_all<std::int64_t, Int128>(series, phase_of<std::int64_t>(x, false), false);
}

TEST_CASE("a constant input of 1e6 samples gives exactly 0 and no NaN at every factor") {
  for (const double level : {0.0, -0.0, 1e-300, 0.3, -123.456, 1e6, 9.81, 1e300}) {
    INFO("level " << level);
    const std::vector<double> y(1000000, level);
    for (const DataKind kind : {DataKind::rate, DataKind::increment, DataKind::phase}) {
      const auto series = PhaseSeries::from_samples(y, kind, 0.01);
      for (const Statistic statistic : kAllStatistics) {
        const auto m = octave(statistic, series.size());
        const auto points = compute_deviation(series, statistic, m);
        CHECK(points.size() == m.size());
        for (const auto& p : points) REQUIRE(p.dev == 0.0);
      }
    }
  }
}

TEST_CASE("a rate ramp: OADEV and MDEV are R tau / sqrt(2), OHDEV and HDEV remove it") {
  // Rate y = R t (t = k tau0): every m-sample mean grows by R tau per cluster, so AVAR =
  // MVAR = (R tau)^2 / 2 (SP 1065, linear frequency drift); the third differences of the
  // quadratic phase are exactly 0.
  const double tau0 = 0.01;
  const std::int64_t M = 1000000;
  SUBCASE("integer ramp: every quantity is exact, so the Hadamard deviations are exactly 0") {
    std::vector<double> y(M);
    for (std::int64_t k = 0; k < M; ++k) y[k] = static_cast<double>(k);  // R = 1 / tau0 per s
    const auto series = PhaseSeries::from_rate(y, tau0);
    for (const Statistic statistic : {Statistic::oadev, Statistic::adev, Statistic::mdev}) {
      for (const auto& p : compute_deviation(series, statistic, octave(statistic, M + 1))) {
        CHECK(p.dev == test::rel(static_cast<double>(p.m) / std::sqrt(2.0), kExact));
      }
    }
    for (const Statistic statistic : {Statistic::ohdev, Statistic::hdev}) {
      for (const auto& p : compute_deviation(series, statistic, octave(statistic, M + 1))) {
        CHECK(p.dev == 0.0);
      }
    }
  }
  SUBCASE("inexact ramp R = 1e-3 unit/s on an offset of 0.7") {
    const double R = 1e-3;
    std::vector<double> y(M);
    for (std::int64_t k = 0; k < M; ++k) y[k] = 0.7 + R * tau0 * static_cast<double>(k);
    const auto series = PhaseSeries::from_rate(y, tau0);
    // y_k is R t_k + 0.7 rounded (1e-16 relative of 0.7..10.7): white noise 7e-17 per sample,
    // whose own OADEV (<= 1e-15 at m = 1) is far below kExact x R tau.
    for (const Statistic statistic : {Statistic::oadev, Statistic::mdev}) {
      for (const auto& p : compute_deviation(series, statistic, octave(statistic, M + 1))) {
        INFO(to_string(statistic) << " m=" << p.m);
        CHECK(p.dev == test::rel(R * p.tau_s / std::sqrt(2.0), kExact));
      }
    }
    // OHDEV is then the Hadamard deviation of that rounding noise plus window-sum rounding:
    // each of the 4 window sums in a term is off by <= 2 ulp of |W| <= m max|y - ybar|, so
    // OHDEV <= 8 eps max|y - ybar| (rate units) = 8 eps 5 R tau0 M ~ 4.4e-14 -- i.e. ~0 next to
    // OADEV (>= 7e-6).
    const double bound = 8.0 * std::numeric_limits<double>::epsilon() * 0.5 * R * tau0 * M;
    const auto oadev = compute_deviation(series, Statistic::oadev, octave(Statistic::ohdev, M + 1));
    const auto ohdev = compute_deviation(series, Statistic::ohdev, octave(Statistic::ohdev, M + 1));
    REQUIRE(oadev.size() == ohdev.size());
    for (std::size_t i = 0; i < ohdev.size(); ++i) {
      INFO("m=" << ohdev[i].m << " OHDEV " << ohdev[i].dev << " OADEV " << oadev[i].dev);
      CHECK(ohdev[i].dev <= bound);
      CHECK(ohdev[i].dev <= 1e-8 * oadev[i].dev);
    }
  }
}

TEST_CASE("1e8 integer samples: OADEV at every octave factor, OHDEV and MDEV at two") {
  // Counts 30000 +- 2000 (uniform): the exact phase (int64) reaches 3e12, and the library's
  // phase is far from the data's zero, over a record long enough for any drift to show.
  const std::int64_t M = 100000000;
  std::vector<std::int64_t> P(M + 1);
  std::vector<double> y(M);
  {
    std::mt19937_64 rng(6);
    std::uniform_int_distribution<int> u(-2000, 2000);
    P[0] = 0;
    for (std::int64_t k = 0; k < M; ++k) {
      const int v = 30000 + u(rng);
      y[k] = v;
      P[k + 1] = P[k] + v;
    }
  }
  const auto series = PhaseSeries::from_rate(y, 0.001);
  std::vector<double>().swap(y);

  const auto m = octave(Statistic::oadev, M + 1);
  REQUIRE(m.size() == 25);  // 1 .. 2^24
  const auto points = compute_deviation(series, Statistic::oadev, m);
  REQUIRE(points.size() == m.size());
  double worst = 0.0;
  for (const auto& p : points) {
    // Exact in integers: d fits int64 (|d| <= 4 * 2000 * m), d^2 and the sum fit __int128.
    Int128 sum = 0;
    const std::int64_t n = p.n_terms;
    const std::int64_t* a = P.data();
    const std::int64_t* b = P.data() + p.m;
    const std::int64_t* c = P.data() + 2 * p.m;
    for (std::int64_t i = 0; i < n; ++i) {
      const std::int64_t d = c[i] - 2 * b[i] + a[i];
      sum += static_cast<Int128>(d) * d;
    }
    const Quad md = p.m;
    const double expected = std::sqrt(static_cast<double>(static_cast<Quad>(sum) / n / (2 * md * md)));
    INFO("oadev m=" << p.m);
    CHECK(p.dev == test::rel(expected, kExact));
    worst = std::max(worst, std::abs(p.dev / expected - 1.0));
  }
  MESSAGE("oadev, 1e8 samples: worst relative error " << worst);
  for (const std::int64_t factor : {std::int64_t{1}, std::int64_t{1} << 20}) {
    for (const Statistic statistic : {Statistic::ohdev, Statistic::mdev}) {
      const std::int64_t f[] = {factor};
      const auto p = compute_deviation(series, statistic, f);
      REQUIRE(p.size() == 1);
      // Exact in integers: |D3| <= 8 * 2000 m and the sums stay far below 2^127 for these
      // data (checked: an overflow fails the test).
      Int128 sum = 0;
      bool overflow = false;
      auto add_square = [&](Int128 v) { overflow |= __builtin_add_overflow(sum, v * v, &sum); };
      if (statistic == Statistic::ohdev) {
        for (std::int64_t i = 0; i < p[0].n_terms; ++i) {
          add_square(P[i + 3 * factor] - 3 * P[i + 2 * factor] + 3 * P[i + factor] - P[i]);
        }
      } else {
        // Exact running sum in integers: V(j+1) = V(j) + D2(j+m) - D2(j).
        auto d2 = [&](std::int64_t i) { return P[i + 2 * factor] - 2 * P[i + factor] + P[i]; };
        Int128 v = 0;
        for (std::int64_t i = 0; i < factor; ++i) v += d2(i);
        for (std::int64_t j = 0; j < p[0].n_terms; ++j) {
          add_square(v);
          if (j + 1 < p[0].n_terms) v += d2(j + factor) - d2(j);
        }
      }
      REQUIRE(!overflow);
      const Quad md = factor;
      const Quad mean = static_cast<Quad>(sum) / p[0].n_terms;
      const Quad var = statistic == Statistic::ohdev ? mean / (6 * md * md)
                                                     : mean / (2 * md * md * md * md);
      INFO(to_string(statistic) << " m=" << factor);
      CHECK(p[0].dev == test::rel(std::sqrt(static_cast<double>(var)), kExact));
    }
  }
}
