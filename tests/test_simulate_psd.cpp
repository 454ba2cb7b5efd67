// The PSD of each simulated noise term against its theory, through the project's Welch PSD
// (psd.hpp): white, quantization, flicker, rate random walk, Gauss-Markov.
//
// Expected value. For Welch with a window w (length M, U = sum w^2), the one-sided estimate at
// bin k is 2 tau0 / U |X_k|^2 averaged over segments, X_k = sum_n a_n x_n, a_n = w_n e^{-2 pi i k n
// / M}. Its expectation is exact and computed here from each term's discrete-time covariance:
//  - stationary terms (white, quantization, flicker, Gauss-Markov) with autocovariance r(l):
//    E|X_k|^2 = sum_{|l|<M} r(l) c(l) cos(2 pi k l / M), c(l) = sum_n w_n w_{n+|l|};
//  - rate random walk b_n = b_s + sum_{j<=n} e_j (e_j iid, variance K^2 tau0): for the periodic
//    Hann window sum_n a_n = 0 at k >= 2, so the level b_s and the mean removal drop out and
//    E|X_k|^2 = K^2 tau0 sum_{j=1}^{M-1} |sum_{n>=j} a_n|^2.
// (Mean removal changes nothing at k >= 2 either: the mean times the window has no power there.)
// So the test checks the simulator against the exact expectation at every bin 2 <= k < M/2, and
// separately that this expectation is the analytic two-sided PSD of noise_model.hpp (x 2, one
// sided) where window leakage and sampling are negligible.
//
// Statistics (false failure < 1e-3 per run of this file, by the union bound):
//  - Segments do not overlap (overlap 0), so for white, quantization and random walk the segments'
//    periodograms are independent, and for flicker and Gauss-Markov nearly so; each bin's EDF is
//    taken as 0.8 x the curve's 2K (K segments), a margin for the residual correlation (and for
//    the chi-squared shape of a periodogram of coloured noise).
//  - R = 10 seeds x 3 axes = 30 independent realizations; P = 5 terms x (M/2 - 2) bins pairs.
//  - Pooled: the mean over the R estimates times R edf / E is ~chi^2(R edf); it must lie inside
//    the two-sided interval of level 1 - 1e-3 / (2 P) (Bonferroni over P pairs, half the budget).
//  - Per estimate ("within the Welch interval"): each estimate is inside its own 99% chi^2(edf)
//    interval with probability >= 0.99; a bin fails when c or more of its R estimates are outside,
//    c the smallest count with P x P(Binomial(R, 0.01) >= c) < 5e-4 (the other half).
#include <boost/math/distributions/binomial.hpp>
#include <boost/math/distributions/chi_squared.hpp>

#include <cmath>
#include <complex>
#include <numbers>

#include "sigmatau/psd.hpp"
#include "sigmatau/simulate.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

constexpr double kRate = 100.0;  // Hz
constexpr double kTau0 = 1 / kRate;
constexpr std::int64_t kSamples = std::int64_t{1} << 17;
constexpr std::int64_t kSegment = 1024;
constexpr int kSeeds = 10;
constexpr int kRealizations = 3 * kSeeds;
constexpr int kTerms = 5;
constexpr std::int64_t kFirstBin = 2;
constexpr int kPairs = kTerms * static_cast<int>(kSegment / 2 - kFirstBin);
constexpr double kEdfMargin = 0.8;
constexpr double kPi = std::numbers::pi;

double hann(std::int64_t n) {  // periodic, as psd.cpp
  return 0.5 - 0.5 * std::cos(2 * kPi * static_cast<double>(n) / static_cast<double>(kSegment));
}

/// c(l) = sum_n w_n w_{n+l}, l = 0..M-1.
std::vector<double> window_correlation() {
  std::vector<double> c(kSegment, 0.0);
  for (std::int64_t l = 0; l < kSegment; ++l)
    for (std::int64_t n = 0; n + l < kSegment; ++n) c[l] += hann(n) * hann(n + l);
  return c;
}

/// Exact expected one-sided Welch PSD at bins 0..M/2 of a stationary process with
/// autocovariance r(l), l = 0..M-1.
std::vector<double> expected_stationary(const std::vector<double>& r) {
  const auto c = window_correlation();
  std::vector<double> e(kSegment / 2 + 1, 0.0);
  for (std::int64_t k = kFirstBin; k < kSegment / 2; ++k) {
    double s = r[0] * c[0];
    for (std::int64_t l = 1; l < kSegment; ++l)
      s += 2 * r[l] * c[l] * std::cos(2 * kPi * static_cast<double>(k * l) / kSegment);
    e[k] = 2 * kTau0 / c[0] * s;  // c[0] = U
  }
  return e;
}

/// Exact expected one-sided Welch PSD of the random walk with increment variance q (see top).
std::vector<double> expected_random_walk(double q) {
  const double u = window_correlation()[0];
  std::vector<double> e(kSegment / 2 + 1, 0.0);
  for (std::int64_t k = kFirstBin; k < kSegment / 2; ++k) {
    std::complex<double> tail = 0;  // sum_{n >= j} a_n, built from the end
    double s = 0;
    for (std::int64_t j = kSegment - 1; j >= 1; --j) {
      tail += hann(j) * std::polar(1.0, -2 * kPi * static_cast<double>(k * j) / kSegment);
      s += std::norm(tail);
    }
    e[k] = 2 * kTau0 / u * q * s;
  }
  return e;
}

/// Autocovariance of the L-tap Kasdin flicker per unit B^2: sum_j h_j h_{j+l}.
std::vector<double> flicker_autocovariance(std::int64_t taps) {
  std::vector<double> h(static_cast<std::size_t>(taps));
  long double v = 1.0L;
  for (std::int64_t j = 0; j < taps; ++j) {
    if (j > 0) v *= (static_cast<long double>(j) - 0.5L) / j;
    h[j] = static_cast<double>(v);
  }
  std::vector<double> r(kSegment, 0.0);
  for (std::int64_t l = 0; l < kSegment; ++l) {
    long double s = 0;
    for (std::int64_t j = 0; j + l < taps; ++j) s += static_cast<long double>(h[j]) * h[j + l];
    r[l] = static_cast<double>(s);
  }
  return r;
}

SimulationConfig config_of(const NoiseTerms& t, std::uint64_t seed) {
  SimulationConfig c;
  c.rate_hz = kRate;
  c.samples = kSamples;
  c.seed = seed;
  ErrorModel g;
  g.noise = {t, t, t};
  c.gyro = g;
  return c;
}

/// Exact expected Welch PSD of one term alone (the terms of the file comment).
std::vector<double> expected_psd(const NoiseTerms& t) {
  std::vector<double> r(kSegment, 0.0);
  if (t.white) r[0] = *t.white * *t.white / kTau0;
  if (t.quantization) {  // (e_k - e_{k-1}) Q / tau0, e of unit variance
    const double q2 = *t.quantization * *t.quantization / (kTau0 * kTau0);
    r[0] = 2 * q2;
    r[1] = -q2;
  }
  for (const GaussMarkov& gm : t.gauss_markov) {
    const double phi = std::exp(-kTau0 / gm.tau_c_s);
    for (std::int64_t l = 0; l < kSegment; ++l)
      r[l] += gm.sigma * gm.sigma * std::pow(phi, static_cast<double>(l));
  }
  if (t.bias_instability) {
    const auto unit = flicker_autocovariance(sampling_of(config_of(t, 1)).flicker_taps);
    for (std::int64_t l = 0; l < kSegment; ++l)
      r[l] = *t.bias_instability * *t.bias_instability * unit[l];
  }
  if (t.rate_random_walk)
    return expected_random_walk(*t.rate_random_walk * *t.rate_random_walk * kTau0);
  return expected_stationary(r);
}

int failure_count() {
  const boost::math::binomial_distribution<> b(kRealizations, 0.01);
  for (int c = 1; c <= kRealizations; ++c)
    if (kPairs * boost::math::cdf(boost::math::complement(b, c - 1)) < 5e-4) return c;
  return kRealizations;
}

/// The two statistical checks of the file comment for one term.
void check_term(const NoiseTerms& t) {
  const auto expected = expected_psd(t);
  const WelchOptions options{kSegment, 0.0, Window::hann, Detrend::mean};
  std::vector<double> pooled(kSegment / 2 + 1, 0.0);
  std::vector<int> outside(kSegment / 2 + 1, 0);
  double edf = 0;
  std::vector<double> channel(static_cast<std::size_t>(kSamples));
  for (int seed = 1; seed <= kSeeds; ++seed) {
    Simulator sim(config_of(t, static_cast<std::uint64_t>(seed)));
    std::vector<double> rows(static_cast<std::size_t>(kSamples * 3));
    REQUIRE(sim.next(rows, kSamples) == kSamples);
    for (int axis = 0; axis < 3; ++axis) {
      for (std::int64_t i = 0; i < kSamples; ++i) channel[i] = rows[static_cast<std::size_t>(3 * i + axis)];
      const PsdCurve curve = welch_psd(channel, kRate, options);
      REQUIRE(curve.psd.size() == static_cast<std::size_t>(kSegment / 2 + 1));
      edf = kEdfMargin * curve.edf[kFirstBin];
      const boost::math::chi_squared chi(edf);
      const double low = boost::math::quantile(chi, 0.005), high = boost::math::quantile(chi, 0.995);
      for (std::int64_t k = kFirstBin; k < kSegment / 2; ++k) {
        pooled[k] += curve.psd[k] / kRealizations;
        const double stat = curve.psd[k] * edf / expected[k];
        if (stat < low || stat > high) ++outside[k];
      }
    }
  }
  const boost::math::chi_squared chi_pooled(kRealizations * edf);
  const double alpha = 1e-3 / (2 * kPairs);
  const double low = boost::math::quantile(chi_pooled, alpha / 2) / (kRealizations * edf);
  const double high = boost::math::quantile(chi_pooled, 1 - alpha / 2) / (kRealizations * edf);
  const int allowed = failure_count();
  int pooled_failures = 0, count_failures = 0;
  double worst = 1;
  for (std::int64_t k = kFirstBin; k < kSegment / 2; ++k) {
    const double ratio = pooled[k] / expected[k];
    if (std::abs(std::log(ratio)) > std::abs(std::log(worst))) worst = ratio;
    if (ratio < low || ratio > high) ++pooled_failures;
    if (outside[k] >= allowed) ++count_failures;
  }
  INFO("pooled ratio interval [" << low << ", " << high << "], worst bin ratio " << worst
                                 << "; a bin fails with " << allowed << " of " << kRealizations
                                 << " estimates outside their 99% interval");
  CHECK(pooled_failures == 0);
  CHECK(count_failures == 0);
}

}  // namespace

TEST_CASE("the arithmetic of the PSD checks") {
  CHECK(kPairs == 2550);
  // c = 7: 2550 x P(Bin(30, 0.01) >= 7) = 2550 x 1.6e-8 = 4e-5 < 5e-4, while c = 6 gives 1.2e-3.
  CHECK(failure_count() == 7);
}

TEST_CASE("each term's Welch PSD matches its exact expected value at every bin") {
  NoiseTerms t;
  SUBCASE("white") { t.white = 1e-3; }
  SUBCASE("quantization") { t.quantization = 1e-6; }
  SUBCASE("flicker") { t.bias_instability = 2e-5; }
  SUBCASE("rate random walk") { t.rate_random_walk = 1e-5; }
  SUBCASE("Gauss-Markov") { t.gauss_markov = {GaussMarkov{1e-4, 0.5}}; }
  check_term(t);
}

TEST_CASE("the exact expected Welch PSD is the analytic PSD up to leakage and sampling") {
  // The one-sided analytic value is 2 two_sided_psd(f) at f = k fs / M. The exact expectation
  // differs by two known effects, bounded per bin:
  //  - the Hann kernel smooths over +-1 bin with second moment 1/3 bin^2, so to second order the
  //    relative change is S''/(6 S) bin^2, estimated by the second difference of S itself (e.g.
  //    1/(3 k^2) for S ~ f^2 or 1/f, 1/k^2 for 1/f^2: large only at the lowest bins);
  //  - the discrete-time process: flicker 1/(2 sin x) and random walk / Gauss-Markov above their
  //    corner 1/(4 sin^2 x) in place of 1/(2x) and 1/(4x^2), x = pi f tau0: (x / sin x)^p - 1
  //    with p = 1 and 2 (white and quantization are exact, two_sided_psd being discrete already).
  // Each bin from k = 4 must lie within 1.15 x the sum (the 15 % covers third-order smoothing
  // terms: at the flicker's k = 4 the second-order estimate 2.08 % is met by 2.25 %). Below k = 4
  // the kernel spans a factor >= 3 in f and the expansion does not hold (1/f^2 at k = 2: 48 %
  // against 41 %); those bins are covered by the exact comparison above.
  constexpr std::int64_t kFirstAnalyticBin = 4;
  struct Case {
    std::string name;
    NoiseTerms terms;
    NoiseTerm term;
    double power;  // p above
  };
  NoiseTerms white, quant, flicker, rw, gm;
  white.white = 1e-3;
  quant.quantization = 1e-6;
  flicker.bias_instability = 2e-5;
  rw.rate_random_walk = 1e-5;
  gm.gauss_markov = {GaussMarkov{1e-4, 0.5}};
  const std::vector<Case> cases{{"white", white, NoiseTerm::white, 0},
                                {"quantization", quant, NoiseTerm::quantization, 0},
                                {"flicker", flicker, NoiseTerm::bias_instability, 1},
                                {"rate random walk", rw, NoiseTerm::rate_random_walk, 2},
                                {"Gauss-Markov", gm, NoiseTerm::gauss_markov, 2}};
  for (const auto& c : cases) {
    const auto e = expected_psd(c.terms);
    const auto analytic = [&](std::int64_t k) {
      return 2 * two_sided_psd(c.terms, c.term, static_cast<double>(k) * kRate / kSegment, kTau0);
    };
    int bad = 0;
    double worst = 0;
    for (std::int64_t k = kFirstAnalyticBin; k < kSegment / 2; ++k) {
      const double s = analytic(k);
      const double smoothing = std::abs(analytic(k + 1) + analytic(k - 1) - 2 * s) / (6 * s);
      const double x = kPi * static_cast<double>(k) / kSegment;
      const double sampling = std::pow(x / std::sin(x), c.power) - 1;
      const double difference = std::abs(e[k] / s - 1);
      worst = std::max(worst, difference / (smoothing + sampling + 1e-13));
      if (difference > 1.15 * (smoothing + sampling) + 1e-12) ++bad;
    }
    INFO(c.name << ": " << bad << " bins outside their bound; worst difference / bound " << worst);
    CHECK(bad == 0);
  }
}
