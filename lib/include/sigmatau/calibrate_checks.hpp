#pragma once
/// \file calibrate_checks.hpp
/// Plausibility checks of a calibration's input and result that catch a column read in the
/// wrong unit (the calibration itself works in SI and cannot know what the user meant), and the
/// notes a user must see beside the numbers (a temperature model that was dropped, a matrix
/// that was not estimated). Each check throws Error naming the unit the user gave and the
/// option that sets it; none can trip on a log in the right units (the bounds are stated below).

#include <numbers>
#include <string>
#include <vector>

#include "sigmatau/calibrate.hpp"
#include "sigmatau/calibrate_log.hpp"

namespace sigmatau {

/// Median over every sample of the accelerometer magnitude [m/s^2] (for increments, the
/// velocity increment's magnitude times `rate_hz`). One pass over the log in fixed memory: the
/// magnitudes are binned by log10 in steps of 1e-3 (a relative resolution of 0.23 %), enough to
/// tell a unit error (a factor of 3 or more) from a working sensor. 0 for an empty log.
double median_accel_magnitude(const CalibrationLog& log, double rate_hz, bool increments);

/// Largest factor [1] by which the median magnitude of all samples (median_accel_magnitude) may
/// differ from the gravity before the accelerometer unit is called wrong. A calibration log is
/// mostly static, so the median is gravity to the sensor's gain error (a few %); it stays within
/// a factor 2 unless the sensor is accelerated by more than 1 g during most of the log. Unit
/// mix-ups are factors of 3.28 (ft/s^2 vs m/s^2), 9.81 (g vs m/s^2), 100 (cm/s^2), 1000 (mg vs g).
inline constexpr double kMaxAccelMagnitudeFactor = 2.0;

/// Throws Error when `median_magnitude` [m/s^2] (as the columns were read with `unit_given`,
/// of SI factor `unit_factor`) is not within kMaxAccelMagnitudeFactor of `gravity` [m/s^2]: the
/// message names `unit_given`, --accel-unit and, when one fits within 20 %, the unit the columns
/// seem to be in. `path` prefixes the message. Rates only for the suggestion (`increments`:
/// the values are velocity increments, no unit is suggested).
void check_accel_unit(double median_magnitude, double gravity, const std::string& unit_given,
                      double unit_factor, bool increments, const std::string& path);

/// RMS misfit [rad] of the gyroscope's rotation fit (TriadCalibration::residual_rms: the
/// calibrated gravity direction carried across each rotation against the next interval's)
/// above which the gyroscope columns cannot be in the unit given. A working gyroscope in the
/// right unit tracks a hand rotation of 90-180 deg to its unmodelled errors: nonlinearity
/// (< 1 % of the angle), g-sensitivity (< 0.1 deg/s/g over the seconds of a rotation) and time
/// stamping give well under 2 deg (0.035 rad); simulated logs give 6e-5 to 3e-4 rad. A gyroscope
/// read in deg/s as rad/s (or in mdps, or a wrong sample rate) turns each rotation by a wrong
/// multiple of its angle and leaves 0.38-0.48 rad (measured on 12- and 18-position logs).
inline constexpr double kMaxGyroRotationMisfit = 0.1;
/// The misfit must also be far beyond the noise (chi^2/dof above this) to be called a unit error:
/// a gyroscope so noisy that 0.1 rad is within its noise is not refused. The wrong-unit logs above
/// gave 683-1.2e4.
inline constexpr double kMinGyroMisfitChi2PerDof = 10.0;

/// Throws Error when the gyroscope's rotation fit misses the rotations by more than
/// kMaxGyroRotationMisfit rms with chi^2/dof above kMinGyroMisfitChi2PerDof: the message names
/// `unit_given` and --gyro-unit (and the other causes: saturation, a wrong sample rate). Does
/// nothing without a gyroscope or when its matrix was not estimated.
void check_gyro_unit(const CalibrationResult& result, const std::string& unit_given,
                     const std::string& path);

/// Rotations tested by check_gyro_rotation_angles: those that turn the calibrated gravity
/// direction by at least this [rad] (30 deg: well above the direction error of an uncalibrated
/// accelerometer, a few deg for a bias of 60 mg).
inline constexpr double kMinTestedGravityTurn = 30.0 * std::numbers::pi / 180;
/// The angle a gyroscope integrates across a rotation (the path length, sum of |w - b| dt) is at
/// least the angle by which gravity turned in the sensor frame (any rotation that turns a vector
/// by an angle has at least that angle), up to the gain error (a few %); below this fraction [1]
/// of it the gyroscope reads too little: rad/s read as deg/s (1/57), a sample rate 2 or more
/// times too high, or a saturated gyroscope.
inline constexpr double kMinGyroPathRatio = 0.5;

/// Angle [rad] by which the raw gyroscope (G = I, the rests' mean rate removed), integrated
/// across a rotation, may miss carrying the calibrated gravity direction of one rest onto the
/// next. A working gyroscope misses by its gain and misalignment errors times the angle (a few
/// % of at most 180 deg: under 10 deg even for 5 % errors); degrees read as radians turn it 57
/// times too far, so the direction lands at random (more than 30 deg off with probability 0.93).
/// This test needs no fit: it also catches the logs whose gyroscope fit fails.
inline constexpr double kMaxRawGyroMisfit = 30.0 * std::numbers::pi / 180;

/// Throws Error when, of at least 3 rotations between consecutive static intervals that turn
/// gravity by kMinTestedGravityTurn or more, at least half have a gyroscope path length below
/// kMinGyroPathRatio times gravity's turn (too small a unit), or else at least half are missed
/// by more than kMaxRawGyroMisfit (a wrong unit either way): the message names `unit_given`
/// and --gyro-unit. One pass over the rotations' rows of `log` (the log `result` came from).
void check_gyro_rotation_angles(const CalibrationLog& log, double rate_hz, bool increments,
                                const CalibrationResult& result, const std::string& unit_given,
                                const std::string& path);

/// Plausible range of an IMU's temperature [K]: 150 K (-123 degC) is far below the coldest
/// rating of any IMU data sheet (-55 degC, 218 K), and a column in degC read as K gives at most
/// 125-150 "K" (the hottest ratings); 500 K (227 degC) is above the hottest (downhole parts,
/// 175-200 degC) and below a column in K read as degC (>= 490 K for a part above -55 degC).
inline constexpr double kMinImuTemperatureK = 150.0;
inline constexpr double kMaxImuTemperatureK = 500.0;

/// Median of the temperature column over every sample [K] (0 without one), to 0.1 K, in one pass
/// and fixed memory (a histogram over -1000 K to 2000 K). A glitch of a few samples cannot move it.
double median_temperature_k(const CalibrationLog& log);

/// Throws Error when `median_k` (median_temperature_k) is outside [kMinImuTemperatureK,
/// kMaxImuTemperatureK]: the message names `unit_given` and --temp-unit. Checked before the
/// calibration, whose temperature model would otherwise extrapolate the biases hundreds of K.
void check_temperature_unit(double median_k, const std::string& unit_given,
                            const std::string& path);

/// Throws Error when the static intervals' temperatures (result.temperature_min_k / max_k) leave
/// [kMinImuTemperatureK, kMaxImuTemperatureK]: the message names `unit_given` and --temp-unit.
/// Does nothing without a temperature column.
void check_temperature_unit(const CalibrationResult& result, const std::string& unit_given,
                            const std::string& path);

/// Mean temperature of the static intervals [K] (0 without temperature): the temperature at
/// which a bias without a temperature model holds.
double mean_interval_temperature_k(const CalibrationResult& result);

/// What a user must know beside the numbers, one sentence each (without a trailing period):
/// a triad whose matrix was not estimated, and a triad whose bias temperature model was dropped
/// although the log has a temperature column (too few static intervals, or a temperature span
/// under 1 K), saying at which temperature its bias then holds.
std::vector<std::string> calibration_notes(const CalibrationResult& result);

}  // namespace sigmatau
