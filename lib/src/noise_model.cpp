// Noise terms, their exact sampled and continuous Allan variances, PSDs and read-off rules.
//
// Glossary (THEORY.md section 2; Zhang 2008; Kasdin 1995):
//   tau0   sample interval [s];  m = n  averaging factor;  tau = m tau0 [s]
//   Q      quantization [rad | m/s];  N white density;  B bias instability;  K rate random walk;
//   R      rate ramp;  sigma, T_c  Gauss-Markov;  A, f  sinusoid (units: noise_model.hpp)
//   phi    exp(-tau0/T_c), the AR(1) coefficient of the sampled Gauss-Markov process
//   h_k    Kasdin fractional-integration filter for 1/f: h_0 = 1, h_k = h_{k-1} (k - 1/2) / k
//   H_k    cumulative sum of h: sum_{j<=k} h_j = (2k + 1) h_k (checked in tools/noise_model_theory.py)
#include "sigmatau/noise_model.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <limits>
#include <numbers>

#include "sigmatau/error.hpp"

namespace sigmatau {
namespace {

constexpr double kPi = std::numbers::pi;

/// Flicker AVAR ratio to its limit 2 ln2/pi is below 1 + 2e-9 for m >= 2^16 (the deviation
/// falls roughly like m^-1.8: 3e-5 at m = 256, THEORY.md section 6), so beyond this factor the
/// untruncated flicker AVAR is its limit.
constexpr std::int64_t kFlickerAsymptoticM = std::int64_t{1} << 16;
/// Untruncated flicker: the explicit sum runs to k = 2m + kFlickerTailFactor * m, and the
/// remaining tail sum_{k>K} c_k^2 ~ m^2 / (8 pi (K - m)^2) is added in closed form; with 400 the
/// tail is 2.5e-7 of the sum and its asymptotic form is accurate to O(1/400), so the result is
/// good to ~2e-9 relative (1.2e-9 measured at m = 1 against 2/pi).
constexpr std::int64_t kFlickerTailFactor = 400;
/// Local ADEV slope accepted as "flat" for the flicker band (the issue's +-0.05).
constexpr double kFlickerFlatSlope = 0.05;
/// Below (2n+1) tau0/T_c = 0.5 the AR(1) AVAR numerator is summed as a Taylor series (the closed
/// form cancels to relative size (n a)^2/3 there); above, the closed form loses < 1e-13.
constexpr double kGaussMarkovSeriesLimit = 0.5;

void require_m_tau0(std::int64_t m, double tau0_s) {
  if (!(m >= 1)) throw Error("averaging factor m must be >= 1, got " + std::to_string(m));
  if (!(tau0_s > 0) || !std::isfinite(tau0_s))
    throw Error("sample interval tau0 must be > 0 s, got " + std::to_string(tau0_s));
}

/// Sampled AR(1) (Gauss-Markov) AVAR per unit stationary variance at n, a = tau0 / T_c:
/// f / (n^2 (1 - phi)^2) with f = n (1 - e^{-2a}) - 3 e^{-a} + 4 e^{-(n+1) a} - e^{-(2n+1) a}
/// (Zhang 2008 with innovation variance sigma^2 (1 - phi^2), rearranged).
double ar1_avar_per_unit(double n, double a) {
  double f = 0;
  if ((2 * n + 1) * a < kGaussMarkovSeriesLimit) {
    // f = sum_{j>=3} (-a)^j / j! c_j(n), c_j = 4 (n+1)^j - (2n+1)^j - n 2^j - 3 (c_0..c_2 = 0).
    double pa = 1, p1 = 1, p2 = 1, p3 = 1, fact = 1;
    for (int j = 1; j <= 60; ++j) {
      pa *= -a;
      p1 *= n + 1;
      p2 *= 2 * n + 1;
      p3 *= 2;
      fact *= j;
      if (j < 3) continue;
      const double term = pa / fact * (4 * p1 - p2 - n * p3 - 3);
      f += term;
      if (std::abs(term) < 1e-18 * std::abs(f)) break;
    }
  } else {
    f = -n * std::expm1(-2 * a) - 3 * std::exp(-a) + 4 * std::exp(-(n + 1) * a) -
        std::exp(-(2 * n + 1) * a);
  }
  const double one_minus_phi = -std::expm1(-a);
  return f / (n * n * one_minus_phi * one_minus_phi);
}

// Continuous-time AVAR of one first-order Gauss-Markov process at tau (noise_model.hpp).
double gauss_markov_continuous_avar(const GaussMarkov& gm, double tau) {
  const double s2 = gm.sigma * gm.sigma;
  const double r = tau / gm.tau_c_s;
  // 3 - 4 e^{-r} + e^{-2r} = (1 - e^{-r})(3 - e^{-r}) = e (2 + e) with e = 1 - e^{-r}.
  // For small r the bracket 1 - e (2 + e)/(2r) cancels; its series is
  // r^2/3 - r^3/4 + 7 r^4/60 - ... (next term ~r^5, i.e. < 1e-9 relative for r < 1e-3).
  if (r < 1e-3) return 2 * s2 * (r / 3 - r * r / 4 + 7 * r * r * r / 60);
  const double e = -std::expm1(-r);
  return 2 * s2 / r * (1 - e * (2 + e) / (2 * r));
}

}  // namespace

std::string_view to_string(Sensor sensor) { return sensor == Sensor::gyro ? "gyro" : "accel"; }

bool NoiseTerms::empty() const {
  return !quantization && !white && !bias_instability && !rate_random_walk && !rate_ramp &&
         gauss_markov.empty() && !sinusoid;
}

std::string_view to_string(NoiseTerm term) {
  switch (term) {
    case NoiseTerm::quantization: return "quantization";
    case NoiseTerm::white: return "white";
    case NoiseTerm::bias_instability: return "bias_instability";
    case NoiseTerm::rate_random_walk: return "rate_random_walk";
    case NoiseTerm::rate_ramp: return "rate_ramp";
    case NoiseTerm::gauss_markov: return "gauss_markov";
    case NoiseTerm::sinusoid: return "sinusoid";
  }
  return "?";
}

bool has_term(const NoiseTerms& t, NoiseTerm term) {
  switch (term) {
    case NoiseTerm::quantization: return t.quantization.has_value();
    case NoiseTerm::white: return t.white.has_value();
    case NoiseTerm::bias_instability: return t.bias_instability.has_value();
    case NoiseTerm::rate_random_walk: return t.rate_random_walk.has_value();
    case NoiseTerm::rate_ramp: return t.rate_ramp.has_value();
    case NoiseTerm::gauss_markov: return !t.gauss_markov.empty();
    case NoiseTerm::sinusoid: return t.sinusoid.has_value();
  }
  return false;
}

NoiseTerms only(const NoiseTerms& t, NoiseTerm term) {
  NoiseTerms r;
  switch (term) {
    case NoiseTerm::quantization: r.quantization = t.quantization; break;
    case NoiseTerm::white: r.white = t.white; break;
    case NoiseTerm::bias_instability: r.bias_instability = t.bias_instability; break;
    case NoiseTerm::rate_random_walk: r.rate_random_walk = t.rate_random_walk; break;
    case NoiseTerm::rate_ramp: r.rate_ramp = t.rate_ramp; break;
    case NoiseTerm::gauss_markov: r.gauss_markov = t.gauss_markov; break;
    case NoiseTerm::sinusoid: r.sinusoid = t.sinusoid; break;
  }
  return r;
}

namespace {

/// flicker_avar_per_unit's sum, O(m) long double operations (0.1 s at m = 2^17).
double flicker_avar_sum(std::int64_t m, std::int64_t taps);

/// Most (m, taps) pairs flicker_avar_per_unit keeps: a fit and its consistency guards ask for
/// the same octave factors again and again (11 s of a 6-channel fit of a 1e6-sample log went
/// to recomputing them).
constexpr std::size_t kFlickerCacheSize = 4096;

}  // namespace

NoiseTerms only_gauss_markov(const NoiseTerms& t, std::size_t index) {
  if (index >= t.gauss_markov.size())
    throw Error("Gauss-Markov entry " + std::to_string(index) + " requested, the model has " +
                std::to_string(t.gauss_markov.size()));
  NoiseTerms r;
  r.gauss_markov.push_back(t.gauss_markov[index]);
  return r;
}

double flicker_avar_per_unit(std::int64_t m, std::int64_t taps) {
  if (!(m >= 1)) throw Error("averaging factor m must be >= 1, got " + std::to_string(m));
  if (!(taps >= 0)) throw Error("flicker taps must be >= 0, got " + std::to_string(taps));
  const bool untruncated = taps == 0;
  if (untruncated && m >= kFlickerAsymptoticM) return 2 * std::numbers::ln2 / kPi;
  static std::mutex mutex;
  static std::map<std::pair<std::int64_t, std::int64_t>, double> cache;
  const std::pair key{m, taps};
  {
    std::lock_guard lock(mutex);
    if (const auto it = cache.find(key); it != cache.end()) return it->second;
  }
  const double value = flicker_avar_sum(m, taps);
  std::lock_guard lock(mutex);
  if (cache.size() >= kFlickerCacheSize) cache.clear();
  cache.emplace(key, value);
  return value;
}

namespace {

double flicker_avar_sum(std::int64_t m, std::int64_t taps) {
  const bool untruncated = taps == 0;
  // k runs over the support of c = h * a_m: [0, L - 1 + 2m] (truncated) or [0, K] + tail.
  const std::int64_t k_end = untruncated ? 2 * m + kFlickerTailFactor * m : taps - 1 + 2 * m;
  // H_k for k = 0..k_end, with H_k = H_{L-1} for k >= L (truncated filter). The loop reads
  // H_{k-m} and H_{k-2m}: kept in a ring of the last 2m + 1 values, or, when the filter is
  // shorter than that ring, as its L values (H saturates beyond them), so that memory stays
  // O(min(m, L)). A ring at the longest taus of a simulator sidecar (m ~ N/6) took 16 (2m + 1)
  // bytes: 0.5 GiB at 1e8 samples, 4 GiB at 1e9.
  const bool by_filter = !untruncated && taps < 2 * m + 1;
  std::vector<long double> stored(static_cast<std::size_t>(by_filter ? taps : 2 * m + 1), 0.0L);
  const auto slot = [&](std::int64_t k) -> long double& {
    if (by_filter) return stored[static_cast<std::size_t>(std::min(k, taps - 1))];
    return stored[static_cast<std::size_t>(k % (2 * m + 1))];
  };
  long double h = 1.0L;  // h_k
  long double sum = 0.0L;
  const long double inv_m = 1.0L / static_cast<long double>(m);
  for (std::int64_t k = 0; k <= k_end; ++k) {
    if (k > 0 && (untruncated || k < taps)) h *= (static_cast<long double>(k) - 0.5L) / k;
    const long double big_h =
        (untruncated || k < taps) ? (2.0L * k + 1.0L) * h : slot(k - 1);  // saturates
    const long double h_m = k >= m ? slot(k - m) : 0.0L;
    const long double h_2m = k >= 2 * m ? slot(k - 2 * m) : 0.0L;
    slot(k) = big_h;
    const long double c = (big_h - 2.0L * h_m + h_2m) * inv_m;
    sum += c * c;
  }
  double total = static_cast<double>(sum);
  if (untruncated) {
    const double d = static_cast<double>(k_end - m);
    total += static_cast<double>(m) * static_cast<double>(m) / (8 * kPi * d * d);
  }
  return 0.5 * total;
}

}  // namespace

FlickerBand flicker_band(std::int64_t taps) {
  if (!(taps >= 0)) throw Error("flicker taps must be >= 0, got " + std::to_string(taps));
  const std::int64_t m_limit = taps == 0 ? kFlickerAsymptoticM : taps;
  FlickerBand band;
  double previous = flicker_avar_per_unit(1, taps);
  for (std::int64_t m = 1; 2 * m <= m_limit; m *= 2) {
    const double next = flicker_avar_per_unit(2 * m, taps);
    const double slope = 0.5 * std::log(next / previous) / std::log(2.0);
    previous = next;
    const bool flat = std::abs(slope) <= kFlickerFlatSlope;
    if (flat && band.m_low == 0) band.m_low = m;
    if (flat && band.m_low != 0) band.m_high = 2 * m;
    if (!flat && band.m_low != 0) break;
  }
  if (taps == 0 && band.m_low != 0) band.m_high = std::numeric_limits<std::int64_t>::max();
  return band;
}

double sampled_avar(const NoiseTerms& t, NoiseTerm term, std::int64_t m, const Sampling& s) {
  require_m_tau0(m, s.tau0_s);
  const double n = static_cast<double>(m);
  const double tau0 = s.tau0_s;
  const double tau = n * tau0;
  switch (term) {
    case NoiseTerm::quantization:
      return t.quantization ? 3 * *t.quantization * *t.quantization / (tau * tau) : 0;
    case NoiseTerm::white: return t.white ? *t.white * *t.white / tau : 0;
    case NoiseTerm::bias_instability:
      return t.bias_instability ? *t.bias_instability * *t.bias_instability *
                                      flicker_avar_per_unit(m, s.flicker_taps)
                                : 0;
    case NoiseTerm::rate_random_walk: {
      if (!t.rate_random_walk) return 0;
      const double w2 = *t.rate_random_walk * *t.rate_random_walk * tau0;
      return (2 * n * n + 1) * w2 / (6 * n);
    }
    case NoiseTerm::rate_ramp: return t.rate_ramp ? 0.5 * std::pow(*t.rate_ramp * tau, 2) : 0;
    case NoiseTerm::gauss_markov: {
      double sum = 0;  // independent processes: their AVARs add
      for (const GaussMarkov& gm : t.gauss_markov)
        sum += gm.sigma * gm.sigma * ar1_avar_per_unit(n, tau0 / gm.tau_c_s);
      return sum;
    }
    case NoiseTerm::sinusoid: {
      if (!t.sinusoid) return 0;
      const double theta = 2 * kPi * t.sinusoid->frequency_hz * tau0;
      double amplitude = t.sinusoid->amplitude;
      if (s.interval_average) {
        const double x = kPi * t.sinusoid->frequency_hz * tau0;
        amplitude *= std::sin(x) / x;
      }
      const double s_half = std::sin(0.5 * theta);
      const double s_n = std::sin(0.5 * n * theta);
      if (s_half == 0) return 0;  // f a multiple of the sample rate: every sample is the same
      return amplitude * amplitude * std::pow(s_n, 4) / (n * n * s_half * s_half);
    }
  }
  return 0;
}

double sampled_avar(const NoiseTerms& t, std::int64_t m, const Sampling& s) {
  double total = 0;
  for (NoiseTerm term : kAllNoiseTerms) total += sampled_avar(t, term, m, s);
  return total;
}

double continuous_avar(const NoiseTerms& t, NoiseTerm term, double tau) {
  if (!(tau > 0) || !std::isfinite(tau))
    throw Error("tau must be > 0 s, got " + std::to_string(tau));
  switch (term) {
    case NoiseTerm::quantization:
      return t.quantization ? 3 * *t.quantization * *t.quantization / (tau * tau) : 0;
    case NoiseTerm::white: return t.white ? *t.white * *t.white / tau : 0;
    case NoiseTerm::bias_instability:
      return t.bias_instability ? std::pow(kFlickerFloorFactor * *t.bias_instability, 2) : 0;
    case NoiseTerm::rate_random_walk:
      return t.rate_random_walk ? *t.rate_random_walk * *t.rate_random_walk * tau / 3 : 0;
    case NoiseTerm::rate_ramp: return t.rate_ramp ? 0.5 * std::pow(*t.rate_ramp * tau, 2) : 0;
    case NoiseTerm::gauss_markov: {
      double sum = 0;  // independent processes: their AVARs add
      for (const GaussMarkov& gm : t.gauss_markov) sum += gauss_markov_continuous_avar(gm, tau);
      return sum;
    }
    case NoiseTerm::sinusoid: {
      if (!t.sinusoid) return 0;
      const double x = kPi * t.sinusoid->frequency_hz * tau;
      const double s = std::sin(x);
      return t.sinusoid->amplitude * t.sinusoid->amplitude * std::pow(s * s / x, 2);
    }
  }
  return 0;
}

double continuous_avar(const NoiseTerms& t, double tau) {
  double total = 0;
  for (NoiseTerm term : kAllNoiseTerms) total += continuous_avar(t, term, tau);
  return total;
}

double two_sided_psd(const NoiseTerms& t, NoiseTerm term, double f, double tau0_s) {
  if (!(f > 0) || !std::isfinite(f)) throw Error("frequency must be > 0 Hz");
  switch (term) {
    case NoiseTerm::quantization:
      if (!t.quantization) return 0;
      if (!(tau0_s > 0)) throw Error("the quantization PSD needs the sample interval tau0 > 0");
      return 4 * *t.quantization * *t.quantization / tau0_s * std::pow(std::sin(kPi * f * tau0_s), 2);
    case NoiseTerm::white: return t.white ? *t.white * *t.white : 0;
    case NoiseTerm::bias_instability:
      return t.bias_instability ? *t.bias_instability * *t.bias_instability / (2 * kPi * f) : 0;
    case NoiseTerm::rate_random_walk:
      return t.rate_random_walk ? std::pow(*t.rate_random_walk / (2 * kPi * f), 2) : 0;
    case NoiseTerm::gauss_markov: {
      double sum = 0;  // independent processes: their PSDs add
      for (const GaussMarkov& gm : t.gauss_markov)
        sum += 2 * gm.sigma * gm.sigma * gm.tau_c_s / (1 + std::pow(2 * kPi * f * gm.tau_c_s, 2));
      return sum;
    }
    case NoiseTerm::rate_ramp:
    case NoiseTerm::sinusoid: return 0;
  }
  return 0;
}

ReadOff read_off(NoiseTerm term) {
  switch (term) {
    case NoiseTerm::quantization: return {-1.0, std::sqrt(3.0), 1.0};
    case NoiseTerm::white: return {-0.5, 1.0, 1.0};
    case NoiseTerm::bias_instability: return {0.0, 1.0, kFlickerFloorFactor};
    case NoiseTerm::rate_random_walk: return {0.5, 3.0, 1.0};
    case NoiseTerm::rate_ramp: return {1.0, std::sqrt(2.0), 1.0};
    case NoiseTerm::gauss_markov:
    case NoiseTerm::sinusoid: break;
  }
  throw Error(std::string(to_string(term)) + " has no straight-line ADEV read-off rule");
}

double adev_line(NoiseTerm term, double value, double tau_s) {
  const ReadOff r = read_off(term);
  return r.coefficient * value * std::pow(tau_s / r.tau_read_s, r.slope);
}

Eigen::Matrix3d ErrorModel::error_matrix() const {
  Eigen::Matrix3d t = misalignment;
  t.diagonal() = scale_factor;
  return t;
}

Eigen::Vector3d ErrorModel::deterministic_output(const Eigen::Vector3d& truth,
                                                 double temperature_k) const {
  return (Eigen::Matrix3d::Identity() + error_matrix()) * truth + bias +
         temperature_coefficient * (temperature_k - reference_temperature_k);
}

void validate(const NoiseTerms& t, std::string_view what) {
  const auto positive = [&](const std::optional<double>& v, const char* name) {
    if (v && !(*v > 0 && std::isfinite(*v)))
      throw Error(std::string(what) + ": " + name + " must be finite and > 0, got " +
                  std::to_string(*v));
  };
  positive(t.quantization, "quantization Q");
  positive(t.white, "white noise N");
  positive(t.bias_instability, "bias instability B");
  positive(t.rate_random_walk, "rate random walk K");
  if (t.rate_ramp && !std::isfinite(*t.rate_ramp))
    throw Error(std::string(what) + ": rate ramp R must be finite");
  if (t.gauss_markov.size() > kMaxGaussMarkov)
    throw Error(std::string(what) + ": " + std::to_string(t.gauss_markov.size()) +
                " Gauss-Markov processes, at most " + std::to_string(kMaxGaussMarkov) +
                " are supported");
  for (const GaussMarkov& gm : t.gauss_markov) {
    positive(gm.sigma, "Gauss-Markov sigma");
    positive(gm.tau_c_s, "Gauss-Markov tau_c");
  }
  if (t.sinusoid) {
    positive(t.sinusoid->amplitude, "sinusoid amplitude");
    positive(t.sinusoid->frequency_hz, "sinusoid frequency");
    if (!std::isfinite(t.sinusoid->phase_rad))
      throw Error(std::string(what) + ": sinusoid phase must be finite");
  }
}

void ErrorModel::validate(std::string_view what) const {
  const std::string w(what);
  if (!scale_factor.allFinite() || !misalignment.allFinite() || !bias.allFinite() ||
      !temperature_coefficient.allFinite() || !std::isfinite(reference_temperature_k))
    throw Error(w + ": scale factors, misalignments, bias and temperature terms must be finite");
  if (misalignment.diagonal().cwiseAbs().maxCoeff() != 0)
    throw Error(w + ": the misalignment matrix has a non-zero diagonal (scale factors go in s_i)");
  const char* axes[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) sigmatau::validate(noise[i], w + "." + axes[i]);
}

}  // namespace sigmatau
