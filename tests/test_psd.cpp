// Welch PSD and noise density: conventions, statistics and streaming.
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "sigmatau/error.hpp"
#include "sigmatau/psd.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

std::vector<double> white_noise(std::size_t n, double sigma, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  std::vector<double> x(n);
  for (auto& v : x) v = normal(rng);
  return x;
}

/// Two-sided chi-squared interval of a mean level with `edf` degrees of freedom, as a factor.
std::pair<double, double> chi2_factor(double edf, double confidence) {
  boost::math::chi_squared chi2(edf);
  return {edf / boost::math::quantile(chi2, (1 + confidence) / 2),
          edf / boost::math::quantile(chi2, (1 - confidence) / 2)};
}

}  // namespace

TEST_CASE("white noise has the one-sided level 2 sigma^2 / f_s in every window") {
  const double sigma = 0.3, rate = 200.0;
  const auto x = white_noise(1 << 18, sigma, 42);
  for (Window window : {Window::hann, Window::blackman_harris, Window::rectangular}) {
    CAPTURE(to_string(window));
    WelchOptions options;
    options.window = window;
    options.segment_length = 1024;
    const PsdCurve psd = welch_psd(x, rate, options);
    // The mean over all interior bins estimates the level with EDF ~ sum of bin EDFs / window
    // correlation (>> 1e4 here); use the 99.9 % interval of that estimate: a correct estimator
    // fails this with probability 1e-3 for a random seed, and this seed is fixed.
    const auto nd = noise_density(psd, std::make_pair(1.0, 99.0), 0.999);
    const double truth_n = sigma / std::sqrt(rate);
    CHECK(nd.ci_low <= truth_n);
    CHECK(nd.ci_high >= truth_n);
    SIGMATAU_CHECK_REL(nd.one_sided_asd, std::sqrt(2.0) * nd.value, 1e-12);  // definition
  }
}

TEST_CASE("Parseval: the integrated one-sided PSD equals the variance") {
  const double sigma = 2.0, rate = 50.0;
  const auto x = white_noise(1 << 17, sigma, 7);
  WelchOptions options;
  options.segment_length = 512;
  options.detrend = Detrend::none;
  const PsdCurve psd = welch_psd(x, rate, options);
  double integral = 0;
  const double df = rate / static_cast<double>(psd.segment_length);
  for (double p : psd.psd) integral += p * df;
  // The variance estimate from ~2.6e5 correlated periodogram values: its relative standard error
  // is about sqrt(2 / total EDF) ~ 0.4 %; 2 % is 5 standard errors.
  SIGMATAU_CHECK_REL(integral, sigma * sigma, 0.02);
}

TEST_CASE("a sinusoid on a bin puts its power A^2/2 into that bin (rectangular window)") {
  const double rate = 100.0, amplitude = 3.0;
  const std::int64_t length = 256;
  const int bin = 20;
  const double f = bin * rate / length;
  std::vector<double> x(length * 16);
  for (std::size_t n = 0; n < x.size(); ++n) {
    x[n] = amplitude * std::sin(2 * std::numbers::pi * f * static_cast<double>(n) / rate);
  }
  WelchOptions options;
  options.segment_length = length;
  options.window = Window::rectangular;
  options.overlap = 0;
  const PsdCurve psd = welch_psd(x, rate, options);
  const double df = rate / length;
  SIGMATAU_CHECK_REL(psd.psd[bin] * df, amplitude * amplitude / 2, 1e-9);  // exact up to rounding
  CHECK(psd.psd[bin + 1] * df < 1e-20);
  CHECK(psd.frequency_hz[bin] == test::rel(f, 1e-15));
}

TEST_CASE("Welch EDF follows the window's overlap correlation") {
  // Hann at 50 % overlap: the squared correlation of neighbouring segments is
  // (sum w[n] w[n+L/2])^2 / (sum w^2)^2 = (1/6)^2 exactly for the periodic Hann window, so
  // K segments give EDF = 2K / (1 + 2 (1 - 1/K) / 36). (Harris 1978, Table 1: 16.7 %.)
  const auto x = white_noise(64 * 33, 1.0, 1);  // 2 * 64 - 1 = 65 segments of 64 at step 32
  WelchOptions options;
  options.segment_length = 64;
  const PsdCurve psd = welch_psd(x, 10.0, options);
  const double k = static_cast<double>(psd.segments);
  CHECK(psd.segments == 65);
  const double expected = 2 * k / (1 + 2 * (1 - 1 / k) / 36.0);
  SIGMATAU_CHECK_REL(psd.edf[5], expected, 1e-12);
  SIGMATAU_CHECK_REL(psd.edf[0], expected / 2, 1e-12);  // DC is a real value: half the EDF
}

TEST_CASE("streaming in blocks of any size gives the same PSD as one call") {
  const auto x = white_noise(20000, 1.0, 3);
  WelchOptions options;
  options.segment_length = 1000;
  options.detrend = Detrend::linear;
  const PsdCurve once = welch_psd(x, 100.0, options);
  WelchAccumulator accumulator(100.0, options);
  std::size_t used = 0, block = 1;
  while (used < x.size()) {
    const std::size_t take = std::min(block, x.size() - used);
    accumulator.add(std::span<const double>(x).subspan(used, take));
    used += take;
    block = block * 3 + 1;
  }
  const PsdCurve streamed = accumulator.result();
  REQUIRE(streamed.psd.size() == once.psd.size());
  CHECK(streamed.segments == once.segments);
  for (std::size_t k = 0; k < once.psd.size(); ++k) CHECK(streamed.psd[k] == once.psd[k]);
}

TEST_CASE("a huge offset and a linear drift do not leak into the spectrum") {
  auto x = white_noise(1 << 16, 1e-3, 11);
  for (std::size_t n = 0; n < x.size(); ++n) x[n] += 1e3 + 1e-6 * static_cast<double>(n);
  WelchOptions options;
  options.segment_length = 1024;
  options.detrend = Detrend::linear;
  const PsdCurve psd = welch_psd(x, 100.0, options);
  const auto nd = noise_density(psd, std::make_pair(0.5, 40.0), 0.999);
  const double truth = 1e-3 / std::sqrt(100.0);
  // 99.9 % interval of the band estimate (see the white-noise case for the reasoning).
  CHECK(nd.ci_low <= truth);
  CHECK(nd.ci_high >= truth);
}

TEST_CASE("the automatic band avoids a rate random walk at low frequency") {
  // White (sigma 0.05 per sample at 100 Hz, N = 5e-3 /sqrt(Hz)) plus a random walk whose PSD
  // crosses the white level near 0.1 Hz. A band reaching into the walk would read N high.
  const double rate = 100.0, sigma = 0.05;
  auto x = white_noise(1 << 20, sigma, 5);
  std::mt19937_64 rng(6);
  std::normal_distribution<double> step(0.0, 2e-3);
  double walk = 0;
  for (auto& v : x) {
    walk += step(rng);
    v += walk;
  }
  WelchOptions options;
  options.segment_length = 4096;
  const PsdCurve psd = welch_psd(x, rate, options);
  const auto nd = noise_density(psd, std::nullopt, 0.999);
  CHECK(nd.band_detected);
  // The walk's one-sided PSD 2 q / (f_s (2 sin(pi f / f_s))^2), q = (2e-3)^2, is 10 % of the
  // white level 2 sigma^2 / f_s at f = 2.0 Hz: a flat band must start above that.
  CHECK(nd.band_low_hz > 2.0);
  // Over [2 Hz, 40 Hz] in linear frequency bins the walk adds < 1 % to the mean level (its
  // PSD falls as 1/f^2), i.e. < 0.5 % to N; the estimate's own 1-sigma error is ~0.1 %.
  SIGMATAU_CHECK_REL(nd.value, sigma / std::sqrt(rate), 0.01);
}

TEST_CASE("log binning keeps the level and adds up the EDF") {
  const auto x = white_noise(1 << 18, 1.0, 9);
  WelchOptions options;
  options.segment_length = 4096;
  const PsdCurve psd = welch_psd(x, 1000.0, options);
  const PsdCurve binned = log_binned(psd, 10);
  REQUIRE(binned.psd.size() > 10);
  for (std::size_t i = 1; i < binned.frequency_hz.size(); ++i) {
    CHECK(binned.frequency_hz[i] > binned.frequency_hz[i - 1]);
  }
  // Each binned value is within its own 99.9 % chi-squared interval of the true level 2/f_s.
  for (std::size_t i = 0; i < binned.psd.size(); ++i) {
    const auto [lo, hi] = chi2_factor(binned.edf[i], 0.999);
    CAPTURE(binned.frequency_hz[i]);
    CHECK(binned.psd[i] * lo <= 2.0 / 1000.0);
    CHECK(binned.psd[i] * hi >= 2.0 / 1000.0);
  }
}

TEST_CASE("the default segment length saturates at kDefaultSegmentSaturation samples") {
  CHECK(default_segment_length(kDefaultSegmentSaturation) == kMaxDefaultSegmentLength);
  CHECK(default_segment_length(kDefaultSegmentSaturation - 1) == kMaxDefaultSegmentLength / 2);
  CHECK(default_segment_length(std::int64_t{1} << 40) == kMaxDefaultSegmentLength);
  CHECK(default_segment_length(0) == 16);
}

TEST_CASE("bad PSD arguments are clear errors") {
  const auto x = white_noise(100, 1.0, 1);
  WelchOptions options;
  options.segment_length = 1000;
  CHECK_THROWS_WITH_AS(welch_psd(x, 10.0, options), doctest::Contains("shorter than one segment"),
                       Error);
  options.segment_length = 16;
  options.overlap = 1.0;
  CHECK_THROWS_AS(welch_psd(x, 10.0, options), Error);
  options.overlap = std::nan("");
  CHECK_THROWS_AS(welch_psd(x, 10.0, options), Error);
  options.overlap = 0.5;
  CHECK_THROWS_AS(welch_psd(x, 0.0, options), Error);
  CHECK_THROWS_AS(parse_window("hamming"), Error);
  const PsdCurve psd = welch_psd(x, 10.0, options);
  CHECK_THROWS_AS(noise_density(psd, std::make_pair(3.0, 7.0), 0.683), Error);  // above Nyquist
}
