// The AVAR of a real quantizer of the integrated output: see simulate_quantizer.hpp for the
// notation and the derivation.

#include "simulate_quantizer.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>

namespace sigmatau::detail {
namespace {

constexpr double kPi = std::numbers::pi;
/// Series terms are dropped once exp(-a n^2) < e^-40 (4e-18, below double rounding).
constexpr double kSeriesCut = 40;
/// At most this many series terms; beyond it (a Gaussian part below ~1e-6 D) the Gaussian
/// factor is dropped and, without an additive term, the closed form is used: the relative
/// error is about 2 sqrt(a) < 1e-5.
constexpr double kMaxTerms = 1e6;

/// Variance of the sum of m Gauss-Markov samples times tau0^2:
/// sigma^2 tau0^2 (m + 2 phi (m (1 - phi) - (1 - phi^m)) / (1 - phi)^2).
double gauss_markov_increment_variance(const GaussMarkov& gm, double m, double tau0_s) {
  const double phi = std::exp(-tau0_s / gm.tau_c_s);
  const double one = 1 - phi;
  const double sum = one > 1e-12 ? m + 2 * phi * (m * one - (1 - std::pow(phi, m))) / (one * one)
                                 : m * m;  // phi -> 1: a constant over the m samples
  return gm.sigma * gm.sigma * tau0_s * tau0_s * sum;
}

/// R(j) of the file comment for mean increment mu, Gaussian variance v and uniform width w.
double rounding_autocovariance(double step, double mu, double v, double w) {
  const double a = 2 * kPi * kPi * v / (step * step);
  const double x = mu / step - std::floor(mu / step);
  if (w == 0 && !(a * kMaxTerms * kMaxTerms > kSeriesCut))  // sum cos(2 pi n x)/n^2 in closed form
    return step * step / 2 * (x * x - x + 1.0 / 6);
  const double terms = a > 0 ? std::min(kMaxTerms, std::ceil(std::sqrt(kSeriesCut / a))) : kMaxTerms;
  double sum = 0;
  for (double n = terms; n >= 1; n -= 1) {  // small terms first
    double t = std::cos(2 * kPi * n * x) * std::exp(-a * n * n) / (n * n);
    if (w > 0) {
      const double y = kPi * n * w / step;
      const double sinc = std::sin(y) / y;
      t *= sinc * sinc;
    }
    sum += t;
  }
  return step * step / (2 * kPi * kPi) * sum;
}

}  // namespace

bool real_quantizer_exact(const SimulationConfig& c, const NoiseTerms& t) {
  return !c.schedule && !c.truth_series && !c.temperature_profile && !t.rate_random_walk &&
         !t.rate_ramp && !t.sinusoid;
}

double flicker_window_variance(std::int64_t j, std::int64_t taps) {
  // S(i) = sum_{t<=i} h_t for 0 <= i < taps (S(taps - 1) beyond); c_p = S(min(taps - 1, j - 1 + p))
  // - S(p - 1) with S(-1) = 0, for p from 1 - j to taps - 1.
  std::vector<double> cumulative(static_cast<std::size_t>(taps));
  double h = 1, sum = 0;
  for (std::int64_t i = 0; i < taps; ++i) {
    if (i > 0) h *= (static_cast<double>(i) - 0.5) / static_cast<double>(i);
    sum += h;
    cumulative[static_cast<std::size_t>(i)] = sum;
  }
  const auto s = [&](std::int64_t i) {
    return i < 0 ? 0.0 : cumulative[static_cast<std::size_t>(std::min(i, taps - 1))];
  };
  double v = 0;
  for (std::int64_t p = 1 - j; p < taps; ++p) {
    const double c = s(std::min(taps - 1, j - 1 + p)) - s(p - 1);
    v += c * c;
  }
  return v;
}

double per_sample_gaussian_variance(const NoiseTerms& t, double tau0_s) {
  double v = t.white ? *t.white * *t.white * tau0_s : 0.0;
  for (const GaussMarkov& gm : t.gauss_markov) v += gauss_markov_increment_variance(gm, 1, tau0_s);
  return v;
}

double real_quantizer_avar(double step, std::int64_t m, double tau0_s, const NoiseTerms& t,
                           double drift, std::int64_t flicker_taps) {
  const double w = t.quantization ? *t.quantization * std::sqrt(12.0) : 0.0;
  const auto r = [&](double j) {
    double v = t.white ? *t.white * *t.white * tau0_s * j : 0.0;
    for (const GaussMarkov& gm : t.gauss_markov)  // independent entries: variances add
      v += gauss_markov_increment_variance(gm, j, tau0_s);
    // Every harmonic is below e^-40 already: R = 0 whatever the flicker adds (it only adds
    // variance), so its O(taps) sum is skipped.
    if (2 * kPi * kPi * v / (step * step) > kSeriesCut) return 0.0;
    if (t.bias_instability)
      v += *t.bias_instability * *t.bias_instability * tau0_s * tau0_s *
           flicker_window_variance(static_cast<std::int64_t>(j), flicker_taps);
    return rounding_autocovariance(step, drift * tau0_s * j, v, w);
  };
  const double md = static_cast<double>(m);
  const double tau = md * tau0_s;
  return (step * step / 2 - 8 * r(md) + 2 * r(2 * md)) / (2 * tau * tau);
}

}  // namespace sigmatau::detail

namespace sigmatau {

std::vector<std::string> simulation_warnings(const SimulationConfig& c) {
  std::vector<std::string> out;
  const double tau0 = 1 / c.rate_hz;
  for (const auto& [model, step, sensor, prefix] :
       {std::tuple{c.gyro ? &*c.gyro : nullptr, c.gyro_quantizer_step, "gyro", "g"},
        std::tuple{c.accel ? &*c.accel : nullptr, c.accel_quantizer_step, "accel", "a"}}) {
    if (!model || !(step > 0)) continue;
    std::string axes;
    double worst = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const NoiseTerms& t = model->noise[static_cast<std::size_t>(axis)];
      if (detail::real_quantizer_exact(c, t)) continue;
      const double s = std::sqrt(detail::per_sample_gaussian_variance(t, tau0));
      const double ratio = s > 0 ? step / s : std::numeric_limits<double>::infinity();
      if (!(ratio > detail::kQuantizerStepRatioLimit)) continue;
      axes += std::string(axes.empty() ? "" : ", ") + prefix + "xyz"[axis];
      worst = std::max(worst, ratio);
    }
    if (axes.empty()) continue;
    char ratio_text[32];
    std::snprintf(ratio_text, sizeof ratio_text, "%.3g", worst);
    out.push_back(
        std::string("the ") + sensor + " quantizer step is " +
        (std::isinf(worst) ? std::string("larger than the (zero) white noise")
                           : std::string(ratio_text) + "x the per-sample white noise") +
        " on " + axes + ", whose model (rate random walk, ramp, sinusoid or a varying truth or "
        "temperature) has no exact quantizer theory: the sidecar's quantization term "
        "3 Q^2/tau^2 (Q = step/sqrt(12)) is then approximate at short tau, too high when the "
        "signal moves less than a step per sample (10x at a step of 40x the noise) and up to 2x "
        "too low with a drift near half a step per sample; it holds to 0.6 % when the step is "
        "at most 2x the per-sample noise");
  }
  return out;
}

}  // namespace sigmatau
