#pragma once
/// \file noise_model.hpp
/// The shared noise-model vocabulary: per-axis noise terms (SI, continuous time), the linear
/// error model of a sensor triad, and "theory in one place": for each term its exact
/// discrete-time Allan variance at tau = m tau0, its continuous (IEEE) Allan variance, its
/// two-sided PSD and its IEEE 952 read-off rule. The simulator, the fit, the plots and the tests
/// all call these functions.
///
/// Units (gyro | accelerometer):
///   Q quantization            rad            | m/s
///   N white (ARW | VRW)       rad/s/sqrt(Hz) | m/s^2/sqrt(Hz)
///   B bias instability        rad/s          | m/s^2
///   K rate random walk        rad/s^2/sqrt(Hz) | m/s^3/sqrt(Hz)
///   R rate ramp               rad/s^2        | m/s^3
///   Gauss-Markov sigma        rad/s          | m/s^2,  tau_c [s]
///   sinusoid amplitude        rad/s          | m/s^2,  frequency [Hz]
/// Two-sided PSDs are in (rate unit)^2/Hz, Allan variances in (rate unit)^2.
///
/// References:
///  - IEEE Std 952-1997 Annex C (PSD forms, read-off rules), as quoted in THEORY.md section 2.
///  - N. F. Zhang, "Allan variance of time series models for measurement data", Metrologia 45
///    (2008) 549 (exact AVAR of sampled white noise, random walk, drift and AR(1)).
///  - N. J. Kasdin, "Discrete simulation of colored noise and stochastic processes and 1/f^alpha
///    power law noise generation", Proc. IEEE 83(5), 1995 (fractional-integration flicker).
///  - Derivation and numerical check of the sampled flicker and sinusoid forms:
///    tools/noise_model_theory.py.

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sigmatau {

/// Which triad a model describes (fixes the units of every term, see the file comment).
enum class Sensor { gyro, accel };
std::string_view to_string(Sensor sensor);

/// First-order Gauss-Markov process: stationary standard deviation and correlation time.
struct GaussMarkov {
  double sigma = 0;    ///< stationary standard deviation [rad/s | m/s^2]
  double tau_c_s = 0;  ///< correlation time T_c [s]
  friend bool operator==(const GaussMarkov&, const GaussMarkov&) = default;
};

/// A sinusoidal disturbance A sin(2 pi f t + phase).
struct Sinusoid {
  double amplitude = 0;     ///< A [rad/s | m/s^2]
  double frequency_hz = 0;  ///< f [Hz]
  double phase_rad = 0;     ///< phase at t = 0 [rad] (does not enter the phase-averaged AVAR)
  friend bool operator==(const Sinusoid&, const Sinusoid&) = default;
};

/// At most this many Gauss-Markov processes per axis (GMWM practice: real MEMS bias behaviour is
/// often described by a sum of up to three first-order Gauss-Markov processes).
inline constexpr std::size_t kMaxGaussMarkov = 3;

/// The noise of one axis, SI, continuous time. A term that is absent (nullopt, or an empty
/// Gauss-Markov list) is absent everywhere: it is not simulated, not fitted, not exported and not
/// plotted.
struct NoiseTerms {
  std::optional<double> quantization;       ///< Q [rad | m/s]
  std::optional<double> white;              ///< N [rad/s/sqrt(Hz) | m/s^2/sqrt(Hz)]
  std::optional<double> bias_instability;   ///< B [rad/s | m/s^2] (flicker, ADEV floor 0.664 B)
  std::optional<double> rate_random_walk;   ///< K [rad/s^2/sqrt(Hz) | m/s^3/sqrt(Hz)]
  std::optional<double> rate_ramp;          ///< R [rad/s^2 | m/s^3]
  /// A sum of 0..kMaxGaussMarkov independent first-order Gauss-Markov processes {sigma, tau_c};
  /// the term's AVAR and PSD are the sums of the entries' (independent processes add).
  std::vector<GaussMarkov> gauss_markov;
  std::optional<Sinusoid> sinusoid;         ///< {amplitude, frequency}

  /// True when no term is present.
  bool empty() const;
  friend bool operator==(const NoiseTerms&, const NoiseTerms&) = default;
};

/// The terms, in a fixed order (also the order of the simulator's random streams).
enum class NoiseTerm {
  quantization,
  white,
  bias_instability,
  rate_random_walk,
  rate_ramp,
  gauss_markov,
  sinusoid,
};
inline constexpr std::array<NoiseTerm, 7> kAllNoiseTerms{
    NoiseTerm::quantization,     NoiseTerm::white,     NoiseTerm::bias_instability,
    NoiseTerm::rate_random_walk, NoiseTerm::rate_ramp, NoiseTerm::gauss_markov,
    NoiseTerm::sinusoid};
/// "quantization", "white", "bias_instability", ...
std::string_view to_string(NoiseTerm term);
/// Whether `terms` has `term` (Gauss-Markov: at least one entry).
bool has_term(const NoiseTerms& terms, NoiseTerm term);
/// The same terms with only `term` kept (for per-term curves; Gauss-Markov: every entry).
NoiseTerms only(const NoiseTerms& terms, NoiseTerm term);
/// The terms with only Gauss-Markov entry `index` kept (for one curve per entry). Throws Error if
/// index is out of range.
NoiseTerms only_gauss_markov(const NoiseTerms& terms, std::size_t index);

/// sqrt(2 ln 2 / pi) = 0.664282: ADEV floor of flicker (bias instability) per unit B
/// (IEEE 952; THEORY.md fact 4).
inline constexpr double kFlickerFloorFactor = 0.66428204938065;

/// How a simulated (sampled) log was made, for the exact discrete-time AVAR.
struct Sampling {
  double tau0_s = 0;  ///< sample interval [s]
  /// Taps L of the Kasdin flicker filter (0 = the untruncated filter). The simulator reports the
  /// value it used (Simulator::flicker_taps()).
  std::int64_t flicker_taps = 0;
  /// true: each sample is the mean of the signal over its interval (increment output), which
  /// changes only the sinusoid's term (amplitude times sinc(f tau0)); false: point samples.
  bool interval_average = false;
};

/// Exact expected overlapping AVAR of one term of a sampled (discrete-time) process, at
/// tau = m tau0, in (rate unit)^2. Absent term: 0. Per term (n = m, see THEORY.md section 2):
///  - quantization: 3 Q^2 / tau^2 (additive angle quantization, exact for every m);
///  - white: sigma^2/n with sigma = N / sqrt(tau0), i.e. N^2 / tau;
///  - flicker: B^2 * a_L(m), the exact AVAR per unit innovation variance of the Kasdin filter
///    h_k = h_{k-1}(k - 1/2)/k truncated to L taps (flicker_avar_per_unit);
///  - rate random walk: (2 n^2 + 1) w^2 / (6 n), w^2 = K^2 tau0 (Zhang 2008);
///  - rate ramp: (R tau)^2 / 2 (exact for a sampled ramp);
///  - Gauss-Markov: per entry an AR(1) with phi = exp(-tau0/T_c), innovation variance
///    q = sigma^2 (1 - phi^2):
///    q [n - 3 phi - n phi^2 + 4 phi^(n+1) - phi^(2n+1)] / [n^2 (1-phi)^2 (1-phi^2)] (Zhang 2008),
///    summed over the entries (independent processes);
///  - sinusoid (phase-averaged): A^2 sin^4(n theta/2) / (n^2 sin^2(theta/2)), theta = 2 pi f tau0.
/// Throws Error if m < 1 or tau0 is not > 0.
double sampled_avar(const NoiseTerms& terms, NoiseTerm term, std::int64_t m,
                    const Sampling& sampling);
/// Sum of sampled_avar over the terms present (the terms are independent, so AVARs add).
double sampled_avar(const NoiseTerms& terms, std::int64_t m, const Sampling& sampling);

/// Exact AVAR of the Kasdin flicker process per unit innovation variance (Q_d = 1) at averaging
/// factor m, for the fractional integrator (1 - z^-1)^(-1/2) truncated to `taps` taps (0:
/// untruncated). Computed as (1/2) sum_k c_k^2 with c = h * (box_m - box_m delayed by m) / m,
/// using the closed form cumulative sum sum_{j<=k} h_j = (2k+1) h_k. Untruncated limits: m=1
/// 2/pi, m=2 1.6/pi, m -> infinity 2 ln2 / pi (THEORY.md section 6 table).
double flicker_avar_per_unit(std::int64_t m, std::int64_t taps);

/// The averaging factors [m_low, m_high] over which the exact ADEV of the Kasdin flicker with
/// `taps` taps is flat: every octave step m -> 2m inside has |d log ADEV / d log tau| <= 0.05.
struct FlickerBand {
  std::int64_t m_low = 0;
  std::int64_t m_high = 0;
};
FlickerBand flicker_band(std::int64_t taps);

/// Continuous-time (IEEE 952) AVAR of one term at tau [s], in (rate unit)^2: 3Q^2/tau^2, N^2/tau,
/// (2 ln 2/pi) B^2, K^2 tau/3, R^2 tau^2/2, the GM formula
/// (2 sigma^2 T_c/tau)[1 - (T_c/2tau)(3 - 4 e^{-tau/T_c} + e^{-2 tau/T_c})], and the sinusoid
/// A^2 [sin^2(pi f tau)/(pi f tau)]^2 (Gauss-Markov summed over its entries). Absent term: 0.
/// Throws Error if tau is not > 0.
double continuous_avar(const NoiseTerms& terms, NoiseTerm term, double tau_s);
double continuous_avar(const NoiseTerms& terms, double tau_s);

/// Two-sided rate PSD S(f) of one term at f > 0 [Hz], in (rate unit)^2/Hz (THEORY.md section 2):
/// quantization (4 Q^2/tau0) sin^2(pi f tau0) (needs tau0, f < 1/(2 tau0)); white N^2;
/// flicker B^2 / (2 pi f); random walk (K / (2 pi f))^2; Gauss-Markov
/// 2 sigma^2 T_c / (1 + (2 pi f T_c)^2) summed over the entries. Ramp and sinusoid have no density (return 0; the
/// sinusoid is a pair of lines of power A^2/4 each at +-f0). Throws Error if f is not > 0.
double two_sided_psd(const NoiseTerms& terms, NoiseTerm term, double f_hz, double tau0_s);

/// IEEE 952 read-off rule: on a log-log ADEV plot the term is the straight line
/// adev(tau) = coefficient * value * (tau / tau_read)^slope, read at tau_read.
struct ReadOff {
  double slope = 0;        ///< ADEV slope
  double tau_read_s = 0;   ///< where the line is read [s]
  double coefficient = 1;  ///< line value at tau_read per unit parameter
};
/// Q: slope -1 at sqrt(3) s; N: -1/2 at 1 s; B: 0, coefficient 0.664 (read anywhere, 1 s here);
/// K: +1/2 at 3 s; R: +1 at sqrt(2) s. Gauss-Markov and sinusoid have no line: Error.
ReadOff read_off(NoiseTerm term);
/// The term's ADEV asymptote at tau [s] for parameter `value` (value in the term's unit).
double adev_line(NoiseTerm term, double value, double tau_s);

/// Linear error model of one triad: y = (I + T) x + b + c (temperature - T0) + v, with
/// T = diag(s) + M (M off-diagonal misalignment / cross-axis sensitivity), b a constant bias and
/// v, b(t) the per-axis noise terms.
struct ErrorModel {
  Eigen::Vector3d scale_factor = Eigen::Vector3d::Zero();  ///< s_i [1] (1e-3 = 1000 ppm)
  /// m_ij, i != j [1] (small-angle rad): axis i sees m_ij of axis j. The diagonal must be 0.
  Eigen::Matrix3d misalignment = Eigen::Matrix3d::Zero();
  Eigen::Vector3d bias = Eigen::Vector3d::Zero();  ///< b [rad/s | m/s^2]
  /// Bias temperature coefficient [rad/s/K | m/s^2/K].
  Eigen::Vector3d temperature_coefficient = Eigen::Vector3d::Zero();
  double reference_temperature_k = 298.15;  ///< T0 [K]
  std::array<NoiseTerms, 3> noise;          ///< per axis x, y, z

  /// T = diag(s) + M.
  Eigen::Matrix3d error_matrix() const;
  /// The noise-free output (I + T) x + b + c (temperature_k - T0) [rad/s | m/s^2].
  Eigen::Vector3d deterministic_output(const Eigen::Vector3d& truth, double temperature_k) const;
  /// Throws Error when a value is not finite, the misalignment diagonal is not 0 or a noise
  /// term is out of range (negative or zero magnitudes, tau_c or frequency not > 0). `what`
  /// names the model in the message ("gyro").
  void validate(std::string_view what) const;
};

/// Checks one axis's terms (magnitudes > 0 and finite, tau_c > 0, 0 < f, at most
/// kMaxGaussMarkov Gauss-Markov entries); throws Error naming `what` and the term.
void validate(const NoiseTerms& terms, std::string_view what);

/// Parses a model string as data sheets print it, e.g.
///   "N=0.15 deg/sqrt(h), B=3 deg/h, K=0.02 deg/h/sqrt(h)"
/// Keys: Q, N, B, K, R, GM=<sigma> @ <tau_c>, SIN=<amplitude> @ <frequency>; every value with its
/// unit (units.hpp), checked against the dimension the sensor's term needs. Returns SI.
/// GM may repeat up to kMaxGaussMarkov times ("GM=0.01 deg/s @ 100 s, GM=0.003 deg/s @ 2000 s":
/// a sum of Gauss-Markov processes, kept in the order written); every other key at most once.
/// Throws Error naming the key, the text and what was expected (unknown key, repeated key, a
/// fourth GM, missing '=', wrong dimension, value not > 0).
NoiseTerms parse_noise_terms(std::string_view text, Sensor sensor);

/// The terms as a model string in SI units (parse_noise_terms reads it back exactly).
std::string format_noise_terms(const NoiseTerms& terms, Sensor sensor);

}  // namespace sigmatau
