#pragma once
/// \file fit.hpp
/// Noise terms with uncertainties from an overlapping Allan variance curve: the IEEE 952 / 1293
/// slope read-outs, and a joint fit that models only what the data supports.
///
/// Joint fit (GMWM-style, Guerrier et al. 2013): the OAVAR at octave averaging factors is
/// modelled as the sum of the exact discrete-time AVAR of each term (noise_model.hpp,
/// sampled_avar), linear in theta = (Q^2, N^2, B^2, K^2, R^2) >= 0, and solved by non-negative
/// generalised least squares whose weight is the inverse of the exact covariance of the OAVAR
/// estimates across taus under the fitted model (oavar_covariance), iterated with the model.
/// Candidate subsets of terms are compared by BIC (one weight matrix, the largest model's); when
/// that finds B, K and R are decided again with each model's own weights by an approximate
/// likelihood of the curve (cube-root chi-squared marginals); a ramp has a 2 % prior and a
/// quantization a 10 % prior;
/// terms not kept are reported as one-sided upper bounds from the variance under the bound.
///
/// References:
///  - IEEE Std 952-1997 Annex C; IEEE Std 1293-1998 (read-off rules; THEORY.md section 2).
///  - S. Guerrier, J. Skaloud, Y. Stebler, M.-P. Victoria-Feser, "Wavelet-variance-based
///    estimation for composite stochastic processes", JASA 108 (2013) 1021 (GMWM).
///  - S. Guerrier, R. Molinari, Y. Stebler, "Theoretical limitations of Allan variance-based
///    regression for time series model estimation", IEEE SPL 23(5) (2016) 597.
///  - C. L. Lawson, R. J. Hanson, "Solving Least Squares Problems", 1974, ch. 23 (NNLS).
///  - G. Schwarz, "Estimating the dimension of a model", Ann. Stat. 6 (1978) 461 (BIC).
///  - E. B. Wilson, M. M. Hilferty, "The distribution of chi-square", PNAS 17 (1931) 684 (the
///    cube root of a chi-squared variable is nearly Gaussian: the selection's likelihood).
///  - S. G. Self, K.-Y. Liang, "Asymptotic properties of maximum likelihood estimators and
///    likelihood ratio tests under nonstandard conditions", JASA 82 (1987) 605 (a parameter on
///    its boundary: the chi-bar-squared 50:50 mixture behind the penalty).
///  - F. E. Satterthwaite, "An approximate distribution of estimates of variance components",
///    Biometrics Bull. 2 (1946) 110 (effective degrees of freedom of the intervals).

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sigmatau/allan_curve.hpp"
#include "sigmatau/noise_model.hpp"

namespace sigmatau {

/// The terms the fit can model (linear in their squared parameter): Q, N, B, K, R.
inline constexpr std::array<NoiseTerm, 5> kFitTerms{
    NoiseTerm::quantization, NoiseTerm::white, NoiseTerm::bias_instability,
    NoiseTerm::rate_random_walk, NoiseTerm::rate_ramp};

/// "Q", "N", "B", "K", "R", and "GM", "SIN" for the terms the joint fit adds (fit_added_terms).
std::string_view term_symbol(NoiseTerm term);
/// Parses "N,B,K" (symbols Q N B K R, case-sensitive, any order, no repeats) for --terms.
/// Throws Error naming the text and the bad item.
std::vector<NoiseTerm> parse_fit_terms(std::string_view text);

enum class FitMethod { joint, slopes, both };
/// "joint" | "slopes" | "both"; throws Error otherwise.
FitMethod parse_fit_method(std::string_view text);
std::string_view to_string(FitMethod method);

/// What the fit needs to know about the log the curve came from.
struct CurveSource {
  double tau0_s = 0;                ///< sample interval [s]
  std::int64_t n_phase_points = 0;  ///< N (rate samples + 1)
  /// Taps of the Kasdin flicker filter when the log is a sigmatau simulation (0: a real
  /// sensor, modelled by the untruncated 1/f process). Only the model mean uses it.
  std::int64_t flicker_taps = 0;
};

struct FitOptions {
  FitMethod method = FitMethod::joint;
  /// Forced model (--terms); empty: the model is selected among the subsets of `candidates`
  /// in the two stages described at the top of this file (BIC, then a curve likelihood for B,
  /// K and R, with priors on R and Q).
  std::vector<NoiseTerm> terms;
  /// Terms model selection may use (default all five of kFitTerms).
  std::vector<NoiseTerm> candidates{kFitTerms.begin(), kFitTerms.end()};
  double confidence_level = 0.95;  ///< two-sided level of the intervals, in (0, 1)
  /// Only points with tau in [tau_min_s, tau_max_s] are fitted (--tau-min / --tau-max): a
  /// sensor that filters its output departs from every noise term at the shortest taus.
  double tau_min_s = 0;
  double tau_max_s = std::numeric_limits<double>::infinity();
  /// When no model of the candidates describes the curve (p < 1e-3), whether the joint fit
  /// may add the terms real sensors add (up to three Gauss-Markov terms and a sinusoid), weight
  /// with a relative model error and leave out the shortest taus a sensor's filter bends
  /// (docs/fit.md, "Real sensors"). --ieee-terms-only turns it off.
  bool added_terms = true;
};

/// Family-wise two-sided level of the curve points' intervals the consistency guards use,
/// whatever the level of the reported intervals (analyze reports at 68.3 %: a 1-sigma interval
/// would call one point in three a contradiction on a fit that is right). Each of the K fitted
/// points is taken at 1 - (1 - kGuardLevel) / K (Bonferroni; guard_point_level): the curve's
/// minimum is the smallest of K scattered points, and at 95 % per point a right fit on a flat
/// floor of a few points was called contradicted one time in eight.
inline constexpr double kGuardLevel = 0.95;
/// The per-point level of the guards on a curve of `points` fitted points.
double guard_point_level(int points);

/// A reported quantity that the measured curve contradicts (docs/fit.md, "Consistency guards").
/// Terms add their Allan variances, so no term alone can lie above the curve, and a model can
/// not stay below the curve's smallest point; "beyond the point's interval" is beyond its
/// chi-squared interval (EDF of the curve point) at guard_point_level.
struct Contradiction {
  enum class Kind {
    /// B in the model: its flicker floor 0.664 B lies above the curve's smallest ADEV.
    floor_above_minimum,
    /// A kept term's own ADEV (exact sampled form) lies above the curve at a fitted tau.
    term_above_curve,
    /// B left out: the model with B at its upper bound stays below the curve's smallest ADEV,
    /// so the bound is below the floor the curve reaches.
    bound_below_minimum,
  };
  Kind kind = Kind::term_above_curve;
  NoiseTerm term = NoiseTerm::white;
  double tau_s = 0;        ///< where (the curve's minimum for the B checks; the worst tau)
  double reported = 0;     ///< the ADEV the fit puts there (0.664 B, the term's, the model's)
  double curve = 0;        ///< the curve's ADEV there
  double curve_limit = 0;  ///< the edge of its interval that is crossed (high, or low)
};
/// One sentence for people, values in the data-sheet unit of `sensor` (display_units.hpp).
std::string describe(const Contradiction& c, Sensor sensor);

/// One parameter of one channel, in SI (units: noise_model.hpp).
struct ParameterEstimate {
  NoiseTerm term = NoiseTerm::white;
  /// true: in the model, value and interval are set; false: not supported by the data, only
  /// `upper_bound` is set.
  bool in_model = false;
  double value = 0;
  double ci_low = 0;
  double ci_high = 0;
  /// One-sided upper bound at the confidence level (also set, = ci_high, for model terms).
  double upper_bound = 0;
  /// B only: tau of the fitted curve's smallest ADEV [s] (NaN for the other terms).
  double tau_min_s = std::numeric_limits<double>::quiet_NaN();
  /// B only: the curve's own ADEV at tau_min_s, in the rate unit (SI), not the model's floor
  /// 0.664 B: the two differ when the model misfits (NaN for the other terms).
  double adev_min = std::numeric_limits<double>::quiet_NaN();
  /// Effective degrees of freedom of the estimate (joint fit: Satterthwaite, 2 theta^2 /
  /// var(theta); slopes: sum of the EDFs of the points on the line). NaN when not applicable.
  double edf = std::numeric_limits<double>::quiet_NaN();
  /// Terms in the model only: the number of fitted taus at which this term carries the curve.
  /// Joint fit: points where its modelled AVAR exceeds the sum of the other kept terms'.
  /// Slopes: points on its slope line (B: 1, the minimum). 0 for a term not in the model
  /// (rise_without_floor reads B's).
  int leading_points = 0;
  /// B only, joint fit with added terms (Gauss-Markov, sinusoid): the bias stability is read
  /// from the model's ADEV floor (its smallest ADEV over the fitted taus / 0.664, what a data
  /// sheet quotes), so value and interval hold that reading, the flicker term alone no longer
  /// being the floor; in_model says whether a flicker term is in the model too, with its own
  /// coefficient in `flicker`.
  bool from_model_floor = false;
  /// B only, from_model_floor with a flicker term in the model: its coefficient [rate unit]
  /// (the model's B); NaN otherwise.
  double flicker = std::numeric_limits<double>::quiet_NaN();
  /// Curve read-outs only (NoiseFit::readings): the factor (<= 1) by which the read-out was
  /// lowered so that the term alone stays within the curve at every fitted tau (the -1/2 line
  /// fitted through a filtered or bending curve crosses it); 1 when it was not.
  double lowered_to_curve = 1;
};

/// One first-order Gauss-Markov term of a joint fit (fit_added_terms.cpp's search), SI.
struct GaussMarkovEstimate {
  double sigma = 0;    ///< stationary standard deviation [rad/s | m/s^2]
  double ci_low = 0;   ///< interval of sigma at the fit's level (T_c estimated too)
  double ci_high = 0;  ///< infinity when the curve does not bound sigma from above
  double tau_c_s = 0;  ///< correlation time [s] (searched on a grid and refined)
  /// Interval of T_c at the fit's level [s] (profile likelihood, searched from tau0 / 4 to the
  /// log's length): 0 (low) or infinity (high; JSON null) on a side the curve does not bound.
  double tau_c_ci_low_s = 0;
  double tau_c_ci_high_s = 0;
  /// Effective degrees of freedom of sigma^2 (Satterthwaite), NaN when not applicable.
  double edf = std::numeric_limits<double>::quiet_NaN();
  /// Fitted taus at which this term's AVAR exceeds the sum of the other terms'.
  int leading_points = 0;
};

/// A sinusoid of a joint fit (fit_added_terms.cpp's search), SI.
struct SinusoidEstimate {
  double amplitude = 0;     ///< A [rad/s | m/s^2]
  double ci_low = 0;        ///< interval of A at the fit's level (f estimated too)
  double ci_high = 0;
  double frequency_hz = 0;  ///< f [Hz] (searched on a grid and refined)
  double frequency_ci_low_hz = 0;   ///< interval of f at the fit's level [Hz] (log-normal)
  double frequency_ci_high_hz = 0;
  double edf = std::numeric_limits<double>::quiet_NaN();
  int leading_points = 0;   ///< fitted taus where its AVAR exceeds the other terms' sum
};

/// The result of one method on one channel.
struct ChannelFit {
  FitMethod method = FitMethod::joint;    ///< joint or slopes
  std::vector<NoiseTerm> model_terms;     ///< in kFitTerms order
  std::vector<ParameterEstimate> parameters;  ///< one per candidate term, kFitTerms order
  /// Joint fit only: the Gauss-Markov terms added because no model of the five IEEE terms
  /// described the curve (p below 1e-3), ascending T_c; empty otherwise.
  std::vector<GaussMarkovEstimate> gauss_markov;
  /// Joint fit only: a sinusoid added for the same reason (a narrow bump: a vibration).
  std::optional<SinusoidEstimate> sinusoid;
  /// Joint fit: generalised chi-squared of the final model and its BIC; iterations of the
  /// weight loop. Slopes: NaN, NaN, 0.
  double chi_squared = 0;
  double bic = 0;
  int iterations = 0;
  int points = 0;  ///< AVAR points used
  /// Joint fit: goodness of fit. dof = points - parameters (2 per Gauss-Markov term); p_value = P(chi2_dof > chi_squared)
  /// (near 0: no model of these terms describes the curve); misfit_tau_s the tau of the point
  /// furthest from the model in standard deviations (EDF-based). Slopes: 0, NaN, NaN.
  int dof = 0;
  double p_value = std::numeric_limits<double>::quiet_NaN();
  /// Joint fit rejected by its own covariance (p < 1e-3): the relative model error kappa of its
  /// weights, Sigma + kappa^2 diag(model AVAR^2), by maximum likelihood (docs/fit.md): the
  /// intervals include the scatter the model leaves. 0 when the fit was not rejected.
  double model_error = 0;
  /// Joint fit only: the shortest taus left out as bent by the sensor's own filter (fit_noise:
  /// the fit was rejected, departed most there, and described the rest better without them),
  /// ascending [s]; empty when none was.
  std::vector<double> left_out_taus_s;
  double misfit_tau_s = std::numeric_limits<double>::quiet_NaN();
  /// The furthest point is among the four shortest taus fitted: a sensor's own filtering (the
  /// fit bends toward the filtered points, so the furthest is among them or just after them).
  bool misfit_at_shortest_taus = false;

  /// What this fit reports that the measured curve contradicts (consistency guards, see
  /// Contradiction); empty when nothing does.
  std::vector<Contradiction> contradictions;

  /// The parameter of `term` (Error if absent from `parameters`).
  const ParameterEstimate& parameter(NoiseTerm term) const;
  /// The model as NoiseTerms (terms in the model only).
  NoiseTerms noise_terms() const;
};

struct NoiseFit {
  std::optional<ChannelFit> joint;
  std::optional<ChannelFit> slopes;
  /// The direct curve readings (the IEEE read-outs, as the slopes method: B from the curve's
  /// minimum, N from the -1/2 line at 1 s, ...) standing in for a joint fit that is rejected
  /// (p below kMisfitPValue) or contradicts its curve; nullopt when the joint fit is reported.
  std::optional<ChannelFit> readings;
  /// Why the readings stand in ("" when they do not): "rejected (p = 2e-12)" and/or
  /// "contradicted by the curve".
  std::string readings_reason;

  /// What a data sheet or a filter takes from this fit: the readings when they stand in, else
  /// the joint fit, else the slopes fit.
  const ChannelFit& reported() const;
};

/// Fits one channel's OADEV curve (statistic oadev; deviations in SI). Points with a
/// non-finite or non-positive deviation are ignored. Every fit is checked against the curve
/// (ChannelFit::contradictions, on the fitted taus); a joint fit that is rejected or
/// contradicted is kept but NoiseFit::readings stand in for it (reported()).
/// Throws Error when the statistic is not oadev, fewer than kMinFitPoints usable points
/// remain (or fewer than the forced model's terms + 1), the source is invalid (tau0 not > 0,
/// N < 3), a point's m does not match its tau, or the confidence level is not in (0, 1).
NoiseFit fit_noise(const AllanCurve& curve, const CurveSource& source, const FitOptions& options);

/// The model's OADEV at each point of `curve` (same order): the exact sampled deviation
/// (sampled_avar) of `fit`'s terms at the point's m, at the points the fit used (usable and
/// inside options' tau range); NaN at the others. What `model_dev` beside `dev` in the fit and
/// results JSON holds, so a reader sees where the model departs from the curve.
std::vector<double> model_deviation(const ChannelFit& fit, const AllanCurve& curve,
                                    const CurveSource& source, const FitOptions& options);

/// Throws Error unless 0 <= tau_min_s < tau_max_s (the --tau-min / --tau-max range of a fit).
void check_tau_range(double tau_min_s, double tau_max_s);

/// The p value below which a joint fit is reported as not describing its curve.
inline constexpr double kMisfitPValue = 1e-3;
/// A warning naming `channel` when the joint fit's p value is below kMisfitPValue, else "".
std::string misfit_warning(const ChannelFit& fit, const std::string& channel);

/// A warning naming `channel` when the joint fit left out its shortest taus as bent by the
/// sensor's own filter (ChannelFit::left_out_taus_s), else "".
std::string left_out_warning(const ChannelFit& fit, const std::string& channel);

/// A warning naming `channel` when the curve's read-outs stand in for the joint fit
/// (NoiseFit::readings): why, each contradiction (values in `sensor`'s data-sheet units), and
/// what is reported instead; "" otherwise.
std::string readings_warning(const NoiseFit& fit, const std::string& channel, Sensor sensor);

/// A rise (K or R) read from this many fitted taus or fewer is a short log's: see
/// rise_without_floor.
inline constexpr int kShortLogRisePoints = 3;
/// Whether a joint fit keeps K or R, carrying the curve at no more than kShortLogRisePoints taus,
/// while B carries it at none (B left out, or kept but below the other terms' sum everywhere):
/// the curve shows no flicker floor before its last few points rise, so the rise is not told
/// apart from B. bench/results_fit_short_logs.md (N = 0.2 deg/sqrt(h), B = 4 deg/h, K = 20
/// deg/h/sqrt(h), 200 Hz; 2 h MEMS gyro and consumer accelerometer): every K kept from a 5-minute
/// log is such a K; a K with a floor, or rising over 4 or more taus (the 2 h accelerometer, whose
/// floor hides between N and K), covers its truth about as its level says.
bool rise_without_floor(const ChannelFit& fit);
/// Measured on K flagged by rise_without_floor (bench/results_fit_short_logs.md, 200 seeds x 3
/// axes, seeds 1-200): the coverage of its nominal 95 % interval and its median value / truth,
/// on 5-minute logs (96 of 600 channels kept K, all flagged) and 30-minute logs (107 of 600; the
/// 117 that kept K with a floor covered in 99.1 %, median 1.13). Quoted by short_log_warning.
inline constexpr double kRiseWithoutFloorCoverage5min = 0.010;
inline constexpr double kRiseWithoutFloorRatio5min = 3.27;
inline constexpr double kRiseWithoutFloorCoverage30min = 0.589;
inline constexpr double kRiseWithoutFloorRatio30min = 1.51;
/// A warning naming `channel` when rise_without_floor(fit), else "".
std::string short_log_warning(const ChannelFit& fit, const std::string& channel);

/// Fewest usable AVAR points a fit accepts.
inline constexpr int kMinFitPoints = 4;

/// Exact covariance of the overlapping AVAR estimates at averaging factors `m` for a Gaussian
/// process with the given terms sampled at tau0 (N phase points), in (rate unit)^4:
/// Cov(s2_a, s2_b) = (1 / (4 n_a n_b)) sum_{k,l} [2 c_ab(l-k)^2 + 4 mu_a mu_b c_ab(l-k)],
/// c_ab the covariance of the second differences (closed form per term, summed over every lag
/// by quadrature), mu the ramp's mean difference, n = N - 2m. Q, N, B (untruncated 1/f), K, R,
/// Gauss-Markov are modelled; a sinusoid is ignored. Quantization is the one non-Gaussian term: its phase error is a
/// uniform rounding error, whose fourth cumulant (-1.2 Q^4) adds a term to the Q-Q part. Throws Error when an m is < 1 or N - 2m < 1.
Eigen::MatrixXd oavar_covariance(const NoiseTerms& terms, std::span<const std::int64_t> m,
                                 std::int64_t n_phase_points, double tau0_s);

/// Per-sensor summary of a triad's channels: mean and worst (largest) value of each parameter
/// over the channels that have it in their model.
struct TriadSummary {
  Sensor sensor = Sensor::gyro;
  std::vector<std::string> channels;
  struct Entry {
    NoiseTerm term;
    int channels_in_model = 0;
    double mean = 0;
    double worst = 0;
    std::string worst_channel;
  };
  std::vector<Entry> entries;  ///< kFitTerms order, terms in no channel's model left out
};
/// `fits[i]` belongs to channel `names[i]` of `sensors[i]`; one summary per sensor with >= 2
/// channels.
std::vector<TriadSummary> summarise_triads(const std::vector<std::string>& names,
                                           const std::vector<Sensor>& sensors,
                                           const std::vector<const ChannelFit*>& fits);

}  // namespace sigmatau
