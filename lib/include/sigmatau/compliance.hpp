#pragma once
/// \file compliance.hpp
/// Does a measured unit meet its data sheet? Each measured parameter with a matching data-sheet
/// value gets a verdict and margins:
///   pass      the upper confidence bound is within the limit,
///   marginal  the estimate is within the limit but its upper bound is not,
///   fail      the estimate exceeds the limit (shown as "fail (within uncertainty)" when the
///             interval's lower bound is still at or below the limit: not a significant failure
///             at that confidence, though it counts as a fail for `check`'s exit status),
///   not specified  the sheet prints no value for it.
/// A noise term the fit left out (not detected: the data gave only a one-sided upper bound) is
/// still checked, by its bound alone: pass when the bound is within the limit (the term is at
/// most that), else inconclusive (the log cannot decide; a longer one is needed). A bound alone
/// never fails.
/// The limit is the printed max, else the typical value (said so in the item: a typical value
/// is a population 1-sigma figure, not a guarantee; THEORY.md 8.3).
///
/// Conventions (the same as convert.hpp, so a sheet means one thing everywhere):
///  - measured N against a printed noise density ND: N is compared with ND (two-sided, default)
///    or ND / sqrt(2) (one-sided); against a printed ARW / VRW directly;
///  - measured B (flicker coefficient) against a printed in-run bias stability: the printed
///    value is the ADEV floor 0.664 B, so 0.664 B is compared with it;
///  - offsets, gain errors, cross-axis terms, non-orthogonality and temperature coefficients by
///    magnitude;
///  - a calibrated triad's misalignment / cross-axis sensitivity: only what is frame-independent
///    (triad_frames.hpp) is compared, the non-orthogonality delta_ij of each axis pair
///    (~ m_ij + m_ji). A printed "axis-to-axis" misalignment bounds delta_ij itself; any other
///    printed misalignment or cross-axis sensitivity c bounds each axis against the package, which
///    leaves a pair within 2c of 90 deg, so delta_ij is compared with 2c (the tilt against the
///    package needs a package reference and is not measured);
///  - the rotation from the accelerometer triad to the gyro triad is reported, never judged (no
///    data sheet field prints it).

#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sigmatau/convert.hpp"
#include "sigmatau/noise_model.hpp"
#include "sigmatau/spec.hpp"

namespace sigmatau {

/// What was measured, in SI (the units of noise_model.hpp; ratios for gain and cross-axis).
enum class MeasuredQuantity {
  white_noise,            ///< N [rad/s/sqrt(Hz) | m/s^2/sqrt(Hz)]
  bias_instability,       ///< B [rad/s | m/s^2]
  rate_random_walk,       ///< K [rad/s^2/sqrt(Hz) | m/s^3/sqrt(Hz)]
  bias,                   ///< turn-on bias / zero-rate offset b_i [rad/s | m/s^2]
  scale_factor_error,     ///< s_i [1]
  cross_axis,             ///< m_ij [1]
  bias_temperature_coefficient,  ///< db/dT [rad/s/K | m/s^2/K]
  /// 90 deg - angle between sensing axes i and j of one triad [rad] (axis "xy", "xz", "yz");
  /// frame-independent (triad_frames.hpp)
  non_orthogonality,
  /// rotation vector carrying the accelerometer triad's axes onto the gyro triad's, component
  /// along x, y or z of the accelerometer frame [rad] (sensor gyro); informational
  frame_rotation,
};
std::string_view to_string(MeasuredQuantity quantity);

/// True when the quantity is compared with its limit by magnitude (|b|, |s|, |m|, |delta|,
/// |db/dT|): its sign is real but not part of the verdict.
bool compared_by_magnitude(MeasuredQuantity quantity);

/// One measured value with its confidence interval (SI), or, for a noise term the fit did not
/// keep, only its one-sided upper bound.
struct MeasuredParameter {
  Sensor sensor = Sensor::gyro;
  MeasuredQuantity quantity = MeasuredQuantity::white_noise;
  std::string axis;  ///< "x", "y", "z", or "xy", "xz", ... for cross-axis terms
  double value = 0;    ///< estimate (SI); unused when !detected
  double ci_low = 0;   ///< lower confidence bound (SI); unused when !detected
  double ci_high = 0;  ///< upper confidence bound (SI); unused when !detected
  /// false: the fit left the term out (the data do not support it) and only `upper_bound` is
  /// known (fit.hpp, ParameterEstimate::in_model == false).
  bool detected = true;
  /// One-sided upper bound on the term when !detected (SI, the unit of `value`; NaN when the
  /// fit could not bound it).
  double upper_bound = 0;
  /// p value of the joint fit the term comes from (fit.hpp, ChannelFit::p_value); NaN when not
  /// known (a calibration, a slopes fit, an older file). Below kMisfitPValue the fit is
  /// rejected (no model describes the curve) and a verdict from it is marked so.
  double fit_p_value = std::numeric_limits<double>::quiet_NaN();
  /// true: the value is the curve's own read-out (IEEE 952: the minimum for B, the -1/2 line
  /// for N), standing in for a joint fit that was rejected or contradicted the curve
  /// (fit.hpp, NoiseFit::readings); fit_p_value is then NaN.
  bool from_curve_readings = false;
};

/// True when the term's fit was rejected: fit_p_value below fit.hpp's kMisfitPValue (1e-3), the
/// threshold at which analyze and fit warn that no model describes the curve.
bool fit_rejected(const MeasuredParameter& p);

/// pass / marginal / fail / not specified as in the file comment; inconclusive: the term was not
/// detected and its upper bound exceeds the limit.
enum class Verdict { pass, marginal, fail, inconclusive, not_specified };
std::string_view to_string(Verdict verdict);

/// The verdict on one measured parameter against one data-sheet field.
struct ComplianceItem {
  MeasuredParameter measured;
  Verdict verdict = Verdict::not_specified;
  std::string spec_field;       ///< data-sheet key compared with ("" when not specified)
  std::string limit_text;       ///< as printed, e.g. "±20 deg/s" or "0.015 deg/s/sqrt(Hz)"
  std::string limit_unit;       ///< the printed unit ("deg/s"), for showing values like the sheet
  bool limit_is_typical = false;
  double limit_si = 0;          ///< the limit in the units of `compared` (SI) actually used:
                                ///< the printed value times `limit_factor`
  double limit_factor = 1;      ///< limit_si / printed value (1/sqrt(2) for a one-sided noise
                                ///< density, 2 for a per-axis misalignment against a pair)
  std::string limit_factor_text;  ///< how the printed value was scaled ("/√2", "×2"), "" for 1
  double compared = 0;          ///< the measured estimate as compared (e.g. |b|, 0.664 B) [SI];
                                ///< NaN when the term was not detected
  double compared_upper = 0;    ///< its upper confidence bound as compared [SI] (not detected:
                                ///< the one-sided upper bound as compared, e.g. 0.664 B_upper)
  double compared_low = 0;      ///< its lower confidence bound as compared [SI] (0.664 B_low;
                                ///< for a magnitude, the smallest |x| in the interval, 0 when
                                ///< the interval holds 0); NaN when not detected
  double margin = 0;            ///< compared / limit (< 1 is within); NaN when not detected
  double margin_upper = 0;      ///< compared_upper / limit
  double margin_low = 0;        ///< compared_low / limit; NaN when not detected
  std::string rule;             ///< one line: how the two were put on the same footing
};

struct ComplianceOptions {
  DensityConvention convention = DensityConvention::two_sided;
};

/// Checks every parameter against `sheet`, undetected ones by their upper bound (pass or
/// inconclusive). Parameters of a sensor the sheet lacks, or with no matching field, come back
/// as not_specified.
std::vector<ComplianceItem> check_compliance(const std::vector<MeasuredParameter>& measured,
                                             const DataSheet& sheet,
                                             const ComplianceOptions& options = {});

/// True when the item failed but its lower bound is at or below the limit: the estimate is over,
/// the interval is not wholly over, so the failure is not significant at the intervals' level.
/// Still a fail (any_failed, `check`'s exit status 1).
bool fail_within_uncertainty(const ComplianceItem& item);

/// What qualifies a verdict, "" when nothing: "within uncertainty" (a fail whose lower bound is
/// within the limit), "fit rejected, p = 3e-07" (the fit behind it describes no curve) and
/// "curve read-out" (the value is the curve's own read-out, MeasuredParameter::
/// from_curve_readings), joined by "; ". `fit_p_value` NaN or at/above kMisfitPValue adds nothing.
std::string verdict_qualifiers(bool within_uncertainty, double fit_p_value,
                               bool from_curve_readings = false);

/// The verdict as tables show it: "fail", or "fail (within uncertainty; fit rejected, p = 0)".
std::string verdict_text(std::string_view verdict, bool within_uncertainty, double fit_p_value,
                         bool from_curve_readings = false);

/// Said where the verdicts are explained when a row is a curve read-out.
inline constexpr const char* kCurveReadingNote =
    "curve read-out: the joint fit of that channel was rejected or contradicted its own curve, "
    "so the value is read from the curve as IEEE 952 does (bias stability: the curve's minimum; "
    "N: the -1/2 line at 1 s; K: the +1/2 line at 3 s), and so are the filter files";

/// Said where the verdicts are explained, with kFitRejectedNote when a row is marked.
inline constexpr const char* kWithinUncertaintyNote =
    "fail (within uncertainty): the estimate exceeds the limit but the interval's lower bound "
    "does not, so the failure is not significant at this confidence (it still counts as a "
    "fail, and check still exits 1)";
inline constexpr const char* kFitRejectedNote =
    "fit rejected: no model of the noise terms describes that channel's curve (p below 0.001), "
    "so the value and its verdict are not to be trusted (see the warnings)";

/// True when any item failed (the `check` exit code 1).
bool any_failed(const std::vector<ComplianceItem>& items);

/// The number of items compared with the sheet (every verdict but not_specified). Zero means
/// the sheet prints none of the measured items: nothing was checked (`check` exits 2).
int items_checked(const std::vector<ComplianceItem>& items);

/// The overall verdict: "fail" when any item failed, else "marginal" when any is marginal, else
/// "inconclusive" when any is inconclusive, else "all pass" when something passed, else
/// "nothing to check".
std::string overall_verdict(const std::vector<ComplianceItem>& items);

/// A ratio (measured / limit, bound / limit) for people: 3 significant digits, 4 within 1 % of
/// 1, more when needed so that a ratio other than 1 never reads as "1"; trailing zeros kept
/// ("1.000", "0.500"); at or above 100 as a whole number; "n/a" when not finite.
/// Examples: 1.0013 -> "1.001", 0.5 -> "0.500", 0.99996 -> "0.99996".
std::string format_ratio(double ratio);

/// True when any checked item (verdict other than not_specified) was judged against a typical
/// value because the sheet prints no max.
bool any_typical_limit(const std::vector<ComplianceItem>& items);

/// Said once beside the verdict when any limit is a typical value (any_typical_limit): a typ is
/// the population's centre, not a bound.
inline constexpr const char* kTypicalLimitNote =
    "limits marked (typ) are typical values, not guaranteed maxima: a unit at its typical noise "
    "exceeds them about half the time";

/// Said where the verdict rule is explained: how strong a pass is at the intervals' two-sided
/// `confidence` (68.3 % by default); "" from 95 % up, where the advice is already followed.
std::string gate_confidence_note(double confidence);

/// The verdicts as JSON text (SI): {"spec":{"name","part","manufacturer"},"density_convention",
/// "verdict","failed","items":[{"sensor","quantity","axis","detected", then "value","ci_low",
/// "ci_high" when detected or "upper_bound" when not (as in a fit result), "verdict",
/// "fit_p_value" and "fit_rejected" when the fit's p value is known, "from_curve_readings" when
/// the value is a curve read-out, and when
/// specified "spec_field","limit_text","limit_unit","limit_is_typical","limit_si",
/// "compared_upper","margin_upper","limit_factor","rule", plus "compared","margin",
/// "compared_low","margin_low","within_uncertainty" when detected and
/// "limit_factor_text" when the printed value was scaled; "rule" also on
/// an unspecified item that explains itself, e.g. the informational frame_rotation}]}. "verdict" is one of "pass",
/// "marginal", "fail", "inconclusive", "not specified". Written by `check --format json` and into
/// analyze's results.json.
std::string compliance_json(const std::vector<ComplianceItem>& items, const DataSheet& sheet,
                            const ComplianceOptions& options);

/// Reads measured parameters from a sigmatau result file's JSON text: a `fit` result
/// ({"channels":[{"name","quantity","parameters":{"N":{...},"B":...,"K":...}}]}), a `calibrate`
/// result ({"accelerometer":{...},"gyroscope":{...}}), or an `analyze` results.json (which holds
/// both under "fit" and "calibration"). A fit term given only as "upper_bound" is read as not
/// detected (a null bound, written for NaN, as an unknown bound). A calibrate triad gives its
/// biases, scale factor errors and temperature coefficients, and from its "matrix" (A) with
/// "parameters" and "covariance" the non-orthogonality of its three axis pairs; with both triads,
/// also the accelerometer-to-gyro frame_rotation. Intervals use the result's "confidence"
/// (default 0.95). A fit channel's "p_value" (joint fits) becomes fit_p_value. The sensor is the
/// channel's "quantity" (angular_rate / specific_force) when given, else its name's
/// (classify_channel, channel_names.hpp: gx, gyro_x, wx, ax, acc_x, ...); the axis is the name's
/// trailing x/y/z. Throws Error
/// naming `file` on any other shape.
std::vector<MeasuredParameter> measured_parameters_from_json(std::string_view json_text,
                                                             const std::string& file);

}  // namespace sigmatau
