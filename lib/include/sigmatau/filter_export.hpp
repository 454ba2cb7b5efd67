#pragma once
/// \file filter_export.hpp
/// Writes converted noise (convert.hpp) in the parameter format of a filter project, in that
/// project's units and conventions (THEORY.md section 5, with the sources named there):
///
///  - kalibr (imu.yaml; Kalibr wiki "IMU Noise Model"): continuous densities,
///    *_noise_density = N [unit/sqrt(Hz)], *_random_walk = K [unit/s/sqrt(Hz)].
///  - openvins (kalibr_imu_chain.yaml, `imu0:`; docs/propagation-discrete.dox): the same
///    continuous densities as Kalibr; OpenVINS discretises sigma_d = sigma/sqrt(dt),
///    sigma_bd = sigma_b sqrt(dt) itself.
///  - vins-fusion (acc_n, gyr_n, acc_w, gyr_w; vins_estimator/src/factor/integration_base.h):
///    the midpoint propagation adds 0.5 dt on each of two white samples and dt on the bias
///    drive, so Var(dtheta) = 0.5 gyr_n^2 dt^2 and Var(db) = gyr_w^2 dt^2 per step. Matching the
///    continuous model (N^2 dt and K^2 dt) gives gyr_n = N sqrt(2 f_s), gyr_w = K sqrt(f_s),
///    with f_s the IMU rate.
///  - gtsam (PreintegrationParams / PreintegrationCombinedParams): continuous covariances,
///    gyroscopeCovariance = N^2 (times the correlation), biasOmegaCovariance = K^2; GTSAM
///    multiplies the measurement covariance by 1/dt and the bias covariance by dt itself.
///  - px4 (EKF2_GYR_NOISE, EKF2_ACC_NOISE, EKF2_GYR_B_NOISE, EKF2_ACC_B_NOISE;
///    src/modules/ekf2/EKF/covariance.cpp): EKF2 down-samples the IMU to its prediction
///    interval dt and adds (dt EKF2_GYR_NOISE)^2 per delta angle and (dt EKF2_GYR_B_NOISE)^2 per
///    step, so EKF2_GYR_NOISE = N / sqrt(dt) [rad/s], EKF2_GYR_B_NOISE = K / sqrt(dt) [rad/s^2]
///    (accelerometer likewise in m/s^2, m/s^3). dt is the whole number of IMU intervals nearest
///    to EKF2_PREDICT_US (default 10000 us), at least one (px4_prediction_interval).
///  - vins-fusion and openvins are read by OpenCV's cv::FileStorage, which refuses a YAML file
///    whose first line is not "%YAML:1.0" and, of two equal keys, keeps the first (checked with
///    OpenCV 4.6): both files start with that line, and the VINS-Fusion one says to replace
///    the four keys in the user's config rather than append them.
///  - json: the discrete covariances at f_s, SI (the shape; see export_json).
///
/// These formats have no Gauss-Markov bias; for --bias-model gm the random walk with the same
/// per-step variance is written, and a comment says so. Where axes differ, the formats with one
/// number per triad get the largest axis (a comment says so). Densities and sigmas already
/// carry the inflation factor.

#include <string>
#include <string_view>
#include <vector>

#include "sigmatau/convert.hpp"

namespace sigmatau {

enum class ExportFormat { kalibr, openvins, vins_fusion, gtsam, px4, json };

/// "kalibr" | "openvins" | "vins-fusion" | "gtsam" | "px4" | "json"; throws Error otherwise.
ExportFormat parse_export_format(std::string_view text);
std::string_view to_string(ExportFormat format);

/// Settings that the converted noise does not carry.
struct ExportOptions {
  std::string rostopic = "/imu0";  ///< kalibr / openvins topic name
  /// PX4 EKF2_PREDICT_US [s] (default 10000 us; THEORY.md 5.5): the prediction interval asked
  /// for, which EKF2 rounds to whole IMU intervals (px4_prediction_interval).
  double px4_predict_interval_s = 0.01;
};

/// PX4's documented range of EKF2_PREDICT_US [us] (src/modules/ekf2/module.yaml).
inline constexpr double kPx4PredictMinUs = 1000;
inline constexpr double kPx4PredictMaxUs = 20000;

/// The prediction interval EKF2 uses [s] for EKF2_PREDICT_US = `predict_interval_s` [s] and IMU
/// samples at `imu_rate_hz` [Hz] (the rate EKF2 receives, IMU_INTEG_RATE): the whole number of
/// IMU intervals nearest to it, at least one (ImuDownSampler::reset: max(roundf(target / dt), 1)
/// intervals). 8000 us at 200 Hz gives 0.010 s; 5000 us at 100 Hz 0.010 s. Throws Error when
/// EKF2_PREDICT_US is outside PX4's documented range or not a whole number of microseconds, or
/// the rate is not > 0.
double px4_prediction_interval(double predict_interval_s, double imu_rate_hz);

/// A value a filter format needs that the converted noise lacks.
struct MissingFilterValue {
  Sensor sensor = Sensor::gyro;
  /// false: the white noise N; true: the bias drive (a random walk K, or one made from a bias
  /// stability or a Gauss-Markov).
  bool bias = false;
  std::string key;  ///< the format's key or field, e.g. "accelerometer_random_walk"
};

/// The values `format`'s consumer needs that `noise` cannot fill: white noise and bias of both
/// sensors for Kalibr, OpenVINS, VINS-Fusion, GTSAM and PX4 (missing_key_consequence says what
/// each does without one); none for JSON, where a sensor not given is absent, never zero.
std::vector<MissingFilterValue> missing_filter_values(const DiscreteNoise& noise,
                                                      ExportFormat format);

/// The keys of missing_filter_values, in the same order.
std::vector<std::string> missing_filter_keys(const DiscreteNoise& noise, ExportFormat format);

/// The terms `missing` stands for, by sensor: "accelerometer white noise and bias, gyroscope
/// bias".
std::string missing_values_text(const std::vector<MissingFilterValue>& missing);

/// What `format`'s consumer does with a key it needs that is missing, one clause: Kalibr and
/// OpenVINS stop; VINS-Fusion reads 0 (OpenCV's value of a missing node) and its IMU factor
/// then inverts a singular covariance; PX4 keeps its own default, set for flight far above a
/// sensor's noise; GTSAM keeps an identity covariance. "" for JSON.
std::string_view missing_key_consequence(ExportFormat format);

/// The file text for `format`. A file that lacks values its consumer needs
/// (missing_filter_values) says so in a "# WARNING:" line at its top and a comment where each
/// key would be. Throws Error when nothing convertible is present (no triad), and for PX4 as
/// px4_prediction_interval.
std::string export_filter_config(const DiscreteNoise& noise, ExportFormat format,
                                 const ExportOptions& options = {});

}  // namespace sigmatau
