// The bounded-memory single-pass mode (allan_stream.hpp): equal to the exact estimators where the
// stride is 1, exact strided terms otherwise (against an independent long-double reference),
// independent of how the input is split, bounded memory, and EDFs that match the scatter of
// simulated estimates.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "sigmatau/allan_curve.hpp"
#include "sigmatau/allan_stream.hpp"
#include "sigmatau/error.hpp"
#include "test_support.hpp"

using namespace sigmatau;
using test::rel;

namespace {

/// White FM plus a slow random walk of the rate on an offset, like a gyro axis at rest.
std::vector<double> gyro_like(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> y(n);
  double walk = 0.0;
  for (auto& v : y) {
    walk += 1e-3 * g(rng);
    v = 0.02 + 1e-2 * g(rng) + 1e-2 * walk;
  }
  return y;
}

AllanStream stream_of(const std::vector<double>& y, DataKind kind, const StreamSettings& settings,
                      std::size_t piece = 1 << 30) {
  AllanStream stream(kind, 0.01, settings);
  for (std::size_t i = 0; i < y.size(); i += piece) {
    const std::size_t n = std::min(piece, y.size() - i);
    stream.add(std::span<const double>(y).subspan(i, n));
  }
  return stream;
}

/// Strided OADEV/OHDEV/MDEV at factor m, start points every s, straight from SP 1065 eqs. 11, 20,
/// 14 on the long-double phase (written apart from the library: no window sums, no blocking).
double reference_strided(const std::vector<double>& y, Statistic statistic, std::int64_t m,
                         std::int64_t s, std::int64_t& terms) {
  std::vector<long double> x(y.size() + 1, 0.0L);
  long double mean = 0;
  for (const double v : y) mean += v;
  mean /= static_cast<long double>(y.size());
  for (std::size_t k = 0; k < y.size(); ++k) x[k + 1] = x[k] + (y[k] - mean);
  const auto N = static_cast<std::int64_t>(x.size());
  long double sum = 0;
  terms = 0;
  for (std::int64_t n = 0;; n += s) {
    long double d = 0;
    if (statistic == Statistic::oadev) {
      if (n + 2 * m >= N) break;
      d = x[n + 2 * m] - 2 * x[n + m] + x[n];
    } else if (statistic == Statistic::ohdev) {
      if (n + 3 * m >= N) break;
      d = x[n + 3 * m] - 3 * x[n + 2 * m] + 3 * x[n + m] - x[n];
    } else {
      if (n + 3 * m > N) break;
      for (std::int64_t i = n; i < n + m; ++i) d += x[i + 2 * m] - 2 * x[i + m] + x[i];
    }
    sum += d * d;
    ++terms;
  }
  const long double md = m;
  const long double ms = sum / terms;
  long double var = statistic == Statistic::oadev   ? ms / 2
                    : statistic == Statistic::ohdev ? ms / 6
                                                    : ms / (2 * md * md);
  return static_cast<double>(std::sqrt(var) / md);  // rate input: scale 1/m
}

}  // namespace

TEST_CASE("with stride 1 at every tau the stream equals the exact estimator") {
  const auto y = gyro_like(200000, 1);
  const auto series = PhaseSeries::from_rate(y, 0.01);
  StreamSettings settings;
  settings.statistics = {Statistic::oadev, Statistic::ohdev, Statistic::mdev,
                         Statistic::tdev,  Statistic::adev,  Statistic::hdev};
  settings.density = 1 << 20;  // s = max(1, m / K) = 1 for every m of this log
  const auto stream = stream_of(y, DataKind::rate, settings);
  REQUIRE(stream.size() == series.size());
  const auto curves = stream.curves(0.683);
  REQUIRE(curves.size() == settings.statistics.size());
  for (std::size_t i = 0; i < curves.size(); ++i) {
    const auto exact = compute_allan_curve(series, settings.statistics[i], TauSpec{}, 0.683);
    CAPTURE(to_string(settings.statistics[i]));
    REQUIRE(curves[i].points.size() == exact.points.size());
    for (std::size_t k = 0; k < exact.points.size(); ++k) {
      const auto& a = curves[i].points[k];
      const auto& b = exact.points[k];
      CAPTURE(b.value.m);
      CHECK(a.value.m == b.value.m);
      CHECK(a.value.n_terms == b.value.n_terms);
      // Same terms; the stream removes a provisional mean and sums in other blocks, so the
      // rounding differs: both are within ~1e-14 of the exact value (test_allan_precision).
      CHECK(a.value.dev == rel(b.value.dev, 1e-12));
      // Where >= 30 averages remain both identify the noise by the lag-1 ACF (one-pass sums
      // here, two-pass there): the same type, so the same EDF. Below, the stream's B1 ratio uses
      // the term count of its short series of means (allan_stream.hpp), so it may differ.
      if ((series.size() - 1) / b.value.m >= 30) {
        CHECK(a.confidence.noise.alpha == b.confidence.noise.alpha);
        CHECK(a.confidence.edf == rel(b.confidence.edf, 1e-12));
      }
    }
  }
}

TEST_CASE("the one-pass noise sums identify each power-law type as identify_noise does") {
  // White PM, white FM and random-walk FM rate series: identification differences z 0, 1 or
  // 2 times (3 for the Hadamard statistics), so every series the one-pass sums keep is used.
  constexpr std::size_t kLength = 100000;
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> white(kLength + 1);
  for (auto& v : white) v = g(rng);
  struct Case {
    const char* name;
    int alpha;
    std::vector<double> y;
  };
  std::vector<Case> cases = {{"white PM", 2, {}}, {"white FM", 0, {}}, {"random-walk FM", -2, {}}};
  double walk = 0;
  for (std::size_t k = 0; k < kLength; ++k) {
    cases[0].y.push_back(white[k + 1] - white[k]);  // rate of a white phase
    cases[1].y.push_back(white[k]);
    cases[2].y.push_back(walk += white[k]);
  }
  StreamSettings settings;
  settings.statistics = {Statistic::oadev, Statistic::ohdev, Statistic::mdev};
  settings.density = 1 << 20;  // stride 1: the exact curve is the reference, point by point
  for (const Case& c : cases) {
    CAPTURE(c.name);
    const auto series = PhaseSeries::from_rate(c.y, 1.0);
    const auto curves = stream_of(c.y, DataKind::rate, settings, 5000).curves(0.683);
    for (std::size_t i = 0; i < curves.size(); ++i) {
      const auto exact = compute_allan_curve(series, settings.statistics[i], TauSpec{}, 0.683);
      CAPTURE(to_string(settings.statistics[i]));
      REQUIRE(curves[i].points.size() == exact.points.size());
      // The simulated type at the shortest tau (hundreds of thousands of points: no doubt).
      CHECK(curves[i].points.front().confidence.noise.alpha == c.alpha);
      for (std::size_t k = 0; k < exact.points.size(); ++k) {
        if ((series.size() - 1) / exact.points[k].value.m < 30) break;  // lag-1 ACF range
        CAPTURE(exact.points[k].value.m);
        CHECK(curves[i].points[k].confidence.noise.alpha == exact.points[k].confidence.noise.alpha);
      }
    }
  }
}

TEST_CASE("a constant input gives exactly 0, and a huge offset costs no accuracy") {
  StreamSettings settings;
  settings.statistics = {Statistic::oadev, Statistic::ohdev, Statistic::mdev, Statistic::adev};
  for (const double level : {0.0, 0.3, -123.456, 1e6, 1e300}) {
    CAPTURE(level);
    const std::vector<double> y(50000, level);
    for (const DataKind kind : {DataKind::rate, DataKind::increment, DataKind::phase}) {
      const auto curves = stream_of(y, kind, settings).curves(0.683);
      for (const auto& curve : curves) {
        REQUIRE(!curve.points.empty());
        for (const auto& p : curve.points) {
          CAPTURE(p.value.m);
          CHECK(p.value.dev == 0.0);  // as the exact mode (test_allan_precision)
          CHECK(std::isfinite(p.confidence.edf));
        }
      }
    }
  }
  // 1e6 + white noise of unit size: the stream removes the mean of its first chunk, the exact
  // mode the mean of the whole log; both carry the phase in double-double, so they agree as
  // closely as in the first test case.
  auto y = gyro_like(60000, 8);
  for (auto& v : y) v = 1e6 + 100 * v;
  const auto series = PhaseSeries::from_rate(y, 0.01);
  settings.density = 1 << 20;
  const auto curves = stream_of(y, DataKind::rate, settings).curves(0.683);
  for (std::size_t i = 0; i < curves.size(); ++i) {
    const auto exact = compute_allan_curve(series, settings.statistics[i], TauSpec{}, 0.683);
    REQUIRE(curves[i].points.size() == exact.points.size());
    for (std::size_t k = 0; k < exact.points.size(); ++k) {
      CAPTURE(exact.points[k].value.m);
      CHECK(curves[i].points[k].value.dev == rel(exact.points[k].value.dev, 1e-12));
    }
  }
}

TEST_CASE("strided terms are terms of the exact estimator") {
  const auto y = gyro_like(30000, 2);
  for (const Statistic statistic : {Statistic::oadev, Statistic::ohdev, Statistic::mdev}) {
    for (const int density : {1, 2, 8}) {
      StreamSettings settings;
      settings.statistics = {statistic};
      settings.density = density;
      const auto stream = stream_of(y, DataKind::rate, settings);
      const auto curve = stream.curves(0.683).front();
      REQUIRE(!curve.points.empty());
      for (const auto& p : curve.points) {
        if (p.value.m > 512) break;  // the reference is O(N m) for MDEV
        const std::int64_t s = stream.stride(statistic, p.value.m);
        CHECK(s == std::max<std::int64_t>(1, p.value.m / density));
        std::int64_t terms = 0;
        const double expected = reference_strided(y, statistic, p.value.m, s, terms);
        CAPTURE(to_string(statistic));
        CAPTURE(density);
        CAPTURE(p.value.m);
        CHECK(p.value.n_terms == terms);
        // The reference phase is long double (64-bit significand) with the mean removed; both
        // are far more accurate than this tolerance, which would still catch a wrong term.
        CHECK(p.value.dev == rel(expected, 1e-10));
      }
    }
  }
}

TEST_CASE("the result does not depend on how the input is split") {
  const auto y = gyro_like(150000, 3);
  StreamSettings settings;
  settings.statistics = {Statistic::oadev, Statistic::mdev, Statistic::hdev};
  const auto whole = stream_of(y, DataKind::rate, settings).curves(0.683);
  for (const std::size_t piece : {1, 7, 4096, 65537}) {
    const auto split = stream_of(y, DataKind::rate, settings, piece).curves(0.683);
    REQUIRE(split.size() == whole.size());
    for (std::size_t i = 0; i < whole.size(); ++i) {
      REQUIRE(split[i].points.size() == whole[i].points.size());
      for (std::size_t k = 0; k < whole[i].points.size(); ++k) {
        // Bit for bit: the stream re-chunks its input into fixed pieces.
        CHECK(split[i].points[k].value.dev == whole[i].points[k].value.dev);
        CHECK(split[i].points[k].confidence.edf == whole[i].points[k].confidence.edf);
      }
    }
  }
}

TEST_CASE("phase and increment input give the same deviations as the exact mode") {
  const auto y = gyro_like(50000, 4);
  std::vector<double> phase(y.size());
  double acc = 0;
  for (std::size_t i = 0; i < y.size(); ++i) phase[i] = (acc += y[i] * 0.01);
  StreamSettings settings;
  settings.density = 4;
  for (const DataKind kind : {DataKind::phase, DataKind::increment}) {
    const auto& input = kind == DataKind::phase ? phase : y;
    const auto series = PhaseSeries::from_samples(input, kind, 0.01);
    const auto curve = stream_of(input, kind, settings).curves(0.683).front();
    for (const auto& p : curve.points) {
      if (p.value.m > settings.density) break;  // stride 1 here, so the exact value applies
      const std::int64_t m[] = {p.value.m};
      const auto exact = compute_deviation(series, Statistic::oadev, m);
      CHECK(p.value.dev == rel(exact.front().dev, 1e-12));  // as in the first test case
    }
  }
}

TEST_CASE("memory does not grow with the length of the log") {
  StreamSettings settings;
  settings.statistics = {Statistic::oadev, Statistic::mdev};
  AllanStream stream(DataKind::rate, 0.01, settings);
  const auto y = gyro_like(1 << 18, 5);
  stream.add(y);
  const std::size_t early = stream.memory_bytes();
  for (int i = 0; i < 15; ++i) stream.add(y);  // 4.2e6 samples in all
  const std::size_t late = stream.memory_bytes();
  INFO("after 2^18 samples " << early << " bytes, after 2^22 " << late);
  // Buffers reach their steady size within the first chunks; 25% covers vector growth slack.
  CHECK(late <= early + early / 4);
  // The state is the 16 Ki-sample chunk buffers (x, P in double-double at ~2 levels' worth)
  // plus O(K log N): ~1.1 MiB here; 32 MiB would catch anything growing with N.
  CHECK(late < std::size_t{32} << 20);
}

TEST_CASE("the reported EDF matches the scatter of strided estimates of white FM") {
  // Var(AVAR estimate) / AVAR^2 = 2 / edf for a chi-squared estimate: over R independent
  // records the sample relative variance of the estimates must agree with 2 / edf. With R = 300
  // the sampling error of that variance is ~ sqrt(2 / R) ~ 8% (more for a skewed chi-squared):
  // a 30% band is ~3.5 sigma, and the difference between the strided EDF and the exact one
  // at these points (a factor ~2-4) would fail it.
  constexpr int kRecords = 300;
  constexpr std::size_t kLength = 1 << 13;
  StreamSettings settings;
  settings.density = 2;
  std::vector<std::vector<double>> avar;  // [tau][record]
  std::vector<double> edf;
  std::vector<std::int64_t> factors;
  std::mt19937_64 rng(6);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<double> y(kLength);
  for (int r = 0; r < kRecords; ++r) {
    for (auto& v : y) v = g(rng);
    AllanStream stream(DataKind::rate, 1.0, settings);
    stream.add(y);
    const auto curve = stream.curves(0.683).front();
    if (avar.empty()) {
      avar.resize(curve.points.size());
      for (const auto& p : curve.points) {
        factors.push_back(p.value.m);
        edf.push_back(strided_equivalent_dof(Statistic::oadev, 0, p.value.m,
                                             stream.stride(Statistic::oadev, p.value.m),
                                             stream.size()));
      }
    }
    for (std::size_t k = 0; k < curve.points.size(); ++k) {
      avar[k].push_back(curve.points[k].value.dev * curve.points[k].value.dev);
    }
  }
  int checked = 0;
  for (std::size_t k = 0; k < avar.size(); ++k) {
    if (factors[k] < 8 || factors[k] > 256) continue;  // strided (m > K), and edf >~ 20
    double mean = 0, var = 0;
    for (const double a : avar[k]) mean += a;
    mean /= kRecords;
    for (const double a : avar[k]) var += (a - mean) * (a - mean);
    var /= kRecords - 1;
    const double measured = var / (mean * mean);
    CAPTURE(factors[k]);
    CAPTURE(edf[k]);
    CHECK(measured == rel(2.0 / edf[k], 0.30));
    ++checked;
  }
  CHECK(checked == 6);
}

TEST_CASE("the strided EDF is below the exact one and equal at stride 1") {
  for (const int alpha : {2, 1, 0, -1, -2}) {
    for (const std::int64_t m : {16, 256, 4096}) {
      const std::int64_t N = 1 << 20;
      const double exact = equivalent_dof(Statistic::oadev, alpha, m, N);
      CHECK(strided_equivalent_dof(Statistic::oadev, alpha, m, 1, N) == exact);
      const double strided = strided_equivalent_dof(Statistic::oadev, alpha, m, m / 8, N);
      CAPTURE(alpha);
      CAPTURE(m);
      CHECK(strided < exact);
      CHECK(strided > 0);
    }
  }
}

TEST_CASE("bad settings and samples are errors") {
  StreamSettings settings;
  settings.statistics = {Statistic::totdev};
  CHECK_THROWS_WITH_AS(AllanStream(DataKind::rate, 0.01, settings), doctest::Contains("totdev"),
                       Error);
  settings.statistics = {Statistic::oadev};
  settings.taus = parse_tau_spec("many");
  CHECK_THROWS_WITH_AS(AllanStream(DataKind::rate, 0.01, settings), doctest::Contains("many"),
                       Error);
  settings.taus = TauSpec{};
  settings.density = 0;
  CHECK_THROWS_WITH_AS(AllanStream(DataKind::rate, 0.01, settings), doctest::Contains("density"),
                       Error);
  settings.density = 8;
  CHECK_THROWS_AS(AllanStream(DataKind::rate, std::numeric_limits<double>::quiet_NaN(), settings),
                  Error);
  AllanStream stream(DataKind::rate, 0.01, settings);
  std::vector<double> y(70000, 1.0);
  stream.add(y);
  y[123] = std::numeric_limits<double>::infinity();
  CHECK_THROWS_WITH_AS(stream.add(y), doctest::Contains("sample 70123 (0-based)"), Error);
}

TEST_CASE("decade taus stream to 4e6 samples and name the longer factors the log reaches") {
  // 1, 2 and 4 x 10^k share the odd part 5^k, the shortest lag a power-of-two stride allows:
  // 5^7 = 78125 is beyond the stream's bound, so 10^7 and longer are not held. Before, every
  // decade run failed here ("tau of 10000000 samples has no power-of-two factor").
  StreamSettings settings;
  settings.statistics = {Statistic::oadev};
  settings.taus.kind = TauSpec::Kind::decade;
  AllanStream stream(DataKind::rate, 0.01, settings);
  std::mt19937_64 random(29);
  std::normal_distribution<double> normal;
  std::vector<double> chunk(std::size_t{1} << 20);
  for (double& v : chunk) v = normal(random);
  // OADEV reaches m = M / 4 (Stable32's stop ratio): 10^7 from 4e7 samples on.
  const std::int64_t before = 39'999'999;
  std::int64_t added = 0;
  while (added < before) {
    const auto n = std::min<std::int64_t>(static_cast<std::int64_t>(chunk.size()), before - added);
    stream.add(std::span<const double>(chunk.data(), static_cast<std::size_t>(n)));
    added += n;
  }
  CHECK(stream.factors_left_out().empty());
  stream.add(std::span<const double>(chunk.data(), 1));
  CHECK(stream.factors_left_out() == std::vector<std::int64_t>{10'000'000});
  const AllanCurve curve = stream.curves(0.683).front();
  REQUIRE_FALSE(curve.points.empty());
  CHECK(curve.points.back().value.m == 4'000'000);
  CHECK(curve.points.size() == 7 * 3);  // 1, 2, 4 x 10^0 .. 10^6
}
