// Theory in one place: the exact sampled AVAR of each term against published or independently
// derived values, the continuous forms against their PSDs, read-off rules and the error model.
#include "sigmatau/noise_model.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "sigmatau/error.hpp"
#include "test_support.hpp"

using namespace sigmatau;
using sigmatau::test::rel;

namespace {

constexpr double kPi = std::numbers::pi;

/// 4 int_0^inf S(f) sin^4(pi f tau)/(pi f tau)^2 df (IEEE 952 two-sided kernel), by Simpson's
/// rule in u = ln f over f in [1e-9, 1e5]/tau with 40000 intervals. The integrands here fall
/// like f^-2 (or faster) above 1/tau, so the part beyond 1e5/tau is < 1e-5 relative, and the
/// rule's error at this step (ln-width 4.6e-4) is far below that.
double avar_from_psd(const NoiseTerms& t, NoiseTerm term, double tau) {
  const double lo = std::log(1e-9 / tau), hi = std::log(1e5 / tau);
  const int n = 40000;
  const double h = (hi - lo) / n;
  double sum = 0;
  for (int i = 0; i <= n; ++i) {
    const double f = std::exp(lo + i * h);
    const double x = kPi * f * tau;
    const double g = two_sided_psd(t, term, f, 0.0) * std::pow(std::sin(x), 4) / (x * x) * f;
    sum += g * (i == 0 || i == n ? 1 : (i % 2 ? 4 : 2));
  }
  return 4 * sum * h / 3;
}

}  // namespace

TEST_CASE("sampled flicker AVAR matches the integrated Kasdin table of THEORY.md section 6") {
  // Table values are printed to 6 significant digits: tolerance 2e-6 relative (half a unit in
  // the 6th digit is <= 1.1e-6 relative for these values, plus the sum's own ~1e-9).
  const double q = 2 * std::numbers::ln2 / kPi;
  // Closed forms at m = 1, 2; the untruncated sum's asymptotic tail is good to ~2e-9.
  CHECK(flicker_avar_per_unit(1, 0) == rel(2 / kPi, 5e-9));
  CHECK(flicker_avar_per_unit(2, 0) == rel(1.6 / kPi, 5e-9));
  CHECK(flicker_avar_per_unit(4, 0) == rel(0.463335, 2e-6));
  CHECK(flicker_avar_per_unit(8, 0) == rel(0.448072, 2e-6));
  CHECK(flicker_avar_per_unit(16, 0) == rel(0.443294, 2e-6));
  CHECK(flicker_avar_per_unit(64, 0) == rel(0.441438, 2e-6));
  CHECK(flicker_avar_per_unit(256, 0) == rel(0.441284, 2e-6));
  CHECK(flicker_avar_per_unit(1024, 0) == rel(0.441272, 2e-6));
  CHECK(flicker_avar_per_unit(std::int64_t{1} << 20, 0) == rel(q, 1e-9));
}

TEST_CASE("a long truncated flicker filter approaches the untruncated one at small m") {
  // Truncation to L taps removes power below ~1/L cycles per sample; at m << L the AVAR kernel
  // barely sees it: relative change ~ m/L (here <= 2^-12), so 1e-3 is generous.
  for (std::int64_t m : {1, 4, 16}) {
    SIGMATAU_CHECK_REL(flicker_avar_per_unit(m, std::int64_t{1} << 16), flicker_avar_per_unit(m, 0),
                       1e-3);
  }
  // Near m = L/4 the sharp truncation (a spectral ripple just above 1/L) raises the AVAR a
  // few percent above the untruncated value: 1.5% at m = L/16 (computed; see flicker_band).
  CHECK(flicker_avar_per_unit(4096, 1 << 16) > flicker_avar_per_unit(4096, 0));
}

TEST_CASE("flicker band: flat to +-0.05 in ADEV slope between m_low and m_high") {
  const FlickerBand ideal = flicker_band(0);
  CHECK(ideal.m_low == 4);  // slope(2->4) = -0.068 and slope(4->8) = -0.024 from the table
  CHECK(ideal.m_high == std::numeric_limits<std::int64_t>::max());
  for (std::int64_t taps : {std::int64_t{1} << 14, std::int64_t{1} << 18}) {
    const FlickerBand b = flicker_band(taps);
    INFO("taps " << taps << " band " << b.m_low << ".." << b.m_high);
    CHECK(b.m_low == 4);
    CHECK(b.m_high >= taps / 4);  // the flat band reaches L/4 (the simulator's claimed band)
    CHECK(b.m_high < taps);
    for (std::int64_t m = b.m_low; m < b.m_high; m *= 2) {
      const double slope =
          0.5 * std::log2(flicker_avar_per_unit(2 * m, taps) / flicker_avar_per_unit(m, taps));
      CHECK(std::abs(slope) <= 0.05);
    }
    const double beyond = 0.5 * std::log2(flicker_avar_per_unit(2 * b.m_high, taps) /
                                          flicker_avar_per_unit(b.m_high, taps));
    CHECK(std::abs(beyond) > 0.05);
  }
}

TEST_CASE("sampled white, quantization, random walk and ramp follow Zhang's exact forms") {
  NoiseTerms t;
  t.white = 2e-3;
  t.quantization = 1e-5;
  t.rate_random_walk = 3e-4;
  t.rate_ramp = 1e-6;
  const Sampling s{0.01, 0, false};
  for (std::int64_t m : {1, 3, 100, 12345}) {
    const double tau = static_cast<double>(m) * 0.01;
    // Pure arithmetic identities: tolerance 1e-12 covers rounding.
    SIGMATAU_CHECK_REL(sampled_avar(t, NoiseTerm::white, m, s), 4e-6 / tau, 1e-12);
    SIGMATAU_CHECK_REL(sampled_avar(t, NoiseTerm::quantization, m, s), 3e-10 / (tau * tau), 1e-12);
    SIGMATAU_CHECK_REL(sampled_avar(t, NoiseTerm::rate_random_walk, m, s),
                       9e-8 * tau / 3 + 9e-8 * 1e-4 / (6 * tau), 1e-12);
    SIGMATAU_CHECK_REL(sampled_avar(t, NoiseTerm::rate_ramp, m, s), 1e-12 * tau * tau / 2, 1e-12);
  }
  CHECK(sampled_avar(t, NoiseTerm::gauss_markov, 4, s) == 0);  // absent term: nothing
  CHECK_THROWS_AS(sampled_avar(t, 0, s), Error);
  CHECK_THROWS_AS(sampled_avar(t, 1, Sampling{0.0, 0, false}), Error);
}

TEST_CASE("Gauss-Markov: continuous form reproduces THEORY.md T12 and its hump") {
  NoiseTerms t;
  t.gauss_markov = {GaussMarkov{1.0, 10.0}};
  // T12 is printed to 6 digits: 2e-6 relative.
  CHECK(continuous_avar(t, NoiseTerm::gauss_markov, 1.0) == rel(0.0618919, 2e-6));
  CHECK(continuous_avar(t, NoiseTerm::gauss_markov, 10.0) == rel(0.336182, 2e-6));
  CHECK(continuous_avar(t, NoiseTerm::gauss_markov, 100.0) == rel(0.170002, 2e-6));
  // Peak 0.6174 sigma at 1.892 T_c (THEORY.md fact 11): scan, 4 digits printed.
  double best = 0, best_tau = 0;
  for (double tau = 10; tau < 30; tau += 0.001) {
    const double a = std::sqrt(continuous_avar(t, NoiseTerm::gauss_markov, tau));
    if (a > best) best = a, best_tau = tau;
  }
  CHECK(best == rel(0.6174, 1e-4));
  CHECK(best_tau == rel(18.92, 1e-3));
  // Small tau/T_c uses a series; it must join the closed form continuously (r = 1e-3 switch).
  SIGMATAU_CHECK_REL(continuous_avar(t, NoiseTerm::gauss_markov, 0.00999999),
                     continuous_avar(t, NoiseTerm::gauss_markov, 0.01000001), 1e-5);
}

TEST_CASE("Gauss-Markov: sampled AR(1) form against a long-double ACF sum and its limits") {
  // General ACF form (Zhang 2008): AV_n = s^2/n^2 (n (1 - rho(n)) + sum i [2 rho(n-i) - rho(i)
  // - rho(2n-i)]) with rho(i) = phi^i, summed in long double. Where (2n+1) a < 0.5 the library
  // uses a Taylor series; both sides agree to ~1e-12 here (a >= 1e-3 keeps the ACF sum's
  // cancellation at <= 1e-19 / (n a)^2 ~ 1e-13), so 1e-9 is safe.
  for (double a : {1e-3, 1e-2, 0.3, 2.0}) {
    for (std::int64_t n : {1, 2, 7, 40, 300}) {
      NoiseTerms t;
      t.gauss_markov = {GaussMarkov{1.5, 1.0 / a}};
      const long double phi = std::exp(-static_cast<long double>(a));
      long double acc = n * (1 - std::pow(phi, static_cast<long double>(n)));
      for (std::int64_t i = 1; i < n; ++i)
        acc += i * (2 * std::pow(phi, static_cast<long double>(n - i)) -
                    std::pow(phi, static_cast<long double>(i)) -
                    std::pow(phi, static_cast<long double>(2 * n - i)));
      const double expected = static_cast<double>(2.25L * acc / (static_cast<long double>(n) * n));
      INFO("a = " << a << ", n = " << n);
      SIGMATAU_CHECK_REL(sampled_avar(t, NoiseTerm::gauss_markov, n, Sampling{1.0, 0, false}),
                         expected, 1e-9);
    }
  }
  // tau0/T_c = 1e-3: the sampled form tends to the continuous one; at n >= 100 they differ by
  // the point-sampling term (relative ~1/(2 n^2) in the random-walk regime) plus O(tau0/T_c)
  // in the hump: 2e-3 bounds both.
  NoiseTerms t;
  t.gauss_markov = {GaussMarkov{1.0, 10.0}};
  for (std::int64_t n : {100, 1000, 10000, 100000})
    SIGMATAU_CHECK_REL(sampled_avar(t, NoiseTerm::gauss_markov, n, Sampling{0.01, 0, false}),
                       continuous_avar(t, NoiseTerm::gauss_markov, static_cast<double>(n) * 0.01), 2e-3);
  // tau0/T_c = 1e-8 (the cancellation-prone case) stays on the random-walk line
  // q (2n^2+1)/(6n), q = sigma^2 (1 - phi^2): relative deviation O(n tau0/T_c) <= 1e-5.
  NoiseTerms slow;
  slow.gauss_markov = {GaussMarkov{1.0, 1e8}};
  for (std::int64_t n : {1, 10, 1000}) {
    const double q = -std::expm1(-2e-8);
    SIGMATAU_CHECK_REL(sampled_avar(slow, NoiseTerm::gauss_markov, n, Sampling{1.0, 0, false}),
                       q * (2.0 * static_cast<double>(n * n) + 1) / (6.0 * static_cast<double>(n)), 1e-5);
  }
}

TEST_CASE("sinusoid: sampled form tends to the continuous one, whose ADEV peaks at 0.7246 A") {
  NoiseTerms t;
  t.sinusoid = Sinusoid{2.0, 0.5, 0.3};
  double best = 0, best_tau = 0;
  for (double tau = 0.5; tau < 1.0; tau += 1e-5) {
    const double a = std::sqrt(continuous_avar(t, NoiseTerm::sinusoid, tau));
    if (a > best) best = a, best_tau = tau;
  }
  CHECK(best / 2.0 == rel(0.7246, 1e-4));          // 4 digits printed in THEORY.md
  CHECK(best_tau * 0.5 == rel(0.3710, 2e-4));      // 4 digits printed
  // tau0 = 1e-4 s: n^2 sin^2(theta/2) = (pi f tau)^2 (1 + O(theta^2)), theta = 3e-4 -> 1e-8.
  for (std::int64_t n : {100, 7421, 20000})
    SIGMATAU_CHECK_REL(sampled_avar(t, NoiseTerm::sinusoid, n, Sampling{1e-4, 0, false}),
                       continuous_avar(t, NoiseTerm::sinusoid, static_cast<double>(n) * 1e-4), 1e-7);
  // Interval averaging scales the amplitude by sinc(pi f tau0).
  const double x = kPi * 0.5 * 0.1;
  SIGMATAU_CHECK_REL(sampled_avar(t, NoiseTerm::sinusoid, 3, Sampling{0.1, 0, true}),
                     sampled_avar(t, NoiseTerm::sinusoid, 3, Sampling{0.1, 0, false}) *
                         std::pow(std::sin(x) / x, 2),
                     1e-12);
}

TEST_CASE("continuous AVAR of each term equals the IEEE 4-integral of its two-sided PSD") {
  NoiseTerms t;
  t.white = 3e-3;
  t.bias_instability = 2e-4;
  t.rate_random_walk = 5e-5;
  t.gauss_markov = {GaussMarkov{1e-3, 20.0}};
  for (NoiseTerm term : {NoiseTerm::white, NoiseTerm::bias_instability,
                         NoiseTerm::rate_random_walk, NoiseTerm::gauss_markov}) {
    for (double tau : {0.1, 3.0, 100.0}) {
      INFO(to_string(term) << " tau " << tau);
      // Quadrature and truncation error < 1e-5 (see avar_from_psd); 1e-4 leaves margin.
      SIGMATAU_CHECK_REL(avar_from_psd(t, term, tau), continuous_avar(t, term, tau), 1e-4);
    }
  }
}

TEST_CASE("quantization PSD is the discrete difference of white angle error") {
  NoiseTerms t;
  t.quantization = 1e-4;
  // S(f) = (4 Q^2/tau0) sin^2(pi f tau0) -> tau0 Q^2 (2 pi f)^2 for f << 1/tau0 (THEORY.md).
  SIGMATAU_CHECK_REL(two_sided_psd(t, NoiseTerm::quantization, 0.01, 0.01),
                     0.01 * 1e-8 * std::pow(2 * kPi * 0.01, 2), 1e-7);  // O((pi f tau0)^2)=1e-7
  CHECK_THROWS_AS(two_sided_psd(t, NoiseTerm::quantization, 1.0, 0.0), Error);
  CHECK_THROWS_AS(two_sided_psd(t, NoiseTerm::white, 0.0, 0.01), Error);
}

TEST_CASE("read-off rules: each line passes through the parameter at its IEEE tau") {
  CHECK(adev_line(NoiseTerm::white, 2.0, 1.0) == rel(2.0, 1e-15));
  CHECK(adev_line(NoiseTerm::rate_random_walk, 2.0, 3.0) == rel(2.0, 1e-15));
  CHECK(adev_line(NoiseTerm::rate_ramp, 2.0, std::sqrt(2.0)) == rel(2.0, 1e-15));
  CHECK(adev_line(NoiseTerm::quantization, 2.0, std::sqrt(3.0)) == rel(2.0, 1e-15));
  CHECK(adev_line(NoiseTerm::bias_instability, 1.0, 123.0) == rel(0.664282, 1e-6));
  // and coincides with the continuous ADEV of the power-law terms at every tau (identity).
  NoiseTerms t;
  t.white = 0.3;
  t.rate_random_walk = 0.02;
  t.rate_ramp = 0.001;
  t.quantization = 0.01;
  for (double tau : {0.01, 1.0, 500.0})
    for (NoiseTerm term : {NoiseTerm::white, NoiseTerm::rate_random_walk, NoiseTerm::rate_ramp,
                           NoiseTerm::quantization}) {
      const double value = term == NoiseTerm::white              ? 0.3
                           : term == NoiseTerm::rate_random_walk ? 0.02
                           : term == NoiseTerm::rate_ramp        ? 0.001
                                                                 : 0.01;
      SIGMATAU_CHECK_REL(adev_line(term, value, tau), std::sqrt(continuous_avar(t, term, tau)),
                         1e-13);
    }
  CHECK_THROWS_AS(read_off(NoiseTerm::gauss_markov), Error);
}

TEST_CASE("absent terms are absent everywhere") {
  NoiseTerms t;
  CHECK(t.empty());
  CHECK(sampled_avar(t, 8, Sampling{0.01, 0, false}) == 0);
  CHECK(continuous_avar(t, 1.0) == 0);
  for (NoiseTerm term : kAllNoiseTerms) CHECK_FALSE(has_term(t, term));
  t.white = 1.0;
  t.rate_ramp = 2.0;
  const NoiseTerms w = only(t, NoiseTerm::white);
  CHECK(w.white == 1.0);
  CHECK_FALSE(w.rate_ramp.has_value());
}

TEST_CASE("error model: (I + T) x + b + c (T - T0) and validation") {
  ErrorModel m;
  m.scale_factor = Eigen::Vector3d(1e-3, -2e-3, 5e-4);
  m.misalignment << 0, 1e-3, -2e-3, 3e-3, 0, 4e-4, -1e-4, 2e-4, 0;
  m.bias = Eigen::Vector3d(0.1, -0.2, 0.3);
  m.temperature_coefficient = Eigen::Vector3d(0.01, 0.02, -0.03);
  const Eigen::Vector3d x(1.0, 2.0, -3.0);
  const Eigen::Vector3d y = m.deterministic_output(x, m.reference_temperature_k + 10);
  // Written out by hand, row by row.
  CHECK(y[0] == rel((1 + 1e-3) * 1 + 1e-3 * 2 + -2e-3 * -3 + 0.1 + 0.1, 1e-14));
  CHECK(y[1] == rel(3e-3 * 1 + (1 - 2e-3) * 2 + 4e-4 * -3 - 0.2 + 0.2, 1e-14));
  CHECK(y[2] == rel(-1e-4 * 1 + 2e-4 * 2 + (1 + 5e-4) * -3 + 0.3 - 0.3, 1e-14));
  CHECK_NOTHROW(m.validate("gyro"));
  ErrorModel bad = m;
  bad.misalignment(1, 1) = 1e-3;
  CHECK_THROWS_WITH_AS(bad.validate("gyro"), doctest::Contains("diagonal"), Error);
  bad = m;
  bad.noise[2].white = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_WITH_AS(bad.validate("gyro"), doctest::Contains("gyro.z"), Error);
  bad = m;
  bad.noise[0].gauss_markov = {GaussMarkov{1.0, 0.0}};
  CHECK_THROWS_AS(bad.validate("accel"), Error);
}

TEST_CASE("a sum of Gauss-Markov processes: AVARs and PSDs are the sums of the entries'") {
  // Independent processes: the variance of a sum is the sum of the variances, so every
  // second-moment quantity adds. The sums here are of 2-3 positive doubles: 1e-15 relative.
  const GaussMarkov a{1e-4, 0.5}, b{3e-5, 40.0}, c{2e-6, 3000.0};
  NoiseTerms sum;
  sum.white = 1e-4;
  sum.gauss_markov = {a, b, c};
  const Sampling s{0.01, 0, false};
  CHECK(has_term(sum, NoiseTerm::gauss_markov));
  CHECK_FALSE(has_term(NoiseTerms{}, NoiseTerm::gauss_markov));
  CHECK(only(sum, NoiseTerm::gauss_markov).gauss_markov == sum.gauss_markov);
  CHECK_FALSE(only(sum, NoiseTerm::gauss_markov).white.has_value());
  CHECK(only_gauss_markov(sum, 1).gauss_markov == std::vector<GaussMarkov>{b});
  CHECK_THROWS_AS(only_gauss_markov(sum, 3), Error);
  NoiseTerms gm_only;
  gm_only.gauss_markov = {a};
  CHECK_FALSE(gm_only.empty());
  for (std::int64_t m : {1, 16, 1024, 65536}) {
    double each = 0;
    for (std::size_t i = 0; i < 3; ++i)
      each += sampled_avar(only_gauss_markov(sum, i), NoiseTerm::gauss_markov, m, s);
    SIGMATAU_CHECK_REL(sampled_avar(sum, NoiseTerm::gauss_markov, m, s), each, 1e-15);
    SIGMATAU_CHECK_REL(sampled_avar(sum, m, s),
                       each + sampled_avar(sum, NoiseTerm::white, m, s), 1e-15);
    const double tau = static_cast<double>(m) * 0.01;
    double each_c = 0;
    for (std::size_t i = 0; i < 3; ++i)
      each_c += continuous_avar(only_gauss_markov(sum, i), NoiseTerm::gauss_markov, tau);
    SIGMATAU_CHECK_REL(continuous_avar(sum, NoiseTerm::gauss_markov, tau), each_c, 1e-15);
  }
  for (double f : {1e-4, 0.01, 1.0, 40.0}) {
    double each = 0;
    for (std::size_t i = 0; i < 3; ++i)
      each += two_sided_psd(only_gauss_markov(sum, i), NoiseTerm::gauss_markov, f, 0.01);
    SIGMATAU_CHECK_REL(two_sided_psd(sum, NoiseTerm::gauss_markov, f, 0.01), each, 1e-15);
  }
}
