// Allan curves and PSD pooled over the contiguous segments of a split log (allan_segments.hpp).
// The log used here: 1000 samples at 100 Hz, a 5 s gap (a logger restart), 600 more samples
// whose bias differs by 5 (a restart changes the turn-on bias; large against the noise so the
// cross-gap terms stand out), white noise of sigma 0.01.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "sigmatau/allan_segments.hpp"
#include "sigmatau/confidence.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/log_reader.hpp"
#include "sigmatau/psd.hpp"
#include "test_support.hpp"

using namespace sigmatau;
namespace fs = std::filesystem;

namespace {

constexpr std::int64_t kFirst = 1000;
constexpr std::int64_t kSecond = 600;
constexpr double kRateHz = 100.0;
constexpr double kTau0 = 1.0 / kRateHz;

/// The gap log written to a temporary CSV (t, gx) and read back with --gaps split.
struct GapLog {
  fs::path path;
  Log log;
  GapLog() {
    path = fs::temp_directory_path() /
           ("sigmatau_test_allan_segments_" + std::to_string(::getpid()) + ".csv");
    std::mt19937_64 rng(20261123);
    std::normal_distribution<double> noise(0.0, 0.01);
    {
      std::ofstream out(path);
      out.precision(17);
      out << "t,gx\n";
      for (std::int64_t i = 0; i < kFirst + kSecond; ++i) {
        const bool second = i >= kFirst;
        const double t = static_cast<double>(i) * kTau0 + (second ? 5.0 : 0.0);
        out << t << ',' << (second ? 5.0 : 0.0) + noise(rng) << '\n';
      }
    }
    LogOptions options;
    options.path = path.string();
    options.time_column = "t";
    options.gaps = GapPolicy::split;
    log = read_log(options);
  }
  ~GapLog() { fs::remove(path); }
  std::span<const double> values() const { return log.channels.at(0); }
};

/// The n-weighted mean of the variances of the two halves, each computed on its own series.
double weighted_halves(const std::vector<DeviationPoint>& a, const std::vector<DeviationPoint>& b,
                       std::size_t i) {
  const double na = static_cast<double>(a[i].n_terms);
  const double nb = static_cast<double>(b[i].n_terms);
  return std::sqrt((na * (a[i].dev * a[i].dev) + nb * (b[i].dev * b[i].dev)) / (na + nb));
}

}  // namespace

TEST_CASE("the reader's split becomes two segment ranges, and a trim shifts and drops them") {
  const GapLog g;
  const auto ranges = segment_ranges(g.log.timing.segment_starts, g.log.timing.samples);
  REQUIRE(ranges.size() == 2);
  CHECK(ranges[0].begin == 0);
  CHECK(ranges[0].end == kFirst);
  CHECK(ranges[1].begin == kFirst);
  CHECK(ranges[1].end == kFirst + kSecond);

  const std::vector<std::int64_t> starts{0, 6, 8};
  SUBCASE("a trim inside the first segment shortens it") {
    const auto r = segment_ranges(starts, 12, 2);
    REQUIRE(r.size() == 3);
    CHECK(r[0].begin == 0);
    CHECK(r[0].end == 4);
    CHECK(r[2].end == 10);
  }
  SUBCASE("a trim past the first segment drops it") {
    const auto r = segment_ranges(starts, 12, 7);
    REQUIRE(r.size() == 2);
    CHECK(r[0].begin == 0);
    CHECK(r[0].end == 1);
    CHECK(r[1].begin == 1);
    CHECK(r[1].end == 5);
  }
  SUBCASE("no starts is one segment") {
    const auto r = segment_ranges({}, 12);
    REQUIRE(r.size() == 1);
    CHECK(r[0].size() == 12);
  }
  SUBCASE("starts out of order or outside the log are refused") {
    CHECK_THROWS_AS(segment_ranges(std::vector<std::int64_t>{0, 8, 6}, 12), Error);
    CHECK_THROWS_AS(segment_ranges(std::vector<std::int64_t>{0, 12}, 12), Error);
    CHECK_THROWS_AS(segment_ranges(starts, 12, 12), Error);
  }
}

TEST_CASE("split equals the n-weighted combination of the halves computed apart, exactly") {
  const GapLog g;
  const auto ranges = segment_ranges(g.log.timing.segment_starts, g.log.timing.samples);
  const auto segments = segment_series(g.values(), ranges, DataKind::rate, kTau0);
  const std::vector<double> first(g.values().begin(), g.values().begin() + kFirst);
  const std::vector<double> second(g.values().begin() + kFirst, g.values().end());
  const auto a = PhaseSeries::from_rate(first, kTau0);
  const auto b = PhaseSeries::from_rate(second, kTau0);
  const auto whole = PhaseSeries::from_rate(g.values(), kTau0);
  const std::vector<std::int64_t> m{1, 2, 4, 8, 16, 32, 64};

  for (Statistic s : {Statistic::adev, Statistic::oadev, Statistic::mdev, Statistic::tdev,
                      Statistic::hdev, Statistic::ohdev}) {
    CAPTURE(to_string(s));
    const auto split = compute_segmented_deviation(segments, s, m);
    const auto pa = compute_deviation(a, s, m);
    const auto pb = compute_deviation(b, s, m);
    const auto naive = compute_deviation(whole, s, m);
    REQUIRE(split.size() == m.size());
    REQUIRE(pa.size() == m.size());
    REQUIRE(pb.size() == m.size());
    for (std::size_t i = 0; i < m.size(); ++i) {
      CAPTURE(m[i]);
      CHECK(split[i].m == m[i]);
      CHECK(split[i].n_terms == pa[i].n_terms + pb[i].n_terms);
      CHECK(split[i].dev == weighted_halves(pa, pb, i));  // the same arithmetic: exactly equal
    }
    // The contiguous estimate has terms across the bias step of 5 (and more of them), which the
    // split leaves out: at m = 1 a cross-gap difference of ~5 against ~1600 of ~0.01
    // more than doubles the deviation.
    CHECK(naive[0].n_terms > split[0].n_terms);
    CHECK(naive[0].dev > 2.0 * split[0].dev);
  }
}

TEST_CASE("split OADEV matches a direct sum over both segments' second differences") {
  const GapLog g;
  const auto ranges = segment_ranges(g.log.timing.segment_starts, g.log.timing.samples);
  const auto segments = segment_series(g.values(), ranges, DataKind::rate, kTau0);
  const std::vector<std::int64_t> m{1, 3, 10, 50};
  const auto split = compute_segmented_deviation(segments, Statistic::oadev, m);
  REQUIRE(split.size() == m.size());
  for (std::size_t i = 0; i < m.size(); ++i) {
    // NIST SP 1065 eq. (11) with x the running sum of the rate samples of each segment, the
    // squared second differences of both segments summed and divided once by 2 m^2 sum(n_k).
    long double sum = 0;
    std::int64_t n = 0;
    for (const auto& r : ranges) {
      std::vector<long double> x(1, 0.0L);
      for (std::int64_t k = r.begin; k < r.end; ++k) x.push_back(x.back() + g.values()[k]);
      const auto N = static_cast<std::int64_t>(x.size());
      for (std::int64_t k = 0; k + 2 * m[i] < N; ++k) {
        const long double d = x[k + 2 * m[i]] - 2 * x[k + m[i]] + x[k];
        sum += d * d;
        ++n;
      }
    }
    const double md = static_cast<double>(m[i]);
    const double direct = std::sqrt(static_cast<double>(sum / (2.0L * md * md * n)));
    CAPTURE(m[i]);
    CHECK(split[i].n_terms == n);
    // 1e-12: the long-double running sum of 1600 values up to 5 keeps ~1e-16 relative, the
    // estimator's double-double phase ~1e-16; the deviation is good to far better than 1e-12.
    SIGMATAU_CHECK_REL(split[i].dev, direct, 1e-12);
  }
}

TEST_CASE("a segment too short for a factor contributes nothing there") {
  const GapLog g;
  const auto ranges = segment_ranges(g.log.timing.segment_starts, g.log.timing.samples);
  const auto segments = segment_series(g.values(), ranges, DataKind::rate, kTau0);
  // OADEV needs N - 2m >= 1: the 600-sample segment (N = 601) stops at m = 300.
  const std::vector<std::int64_t> m{301, 400};
  const auto split = compute_segmented_deviation(segments, Statistic::oadev, m);
  const auto alone = compute_deviation(segments[0], Statistic::oadev, m);
  REQUIRE(split.size() == 2);
  REQUIRE(alone.size() == 2);
  for (std::size_t i = 0; i < 2; ++i) {
    CHECK(split[i].n_terms == alone[i].n_terms);
    // sqrt(n d^2 / n) is d to one rounding of the square and one of the root: 4e-16.
    SIGMATAU_CHECK_REL(split[i].dev, alone[i].dev, 4e-16);
  }
  const std::vector<std::int64_t> beyond{900};  // beyond both segments
  CHECK(compute_segmented_deviation(segments, Statistic::oadev, beyond).empty());
}

TEST_CASE("the split curve's EDF is the sum of the segments' EDFs and its interval follows") {
  const GapLog g;
  const auto ranges = segment_ranges(g.log.timing.segment_starts, g.log.timing.samples);
  const auto segments = segment_series(g.values(), ranges, DataKind::rate, kTau0);
  for (Statistic s : {Statistic::oadev, Statistic::mdev, Statistic::hdev, Statistic::totdev}) {
    CAPTURE(to_string(s));
    const AllanCurve curve = compute_segmented_allan_curve(segments, s, TauSpec{}, 0.683);
    REQUIRE(curve.points.size() >= 4);
    for (const auto& p : curve.points) {
      CAPTURE(p.value.m);
      const int alpha = p.confidence.noise.alpha;
      double edf = 0;
      double weighted = 0;
      std::int64_t n = 0;
      for (const auto& segment : segments) {
        const std::vector<std::int64_t> one{p.value.m};
        const auto d = compute_deviation(segment, s, one);
        if (d.empty()) continue;
        const std::int64_t points =
            s == Statistic::totdev ? record_points(segment) : segment.size();
        const double e = equivalent_dof(s, alpha, p.value.m, points);
        if (std::isfinite(e)) edf += e;
        const double bias = s == Statistic::totdev ? totvar_bias(alpha, p.value.m, segment) : 1.0;
        weighted += static_cast<double>(d[0].n_terms) * d[0].dev * d[0].dev / bias;
        n += d[0].n_terms;
      }
      CHECK(p.value.n_terms == n);
      // 1e-14: the same terms summed in the same order, up to the division by the bias (TOTDEV).
      SIGMATAU_CHECK_REL(p.value.dev, std::sqrt(weighted / static_cast<double>(n)), 1e-14);
      SIGMATAU_CHECK_REL(p.confidence.edf, edf, 1e-14);
      const Interval ci = chi_squared_interval(p.value.dev, edf, 0.683);
      SIGMATAU_CHECK_REL(p.confidence.interval.low, ci.low, 1e-14);
      SIGMATAU_CHECK_REL(p.confidence.interval.high, ci.high, 1e-14);
    }
  }
}

TEST_CASE("one segment gives the contiguous curve") {
  const GapLog g;
  const std::vector<double> first(g.values().begin(), g.values().begin() + kFirst);
  const std::vector<PhaseSeries> one{PhaseSeries::from_rate(first, kTau0)};
  const AllanCurve split = compute_segmented_allan_curve(one, Statistic::oadev, TauSpec{}, 0.683);
  const AllanCurve plain = compute_allan_curve(one[0], Statistic::oadev, TauSpec{}, 0.683);
  REQUIRE(split.points.size() == plain.points.size());
  for (std::size_t i = 0; i < split.points.size(); ++i) {
    CHECK(split.points[i].value.n_terms == plain.points[i].value.n_terms);
    CHECK(split.points[i].confidence.noise.alpha == plain.points[i].confidence.noise.alpha);
    // sqrt(n d^2 / n) against d: two roundings, 4e-16; the interval scales with the deviation.
    SIGMATAU_CHECK_REL(split.points[i].value.dev, plain.points[i].value.dev, 4e-16);
    SIGMATAU_CHECK_REL(split.points[i].confidence.edf, plain.points[i].confidence.edf, 1e-15);
    SIGMATAU_CHECK_REL(split.points[i].confidence.interval.high,
                       plain.points[i].confidence.interval.high, 1e-15);
  }
}

TEST_CASE("segments of different kinds or rates are refused") {
  const std::vector<double> v(100, 1.0);
  const std::vector<PhaseSeries> mixed{PhaseSeries::from_rate(v, 0.01),
                                       PhaseSeries::from_rate(v, 0.02)};
  const std::vector<std::int64_t> m{1};
  CHECK_THROWS_AS(compute_segmented_deviation(mixed, Statistic::oadev, m), Error);
  CHECK_THROWS_AS(compute_segmented_deviation({}, Statistic::oadev, m), Error);
}

TEST_CASE("Welch over stretches averages every window inside a stretch, none across a gap") {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<double> a(4096), b(2048), tiny(100);
  for (double& v : a) v = noise(rng);
  for (double& v : b) v = noise(rng);
  for (double& v : tiny) v = noise(rng);
  WelchOptions options;
  options.segment_length = 512;
  const std::vector<std::span<const double>> stretches{a, tiny, b};
  const PsdCurve split = welch_psd_stretches(stretches, kRateHz, options);
  const PsdCurve pa = welch_psd(a, kRateHz, options);
  const PsdCurve pb = welch_psd(b, kRateHz, options);
  CHECK(split.segments == pa.segments + pb.segments);  // the 100-sample stretch holds none
  REQUIRE(split.psd.size() == pa.psd.size());
  for (std::size_t j = 0; j < split.psd.size(); ++j) {
    const double expected =
        (static_cast<double>(pa.segments) * pa.psd[j] + static_cast<double>(pb.segments) * pb.psd[j]) /
        static_cast<double>(pa.segments + pb.segments);
    // The same products and sum, in the same order: a few roundings at most.
    SIGMATAU_CHECK_REL(split.psd[j], expected, 1e-15);
    SIGMATAU_CHECK_REL(split.edf[j], pa.edf[j] + pb.edf[j], 1e-15);
  }
  const std::vector<std::span<const double>> too_short{tiny};
  CHECK_THROWS_AS(welch_psd_stretches(too_short, kRateHz, options), Error);
}
