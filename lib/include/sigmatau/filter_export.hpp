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
///    interval dt = EKF2_PREDICT_US (default 10000 us) and adds (dt EKF2_GYR_NOISE)^2 per delta
///    angle and (dt EKF2_GYR_B_NOISE)^2 per step, so EKF2_GYR_NOISE = N / sqrt(dt) [rad/s],
///    EKF2_GYR_B_NOISE = K / sqrt(dt) [rad/s^2] (accelerometer likewise in m/s^2, m/s^3).
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
  /// PX4 EKF2 prediction interval dt [s] (EKF2_PREDICT_US default 10000 us; THEORY.md 5.5).
  double px4_predict_interval_s = 0.01;
};

/// The keys `format` requires that `noise` cannot fill (Kalibr, OpenVINS and VINS-Fusion
/// refuse a file without all four; PX4 keeps its defaults; GTSAM and JSON: none). The file
/// still says which, in a comment where each would be.
std::vector<std::string> missing_filter_keys(const DiscreteNoise& noise, ExportFormat format);

/// The file text for `format`. Throws Error when nothing convertible is present (no triad).
std::string export_filter_config(const DiscreteNoise& noise, ExportFormat format,
                                 const ExportOptions& options = {});

}  // namespace sigmatau
