#pragma once
/// \file calibrate.hpp
/// Multi-position calibration without a rate table (in the manner of imu_tk): the linear error
/// model y = (I + T) x + b(temperature) + v of noise_model.hpp measured from a log in which the
/// IMU rests in many orientations, with rotations in between.
///
/// Steps and conventions:
///  1. Static intervals: a sliding-window variance detector (detect_static_intervals). Each
///     interval gives the mean of every channel and the covariance of that mean.
///  2. Accelerometer: A = I + T and b from the gravity magnitude alone,
///     |A^-1 (a_k - b(T_k))| = g for every interval k, by Levenberg-Marquardt. Gravity cannot see a
///     common rotation of the triad (A and A Q give the same magnitudes for any rotation Q), so
///     only 6 of T's 9 terms plus the 3 biases are identifiable. Convention: A is lower
///     triangular, i.e. the reference ("accelerometer") frame has x along the x sensing axis and
///     y in the plane of the x and y sensing axes. The identifiable terms are s_x, s_y, s_z and
///     the cross-axis terms m_yx, m_zx, m_zy (the non-orthogonality of the sensing axes);
///     m_xy, m_xz, m_yz are 0 by this convention and reported as not identifiable. The
///     frame-free invariant A A^T (T's symmetric part to first order) is reported too.
///  3. Gyroscope: bias from the static intervals, jointly with the Earth rate w_0 in the frame of
///     the first interval: the attitude C_k of interval k relative to the first is known from
///     the integrated rotations, so interval k sees G C_k^T w_0 (with a latitude the vertical
///     part of w_0 is known and its horizontal part, 2 numbers, is estimated; without, all 3;
///     when that cannot be determined, the unknown part enters each interval's uncertainty as
///     independent noise); G = I + T_g (all 9 terms, in the accelerometer frame of step 2)
///     from the rotations between consecutive static intervals: the calibrated gyro, integrated
///     across each rotation, must carry the calibrated gravity direction of one interval onto
///     the next.
///  4. Temperature (when given): each bias is b0 + c1 (T - T0) [+ c2 (T - T0)^2]; per axis, the
///     quadratic term is kept only when it lowers the corrected Akaike information criterion
///     (AICc = chi^2 + 2p + 2p(p+1)/(n-p-1)).
/// Covariances: from the within-interval noise (white-noise variance of each mean, inflated by
/// a pooled batch-means factor when the noise is visibly correlated), propagated through the
/// fits (the gyroscope's includes the accelerometer fit's uncertainty), and scaled by
/// chi^2/dof when the fit's chi^2 exceeds its 99% quantile (an unmodelled error).
/// Compensation: x = A^-1 (y - b(T)).
/// Memory: the steps stream over the samples (calibrate_log.hpp gives the same calibration for a
/// log of any length in bounded memory); beyond the samples themselves they hold two 8 MiB
/// histograms, at most 2^21 window statistics per sensor, and the gyroscope's integration steps
/// up to CalibrationOptions::rotation_memory_bytes (beyond it, in a temporary file).
///
/// References: D. Tedaldi, A. Pretto, E. Menegatti, "A robust and easy to implement method for
/// IMU calibration without external equipments", ICRA 2014 (imu_tk); C. M. Hurvich, C.-L. Tsai,
/// Biometrika 76 (1989) 297 (AICc).

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "sigmatau/units.hpp"

namespace sigmatau {

// kStandardGravity (units.hpp, 9.80665 m/s^2) is the default magnitude when neither gravity nor
// latitude is given.

/// Samples to calibrate, in SI. Rates (rad/s, m/s^2) or, with `increments`, integrated values
/// per sample (rad, m/s).
struct CalibrationInput {
  double rate_hz = 0;                          ///< sample rate [Hz]
  std::array<std::vector<double>, 3> accel;    ///< ax, ay, az (required)
  std::array<std::vector<double>, 3> gyro;     ///< gx, gy, gz (empty: no gyroscope)
  std::vector<double> temperature_k;           ///< [K] (empty: no temperature)
  bool increments = false;
};

struct CalibrationOptions {
  double gravity = kStandardGravity;    ///< local gravity magnitude [m/s^2]
  std::optional<double> latitude_rad;   ///< for the Earth rate [rad]
  int min_orientations = 9;             ///< distinct gravity directions required
  double window_s = 0.5;                ///< detector window [s] (at least 5 samples)
  double min_interval_s = 2.0;          ///< shortest static interval kept [s]
  double confidence = 0.95;             ///< two-sided level of the reported intervals
  double reference_temperature_k = 298.15;  ///< T0 of the temperature model [K] (25 degC)
  /// Memory for the gyroscope's integration steps [bytes], 24 per sample between consecutive
  /// static intervals (64 MiB: 2.8 million, hours of rotation at 100 Hz); beyond it they are kept
  /// in a temporary file and read back at each evaluation of the fit (same results, slower).
  std::int64_t rotation_memory_bytes = std::int64_t{64} << 20;
};

/// One static interval [first, last] (sample indices, inclusive).
struct StaticInterval {
  std::int64_t first = 0;
  std::int64_t last = 0;
  double start_s = 0, end_s = 0;       ///< times of first and last sample [s] (index / rate)
  Eigen::Vector3d accel_mean = Eigen::Vector3d::Zero();   ///< [m/s^2]
  Eigen::Matrix3d accel_cov = Eigen::Matrix3d::Zero();    ///< covariance of the mean [(m/s^2)^2]
  Eigen::Vector3d gyro_mean = Eigen::Vector3d::Zero();    ///< [rad/s] (zero without gyro)
  Eigen::Matrix3d gyro_cov = Eigen::Matrix3d::Zero();     ///< [(rad/s)^2]
  Eigen::Matrix3d gyro_sample_cov = Eigen::Matrix3d::Zero();  ///< of one sample [(rad/s)^2]
  double temperature_k = 0;            ///< mean temperature [K] (0 without temperature)
};

/// What the detector did (its thresholds are reported so a user can judge them).
struct StaticDetection {
  std::vector<StaticInterval> intervals;
  std::int64_t window_samples = 0;
  double accel_floor = 0, accel_threshold = 0;  ///< window variance statistic [(m/s^2)^2]
  double gyro_floor = 0, gyro_threshold = 0;    ///< [(rad/s)^2] (0 without gyro)
  double noise_inflation = 1;  ///< pooled batch-means factor applied to every mean's covariance
  /// Quiet runs rejected because their batch means drift (slow motion, see the detector).
  int rejected_moving = 0;
  /// The limit they were held to: 10 times the median over the quiet runs of their mean ratio of
  /// batch-means variance to the white-noise prediction, that median taken as 1..100 (the drift
  /// of the sensor's bias over the batches of long dwells is not motion).
  double batch_ratio_limit = 10;
};

/// Finds the static intervals. Per sample, the statistic is the sum over the axes of the
/// variance in a centred window of `window_s` (accelerometer, and gyroscope when present); its
/// noise floor is the exact 25th percentile over the log (a calibration log is mostly static; it is
/// selected in bounded memory, by histogram passes over the values' bit patterns), and a
/// sample is static when the statistic is at most kStaticThresholdFactor times the floor for
/// both sensors. Runs of at least `min_interval_s` become intervals, unless on some axis their 10 batch
/// means vary more than batch_ratio_limit times what the within-run noise predicts (slow motion;
/// 10 times, or more where every run's bias drifts over long dwells). Throws Error on bad input
/// (rate not > 0, missing or unequal channels, non-finite values, log shorter than a window).
StaticDetection detect_static_intervals(const CalibrationInput& input,
                                        const CalibrationOptions& options);

/// Detector threshold over the noise floor. For static white noise the statistic is
/// sigma^2 chi^2_nu / nu with nu >= w - 1 (w window samples; nu = 3(w-1) for equal axes); its
/// 25th percentile is at least (1 - 0.674 sqrt(2/nu)) sigma^2 and a 6-sigma upper bound is
/// (1 + 6 sqrt(2/nu)) sigma^2: for w = 50 and one dominant axis (nu = 49) the ratio of the two is
/// 2.6 < 3, so a static window is flagged as moving with probability < 1e-9, while any real
/// rotation raises the statistic by many orders of magnitude.
inline constexpr double kStaticThresholdFactor = 3.0;

/// A parameter with its standard error and confidence interval.
struct CalibratedValue {
  double value = 0;
  double standard_error = 0;
  double ci_low = 0, ci_high = 0;
};

/// Temperature dependence of one axis's bias: b(T) = b0 + c1 (T - T0) + c2 (T - T0)^2.
struct BiasTemperatureAxis {
  int degree = 1;                ///< 1 or 2 (chosen by AICc)
  CalibratedValue linear;               ///< c1 [unit/K]
  std::optional<CalibratedValue> quadratic;  ///< c2 [unit/K^2]
  double aicc_linear = 0, aicc_quadratic = 0;
};

struct TriadCalibration {
  bool matrix_estimated = false;       ///< false: only the bias (see `note`)
  std::string note;                    ///< why the matrix is missing, or ""
  Eigen::Matrix3d matrix = Eigen::Matrix3d::Identity();  ///< A = I + T
  /// Standard errors of A's entries; NaN where the entry is fixed by the convention.
  Eigen::Matrix3d matrix_se = Eigen::Matrix3d::Zero();
  std::array<CalibratedValue, 3> bias;        ///< b0 at T0 (without temperature: at the log's) [SI]
  std::array<CalibratedValue, 3> scale_factor;          ///< s_i = A_ii - 1 [1]
  /// m_ij = A_ij (i != j) [1]; nullopt where not identifiable (and on the diagonal).
  std::array<std::array<std::optional<CalibratedValue>, 3>, 3> misalignment;
  Eigen::Matrix3d invariant = Eigen::Matrix3d::Identity();  ///< A A^T (frame-free)
  std::vector<std::string> parameter_names;  ///< order of `covariance`
  Eigen::MatrixXd covariance;          ///< of the fitted parameters [SI^2]
  std::optional<std::array<BiasTemperatureAxis, 3>> temperature;
  int static_intervals = 0;            ///< intervals used
  int rotations = 0;                   ///< rotations used (gyroscope)
  double residual_rms = 0;             ///< of the fit residuals [m/s^2 | rad] (unweighted)
  double chi2 = 0;
  int dof = 0;
  double covariance_scale = 1;         ///< chi^2/dof when it was applied, else 1
  /// Gyroscope: the Earth rate in the frame of the first static interval [rad/s], estimated with
  /// the bias (heading model, step 3); nullopt when the Earth rate's unknown part entered the
  /// bias uncertainty as independent noise per interval instead.
  std::optional<Eigen::Vector3d> earth_rate;
  Eigen::Matrix3d earth_rate_covariance = Eigen::Matrix3d::Zero();  ///< of earth_rate [(rad/s)^2]
};

struct CalibrationResult {
  StaticDetection detection;
  int orientations = 0;   ///< distinct gravity directions
  double gravity = kStandardGravity;   ///< [m/s^2]
  double confidence = 0.95;
  double reference_temperature_k = 298.15;
  bool has_temperature = false;
  double temperature_min_k = 0, temperature_max_k = 0;
  TriadCalibration accel;
  std::optional<TriadCalibration> gyro;
};

/// Runs the whole calibration. Throws Error, with the reason, on inputs that cannot determine
/// the model: too few static intervals or distinct orientations (naming the gravity directions
/// never visited), orientations all near one plane or cone, a log that is moving (no static
/// intervals, or a gravity-magnitude misfit far above the noise), an accelerometer whose
/// static magnitude is not near `gravity` (wrong unit), an ill-conditioned fit.
CalibrationResult calibrate(const CalibrationInput& input, const CalibrationOptions& options);

/// The result as JSON text in SI (the keys of issue 8 and those `check` reads): per triad
/// "matrix", "matrix_se", "bias", "bias_ci", "bias_se", "scale_factor_error"(_ci, _se),
/// "misalignment"(_ci, _se) with null where not identifiable, "invariant", "covariance",
/// "parameters", "static_intervals", "residual_rms", "unit", "convention", the data-sheet
/// quantities ("gain_error_percent", "cross_axis_percent", "bias_norm") and, with temperature,
/// "temperature" per axis; plus the detected intervals and the compensation formula.
std::string calibration_json(const CalibrationResult& result);

/// A human-readable table in data-sheet units (deg/s, mg, %, deg/s/degC, mg/degC).
std::string calibration_table(const CalibrationResult& result);

}  // namespace sigmatau
