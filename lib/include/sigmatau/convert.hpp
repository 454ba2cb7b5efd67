#pragma once
/// \file convert.hpp
/// Continuous-time noise terms (a data sheet, a fit or values typed on the command line) to the
/// discrete-time covariances a filter running at f_s = 1/T_s needs, with the arithmetic shown.
///
/// Rules (THEORY.md sections 3.1, 5.6, 5.7; fact numbers refer to section 0):
///  - Data-sheet noise density ND -> white-noise density N (fact 3, section 3.3): two-sided
///    convention (default, the Kalibr / Allan reading) N = ND; one-sided N = ND / sqrt(2).
///    A printed ARW / VRW is the Allan N itself and is used as is, in preference to ND.
///  - White noise per sample (fact 2; Kalibr wiki "IMU Noise Model"):
///    Q = N^2 f_s, sigma = N sqrt(f_s).
///  - Bias as a random walk:
///     from a rate random walk K: Q_bb = K^2 T_s (Kalibr sigma_bd = sigma_b sqrt(T_s));
///     from a data-sheet in-run bias stability B_ds read as the standard deviation the walk
///     reaches after T_ref (THEORY.md 5.7): K = B_ds / sqrt(T_ref), Q_bb = B_ds^2 T_s / T_ref.
///  - Bias as a first-order Gauss-Markov process (THEORY.md 5.6, fact 11):
///     phi = exp(-T_s/T_c), q = sigma^2 (1 - phi^2).
///     From a bias stability the GM is matched so that its ADEV peak (0.6174 sigma at
///     tau = 1.892 T_c) equals the ADEV floor 0.664 B at the tau of the ADEV minimum tau_min:
///     sigma = 0.664 B / 0.6174 = B_ds / 0.6174 and T_c = tau_min / 1.892. The match holds only
///     near tau_min (a GM has a hump, a flicker floor is flat).
///  - Inflation factor F (Kalibr: "x10 or more" for low-cost sensors; OpenVINS: "10-20 times"):
///    every density and standard deviation is multiplied by F, every variance by F^2.
///
/// Data-sheet in-run bias stability: ADI, Xsens and VectorNav print the minimum of the Allan
/// deviation, so B_ds is read as the ADEV floor 0.664 B (B the flicker coefficient of
/// NoiseTerms::bias_instability, kFlickerFloorFactor).

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sigmatau/noise_model.hpp"
#include "sigmatau/spec.hpp"

namespace sigmatau {

/// How a printed noise density ND is read (THEORY.md section 3.3).
enum class DensityConvention {
  two_sided,  ///< N = ND (Kalibr, Allan variance; the default)
  one_sided,  ///< N = ND / sqrt(2) (ND is the square root of a one-sided PSD)
};
std::string_view to_string(DensityConvention convention);
/// "two-sided" | "one-sided"; throws Error otherwise.
DensityConvention parse_density_convention(std::string_view text);
/// The white-noise density N (the Allan N) of a printed noise density ND read under
/// `convention`, in ND's unit (e.g. rad/s/sqrt(Hz)): ND two-sided, ND / sqrt(2) one-sided.
/// Not for a printed ARW / VRW, which is N itself.
inline double white_from_noise_density(double noise_density, DensityConvention convention) {
  return convention == DensityConvention::two_sided ? noise_density
                                                    : noise_density / std::sqrt(2.0);
}
/// How white_from_noise_density reads ND, for explanations: "read as N = ND (two-sided)" or
/// "read as one-sided: N = ND / sqrt(2)".
inline std::string_view noise_density_reading(DensityConvention convention) {
  return convention == DensityConvention::two_sided ? "read as N = ND (two-sided)"
                                                    : "read as one-sided: N = ND / sqrt(2)";
}

/// How the bias is modelled in the filter.
enum class BiasModel {
  random_walk,   ///< "rw"
  gauss_markov,  ///< "gm"
};
std::string_view to_string(BiasModel model);  ///< "rw" | "gm"
/// "rw" | "gm" (also "random-walk", "gauss-markov"); throws Error otherwise.
BiasModel parse_bias_model(std::string_view text);

/// ADEV peak of a first-order Gauss-Markov process per unit sigma, 0.6174 (THEORY.md fact 11,
/// section 2 table; [V] by PSD integration there).
inline constexpr double kGaussMarkovPeakFactor = 0.6174;
/// tau of that peak per unit T_c, 1.892 (THEORY.md fact 11).
inline constexpr double kGaussMarkovPeakTau = 1.892;
/// Default T_ref [s]: the time after which a data-sheet bias stability is reached (the seed's
/// 100 s, THEORY.md 5.7).
inline constexpr double kDefaultReferenceTime = 100.0;

/// One triad to convert: its per-axis continuous noise terms (SI) and where they came from.
struct TriadNoise {
  Sensor sensor = Sensor::gyro;
  /// Per axis x, y, z. Used: white (N), bias_instability (B, flicker), rate_random_walk (K),
  /// gauss_markov (a sum of entries: --bias-model gm carries the entry with the largest sigma,
  /// rw takes K^2 = sum 2 sigma_i^2/T_c_i; TriadDiscrete::gauss_markov_note). Other terms are
  /// ignored by the conversion (and named in the explanation).
  std::array<NoiseTerms, 3> axes;
  /// Correlation between the axes' white noises (unit diagonal); identity when not given.
  Eigen::Matrix3d white_correlation = Eigen::Matrix3d::Identity();
  /// Correlation between the axes' bias drives (unit diagonal); identity when not given.
  Eigen::Matrix3d bias_correlation = Eigen::Matrix3d::Identity();
  /// How N was obtained, for the explanation ("noise density 0.015 deg/s/sqrt(Hz) read as N
  /// (two-sided convention)"). Empty: "N".
  std::string white_origin;
  /// How B / K / GM were obtained, for the explanation. Empty: nothing added.
  std::string bias_origin;
  /// true: on some axis a fit's upper bound stands in for a bias term it did not detect.
  bool bias_from_upper_bound = false;
  /// Per axis x, y, z: B (bias_instability) / K (rate_random_walk) is a fit's upper bound
  /// standing in for a term it did not detect there. The conversion names, in
  /// TriadDiscrete::bias_origin, only the bounds of the term it uses.
  std::array<bool, 3> bias_instability_is_bound{};
  std::array<bool, 3> rate_random_walk_is_bound{};
  /// The fit kept neither B nor K on any axis: both are bounds on every axis.
  bool no_bias_term_detected = false;
  /// Confidence level of those upper bounds (one-sided, the fit's --ci), in (0, 1); 0: unknown.
  double bound_confidence = 0;
  /// Per axis: the tau of the ADEV minimum the fit measured [s] (fit JSON parameters.B.tau_min_s),
  /// the default tau_min of a Gauss-Markov bias made from B; nullopt where not measured.
  std::array<std::optional<double>, 3> adev_minimum_tau_s;
  /// A fit that kept B but K on no axis: the largest axis's upper bound on K, against which a
  /// K made from B by the rule of thumb is compared (it can be several times the bound).
  std::optional<double> rate_random_walk_bound;
};

/// The same terms on all three axes.
TriadNoise uniform_triad(Sensor sensor, const NoiseTerms& terms);

/// Puts terms typed by the user for `sensor` into `triads` (a data sheet's, a fit's, or none),
/// on every axis: a white noise N (`typed.white`) replaces the source's; a bias stability B or
/// a random walk K (`typed.bias_instability`, `typed.rate_random_walk`) replaces the source's
/// whole bias (B, K, Gauss-Markov, and any fit upper bound standing in for them), so the bias
/// written is the typed one. A sensor `triads` lacks is added. `white_origin` / `bias_origin`
/// say what was typed; the explanation adds what it replaced.
void replace_with_typed_terms(std::vector<TriadNoise>& triads, Sensor sensor,
                              const NoiseTerms& typed, const std::string& white_origin,
                              const std::string& bias_origin);

/// The noise terms of one data-sheet section (nominal values: typ, else max; SpecValue::nominal):
/// N from the printed ARW / VRW if any, else from the noise density under `convention`;
/// B = bias stability / 0.664 (the printed value read as the ADEV floor); K from the rate
/// random walk. Throws Error naming the sheet when the section is absent.
TriadNoise triad_from_data_sheet(const DataSheet& sheet, Sensor sensor,
                                 DensityConvention convention);

/// The triads of a noise-term fit result: the JSON of `sigmatau fit --format json` or the "fit"
/// section of `analyze`'s results.json ({"channels":[{"name","quantity","parameters":{"N":
/// {"value",..} | {"upper_bound",..}, "B": ..., "K": ...}}]}). Channels gx/gy/gz and ax/ay/az
/// (or quantity angular_rate / specific_force and a trailing x/y/z) give sensor and axis.
/// A filter models every axis alike, so a bias term (B or K) that the fit kept on some axes
/// only is given, on the others, the upper bound the fit found for it there (conservative),
/// and the explanation says so. Axes with no channel in the result (a single-axis test) get the
/// largest measured axis's terms. Throws Error naming `file` on another shape or a channel whose
/// axis cannot be told.
std::vector<TriadNoise> triads_from_fit_json(std::string_view json_text, const std::string& file);

/// A noise-term fit result read for the filter conversion: its triads and what every filter
/// file written from it must say about the fit it rests on.
struct FitForFilter {
  std::vector<TriadNoise> triads;  ///< as triads_from_fit_json
  /// One line each: channels whose joint fit was rejected by its goodness of fit (p_value below
  /// kMisfitPValue, fit.hpp) with p and the advice, and the data-plausibility check's unit
  /// warnings (analyze's results.json "unit_warnings").
  std::vector<std::string> warnings;
  /// One line each: which method's terms are used (joint, slopes; with both, which and why) and
  /// terms the fit kept that no filter file carries (rate ramp R, quantization Q), with values.
  std::vector<std::string> notes;
  /// The log's sample rate [Hz] when the result records it (results.json / fit JSON
  /// "input": {"rate_hz"}); nullopt otherwise.
  std::optional<double> log_rate_hz;
};

/// Reads a fit result as triads_from_fit_json does, with its warnings and notes. The level of
/// the bounds comes from the result's "confidence" (top level or "fit"), the Gauss-Markov
/// tau_min per axis from parameters.B.tau_min_s. Throws Error as triads_from_fit_json.
FitForFilter read_fit_for_filter(std::string_view json_text, const std::string& file);

/// The note for a filter rate above the log's sample rate (the white level is measured only up
/// to the log's Nyquist frequency, log_rate_hz / 2), or "" when filter_rate_hz <= log_rate_hz.
std::string rate_above_log_note(double filter_rate_hz, double log_rate_hz);

/// Conversion settings.
struct ConvertOptions {
  double rate_hz = 0;  ///< f_s [Hz], > 0
  BiasModel bias_model = BiasModel::random_walk;
  double t_ref_s = kDefaultReferenceTime;  ///< T_ref [s] for a bias stability as a random walk
  /// tau of the ADEV minimum [s] for a bias stability as a GM, on every axis; nullopt: each
  /// axis's TriadNoise::adev_minimum_tau_s (an axis without one takes the shortest measured on
  /// the others), else T_ref.
  std::optional<double> tau_min_s;
  double inflate = 1;  ///< F >= 1 is usual; must be > 0
  /// Recorded in the outputs (the conversion of ND to N happens when the TriadNoise is built).
  DensityConvention convention = DensityConvention::two_sided;
};

/// White measurement noise of one triad at f_s (after inflation).
struct WhiteDiscrete {
  Eigen::Vector3d density;              ///< N per axis [unit/sqrt(Hz)] (continuous, x F)
  Eigen::Vector3d variance_per_sample;  ///< N^2 f_s [unit^2]
  Eigen::Vector3d sigma_per_sample;     ///< N sqrt(f_s) [unit]
  Eigen::Matrix3d q;                    ///< S C S, S = diag(sigma), C = white_correlation
};

/// Where the bias model came from.
enum class BiasSource {
  rate_random_walk,  ///< K given
  bias_stability,    ///< B given (data-sheet in-run bias stability)
  gauss_markov,      ///< a GM {sigma, T_c} given (or a sum of them: see discretize)
};
std::string_view to_string(BiasSource source);

/// Bias process of one triad per filter step T_s (after inflation).
struct BiasDiscrete {
  BiasModel model = BiasModel::random_walk;
  BiasSource source = BiasSource::rate_random_walk;
  Eigen::Vector3d variance_per_step;  ///< Q_bb (rw) or q (gm) [unit^2]
  Eigen::Vector3d sigma_per_step;     ///< sqrt of it [unit]
  /// Random-walk density K [unit/s/sqrt(Hz)] with the same per-step variance:
  /// sqrt(variance_per_step f_s) (exact for rw; for gm the T_c -> infinity equivalent).
  Eigen::Vector3d random_walk_density;
  Eigen::Vector3d phi;      ///< gm: exp(-T_s/T_c); rw: 1
  Eigen::Vector3d tau_c_s;  ///< gm: T_c [s]; rw: 0
  Eigen::Vector3d sigma;    ///< gm: stationary sigma [unit]; rw: 0
  double t_ref_s = 0;       ///< T_ref used (source bias_stability, rw), else 0
  /// Per axis: tau_min [s] used (source bias_stability, gm), else 0.
  Eigen::Vector3d tau_min_s = Eigen::Vector3d::Zero();
  /// Where tau_min came from (source bias_stability, gm), for the files' headers, e.g.
  /// "given (convert --tau-min)"; "" otherwise.
  std::string tau_min_origin;
  Eigen::Matrix3d q;        ///< S C S, S = diag(sigma_per_step), C = bias_correlation
};

/// One converted triad.
struct TriadDiscrete {
  Sensor sensor = Sensor::gyro;
  /// Where the bias came from (TriadNoise::bias_origin), for the files' headers, with the axes
  /// where the term the bias is made from (K for a random walk from K, B otherwise) is a fit's
  /// upper bound, at its level ("K on axis y: not detected, its 95 % upper bound used").
  std::string bias_origin;
  /// true: the bias written rests on such a bound on some axis.
  bool bias_from_upper_bound = false;
  /// A rule-of-thumb K above the fit's own upper bound on K: says by how much ("" otherwise).
  std::string bias_note;
  /// When the bias comes from a sum of Gauss-Markov processes (more than one entry on some
  /// axis): how the sum was carried ("gm": only the entry with the largest sigma, named with
  /// the ones left out; "rw": K^2 summed over the entries). "" otherwise. convert_noise adds it
  /// to DiscreteNoise::notes (every file's header, JSON "notes").
  std::string gauss_markov_note;
  std::optional<WhiteDiscrete> white;
  std::optional<BiasDiscrete> bias;
};

/// The result for all triads.
struct DiscreteNoise {
  ConvertOptions options;
  std::optional<TriadDiscrete> gyro;
  std::optional<TriadDiscrete> accel;
  std::string source;   ///< what was converted ("data sheet specs/tdk_mpu6050.yaml", ...)
  std::string explain;  ///< every step with its numbers (for --explain)
  /// Said at the top of every file ("# WARNING: ...", JSON "warnings"): what makes the values
  /// untrustworthy (FitForFilter::warnings).
  std::vector<std::string> warnings;
  /// Said in every file's header ("# note: ...", JSON "notes"): FitForFilter::notes.
  std::vector<std::string> notes;
  /// rate_above_log_note for this rate, "" when none ("# note: ...", JSON "notes").
  std::string rate_note;
  const TriadDiscrete* triad(Sensor sensor) const;
};

/// Converts one triad. Throws Error on rate_hz, t_ref, tau_min or inflate not > 0, a
/// correlation matrix that is not symmetric with unit diagonal, or a GM bias model requested
/// from K alone (a GM needs sigma and T_c).
TriadDiscrete discretize(const TriadNoise& triad, const ConvertOptions& options);

/// Converts each triad (at most one gyro and one accel) and writes the explanation.
DiscreteNoise convert_noise(const std::vector<TriadNoise>& triads, const ConvertOptions& options,
                            std::string source);

/// convert_noise on a fit result's triads, carrying its warnings and notes into the result, and
/// the rate note when the fit records the log's rate and options.rate_hz is above it.
DiscreteNoise convert_fit(const FitForFilter& fit, const ConvertOptions& options,
                          std::string source);

/// The explanation of one triad's conversion: inputs in SI (and deg for gyros), each formula
/// with its numbers, the results.
std::string explain(const TriadNoise& triad, const TriadDiscrete& result,
                    const ConvertOptions& options);

}  // namespace sigmatau
