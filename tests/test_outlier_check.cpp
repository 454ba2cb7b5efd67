// Outlier check (check_outliers, OutlierChecker) on constructed channels: spikes injected at
// known rows into simulated noise are found (count, rows, values); clean Gaussian, quantized,
// constant, offset, float32-stored and random-walk channels raise nothing; non-finite values are
// never outliers; the checker gives the same warning however the values arrive.
//
// Why "nothing" can be asserted on clean noise: the threshold is 8 robust sigma; a Gaussian
// sample beyond it has probability 1.2e-15, so with the spread of the block's sigma (2.8 %
// standard error) ~1e-14 per sample: the 1e6-sample channels below would raise a false alarm
// about once in 1e8 runs. Every generator is seeded.
#include <algorithm>
#include <cmath>
#include <random>
#include <span>
#include <vector>

#include "sigmatau/data_checks.hpp"
#include "sigmatau/error.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

using test::white;

/// Feeds `x` to a checker in pieces of random length 1..max_piece and returns its warning.
std::optional<DataWarning> in_pieces(const std::vector<double>& x, std::size_t max_piece,
                                     std::uint64_t seed, const OutlierOptions& options) {
  OutlierChecker checker("c", options, "deg/s", 0.5);
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::size_t> length(1, max_piece);
  std::size_t i = 0;
  while (i < x.size()) {
    const std::size_t n = std::min(length(rng), x.size() - i);
    checker.add(std::span<const double>(x.data() + i, n));
    i += n;
  }
  return checker.finish();
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("spikes injected at known rows are counted and located, first and largest") {
  // 100,000 rows = 24 blocks of 4096 and a tail of 1696 (rows 98304..99999), so rows 0 (the
  // first), 40960 (a block's first row), 40959 (a block's last) and 99999 (in the tail) are all
  // covered. Spikes of 12..40 sigma: far beyond 8, and the noise never reaches 8 (see top).
  auto x = white(100000, 0.0, 1.0, 11);
  const std::vector<std::pair<std::size_t, double>> spikes = {
      {0, 12.0}, {40959, -15.0}, {40960, 20.0}, {77777, -40.0}, {99999, 25.0}};
  for (const auto& [row, value] : spikes) x[row] = value;
  const auto w = check_outliers(x, "gyro_x", {}, "rad/s", 1.0);
  REQUIRE(w.has_value());
  CHECK(w->kind == DataWarningKind::outlier);
  CHECK(w->channel == "gyro_x");
  CHECK(w->runs == 5);
  CHECK(w->rows_flagged == 5);
  CHECK(w->first_row == 0);
  CHECK(w->first_value == 12.0);
  CHECK(w->longest_row == 77777);
  CHECK(w->value == -40.0);
  // The block's sigma is 1 within its 2.8 % standard error; 15 % is > 5 standard errors.
  CHECK(w->largest_sigma == doctest::Approx(40.0).epsilon(0.15).scale(0));
  CHECK(contains(w->message, "gyro_x: 5 samples beyond 8 robust sigma of their 4096-row block"));
  CHECK(contains(w->message, "(-40 rad/s) at row 77777, first at row 0 (12 rad/s)"));
  SUBCASE("values are shown in the given unit (SI value / to_si)") {
    const auto deg = check_outliers(x, "gyro_x", {}, "deg/s", 0.5);
    REQUIRE(deg.has_value());
    CHECK(contains(deg->message, "(-80 deg/s) at row 77777"));
    CHECK(deg->value == -40.0);  // the field keeps the value as given
  }
  SUBCASE("a spike below the threshold is not counted") {
    x[50000] = 5.0;  // 5 sigma: part of the noise at this threshold
    CHECK(check_outliers(x, "gyro_x")->runs == 5);
    OutlierOptions low;
    low.threshold_sigma = 4.5;  // now it is beyond; the noise's own 4.5-sigma tail may add some
    CHECK(check_outliers(x, "gyro_x", low)->runs >= 6);
  }
}

TEST_CASE("clean Gaussian noise, at any offset and stored as float32, raises no outlier") {
  CHECK_FALSE(check_outliers(white(1000000, 0.0, 1.0, 1), "x").has_value());
  // 1e6 + noise of 1e-3: |x - m| loses nothing in double (ulp 1.2e-10).
  CHECK_FALSE(check_outliers(white(1000000, 1e6, 1e-3, 2), "x").has_value());
  SUBCASE("float32 storage: 1000 + noise of 1e-3 (ulp 6.1e-5) and 1e6 + noise of 0.05 (0.0625)") {
    for (const auto& [offset, sigma] : {std::pair{1e3, 1e-3}, std::pair{1e6, 0.05}}) {
      auto x = white(500000, offset, sigma, 3);
      for (auto& v : x) v = static_cast<double>(static_cast<float>(v));
      CHECK_FALSE(check_outliers(x, "x").has_value());
      x[123456] = static_cast<double>(static_cast<float>(offset + 40 * std::max(sigma, 0.0625)));
      const auto w = check_outliers(x, "x");
      REQUIRE(w.has_value());
      CHECK(w->runs == 1);
      CHECK(w->first_row == 123456);
    }
  }
}

TEST_CASE("quantized noise is not flagged for its codes, whatever the noise per LSB") {
  // Integer codes of noise from 0.1 LSB (98 % of samples on one code: q90 = 0, sigma = d_min =
  // 1 LSB) to 3 LSB; mean off the code grid by 0.3 LSB, as a real bias is.
  for (const double sigma : {0.1, 0.2, 0.3, 0.45, 0.7, 1.0, 3.0}) {
    CAPTURE(sigma);
    auto x = white(1000000, 0.3, sigma, 4);
    for (auto& v : x) v = std::round(v);
    CHECK_FALSE(check_outliers(x, "x").has_value());
    x[654321] = 60;  // a spike of 60 LSB is found at any of these noise levels
    const auto w = check_outliers(x, "x");
    REQUIRE(w.has_value());
    CHECK(w->runs == 1);
    CHECK(w->longest_row == 654321);
  }
}

TEST_CASE("a constant channel, or one with a single distinct row, raises no outlier") {
  std::vector<double> x(10000, 0.123);
  CHECK_FALSE(check_outliers(x, "x").has_value());
  // A spike in a constant block has nothing to be measured against (sigma would be the spike
  // itself): the stuck check is what reports such a channel.
  x[5000] = 7.0;
  CHECK_FALSE(check_outliers(x, "x").has_value());
}

TEST_CASE("random-walk-dominated values raise no outlier") {
  // A random walk of 1e6 unit steps: its 4096-row blocks wander by ~64 sigma of a step. Every
  // block keeps 90 % of its rows within q90 of its median, so the walk cannot put a row 8 x
  // q90 / 1.645 = 4.9 q90 away.
  auto x = white(1000000, 0.0, 1.0, 5);
  for (std::size_t i = 1; i < x.size(); ++i) x[i] += x[i - 1];
  CHECK_FALSE(check_outliers(x, "x").has_value());
  SUBCASE("in differences (phase data), a step of the walk is one outlier at its row") {
    OutlierOptions diff;
    diff.differences = true;
    CHECK_FALSE(check_outliers(x, "x", diff).has_value());
    for (std::size_t i = 300000; i < x.size(); ++i) x[i] += 30.0;  // a rate spike: a phase step
    const auto w = check_outliers(x, "x", diff);
    REQUIRE(w.has_value());
    CHECK(w->runs == 1);
    CHECK(w->first_row == 300000);  // x[300000] - x[299999]
    CHECK(contains(w->message, "1 difference of consecutive samples beyond"));
  }
}

TEST_CASE("non-finite values are never outliers and do not enter the statistics") {
  auto x = white(20000, 0.0, 1.0, 6);
  for (std::size_t i = 100; i < 3000; i += 7) x[i] = NAN;
  x[4000] = INFINITY;
  x[4001] = -INFINITY;
  x[9000] = 30.0;
  const auto w = check_outliers(x, "x");
  REQUIRE(w.has_value());
  CHECK(w->runs == 1);
  CHECK(w->first_row == 9000);
  CHECK_FALSE(check_outliers(std::vector<double>(5000, NAN), "x").has_value());
}

TEST_CASE("a short channel is one block from 64 rows on, and not checked below") {
  auto x = white(63, 0.0, 1.0, 7);
  x[10] = 1000.0;
  CHECK_FALSE(check_outliers(x, "x").has_value());
  x.push_back(0.5);  // 64 rows: now checked
  const auto w = check_outliers(x, "x");
  REQUIRE(w.has_value());
  CHECK(w->first_row == 10);
}

TEST_CASE("the checker in pieces gives check_outliers' warning, bit for bit") {
  auto x = white(30000, 2.0, 1.0, 8);
  OutlierOptions options;
  SUBCASE("spikes and non-finite values") {
    for (std::size_t i = 17; i < x.size(); i += 1013) x[i] += (i % 2 ? 25.0 : -30.0);
    x[5000] = NAN;
    x[29990] = INFINITY;
  }
  SUBCASE("differences, small blocks, a low threshold") {
    for (std::size_t i = 1; i < x.size(); ++i) x[i] += x[i - 1];
    options.differences = true;
    options.block_rows = 100;
    options.threshold_sigma = 3.5;  // many chance outliers: more for the pieces to get wrong
  }
  SUBCASE("clean") {}
  OutlierChecker whole_checker("c", options, "deg/s", 0.5);
  whole_checker.add(x);
  const auto whole = whole_checker.finish();
  const auto pure = check_outliers(x, "c", options, "deg/s", 0.5);
  REQUIRE(pure.has_value() == whole.has_value());
  if (whole) CHECK(pure->message == whole->message);
  for (std::size_t max_piece : {1, 7, 4095, 4097, 50000}) {
    CAPTURE(max_piece);
    const auto pieces = in_pieces(x, max_piece, max_piece, options);
    REQUIRE(pieces.has_value() == whole.has_value());
    if (!whole) continue;
    CHECK(pieces->message == whole->message);
    CHECK(pieces->runs == whole->runs);
    CHECK(pieces->first_row == whole->first_row);
    CHECK(pieces->longest_row == whole->longest_row);
    CHECK(pieces->largest_sigma == whole->largest_sigma);  // exact: the same arithmetic
    CHECK(pieces->value == whole->value);
  }
}

TEST_CASE("a block's robust sigma is sigma on Gaussian noise and 1 LSB on mostly one code") {
  const auto x = white(4096, 5.0, 2.0, 9);
  // 1024 values (every 4th): q90 gives sigma within 2.8 % (1 standard error), the MAD 3.6 %;
  // 12 % is > 3 standard errors of either. The median within 0.08 sigma (2 standard errors).
  for (const double q : {0.9, 0.5}) {
    CAPTURE(q);
    const OutlierScale s = outlier_scale(x, q);
    CHECK(s.sigma == doctest::Approx(2.0).epsilon(0.12).scale(0));
    CHECK(std::abs(s.median - 5.0) < 0.08 * 2.0);
  }
  auto codes = white(4096, 0.0, 0.2, 10);          // 99 % on code 0
  for (auto& v : codes) v = std::round(v) * 0.01;  // an LSB of 0.01
  const OutlierScale c = outlier_scale(codes);
  CHECK(c.median == 0.0);
  CHECK(c.sigma == 0.01);  // the smallest step away from m, exactly
  CHECK(outlier_scale(std::vector<double>(100, 3.0)).sigma == 0.0);
  CHECK(outlier_scale(std::vector<double>{}).sigma == 0.0);
  CHECK_THROWS_AS(outlier_scale(x, 0.4), Error);
  CHECK_THROWS_AS(outlier_scale(x, 1.0), Error);
}

namespace {
/// m and s as the method defines them, by std::nth_element (the selection outlier_scale uses
/// is a faster one; a quantile is one value, so the two must agree exactly).
OutlierScale scale_by_nth_element(std::span<const double> window, double q) {
  const std::size_t stride = std::max<std::size_t>(1, window.size() / 1024);
  std::vector<double> s;
  for (std::size_t i = 0; i < window.size(); i += stride) {
    if (std::isfinite(window[i])) s.push_back(window[i]);
  }
  if (s.empty()) return {};
  std::nth_element(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(s.size() / 2), s.end());
  const double m = s[s.size() / 2];
  double d_min = INFINITY;
  for (double& v : s) {
    v = std::abs(v - m);
    if (v > 0 && v < d_min) d_min = v;
  }
  if (d_min == INFINITY) return {m, 0.0};
  double z = 0, hi = 40;  // |z| with P(|Z| <= z) = q, by bisection as the library does
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (z + hi);
    if (mid == z || mid == hi) break;
    (std::erfc(mid / std::sqrt(2.0)) > 1 - q ? z : hi) = mid;
  }
  z = 0.5 * (z + hi);
  const auto k = std::min(s.size() - 1, static_cast<std::size_t>(q * static_cast<double>(s.size())));
  std::nth_element(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(k), s.end());
  return {m, std::max(s[k] / z, d_min)};
}
}  // namespace

TEST_CASE("the block's median and robust sigma are the exact order statistics on any values") {
  // Windows that stress a selection: sorted either way, organ pipe, heavy ties (codes), two
  // values, constant, one spike, NaN holes, every length from 1 to past two strides.
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g(0.0, 1.0);
  std::vector<std::vector<double>> windows;
  for (const std::size_t n : {1u, 2u, 3u, 47u, 48u, 49u, 100u, 1023u, 1024u, 2047u, 4096u, 9000u}) {
    std::vector<double> w(n);
    for (auto& v : w) v = g(rng);
    windows.push_back(w);
    std::sort(w.begin(), w.end());
    windows.push_back(w);
    std::reverse(w.begin(), w.end());
    windows.push_back(w);
    for (std::size_t i = 0; i < n; ++i) w[i] = static_cast<double>(std::min(i, n - 1 - i));
    windows.push_back(w);
    for (auto& v : w) v = std::round(g(rng) * 0.3);
    windows.push_back(w);
    for (std::size_t i = 0; i < n; ++i) w[i] = i % 3 == 0 ? 1.0 : -2.0;
    windows.push_back(w);
    std::fill(w.begin(), w.end(), 7.25);
    w[n / 2] = 1e6;
    windows.push_back(w);
    for (std::size_t i = 0; i < n; i += 5) w[i] = NAN;
    windows.push_back(w);
  }
  for (std::size_t c = 0; c < windows.size(); ++c) {
    for (const double q : {0.5, 0.9, 0.99}) {
      CAPTURE(c);
      CAPTURE(q);
      const OutlierScale got = outlier_scale(windows[c], q);
      const OutlierScale want = scale_by_nth_element(windows[c], q);
      CHECK(got.median == want.median);
      CHECK(got.sigma == want.sigma);
    }
  }
}

TEST_CASE("bad outlier options are refused") {
  OutlierOptions options;
  options.block_rows = 63;
  CHECK_THROWS_AS(OutlierChecker("x", options), Error);
  options = {};
  options.threshold_sigma = 0;
  CHECK_THROWS_AS(OutlierChecker("x", options), Error);
  options.threshold_sigma = NAN;
  CHECK_THROWS_AS(OutlierChecker("x", options), Error);
  options.threshold_sigma = 8;
  options.scale_quantile = 0.3;
  CHECK_THROWS_AS(OutlierChecker("x", options), Error);
  CHECK_THROWS_AS(OutlierChecker("x", {}, "deg/s", 0.0), Error);
  CHECK(to_string(DataWarningKind::outlier) == "outlier");
}
