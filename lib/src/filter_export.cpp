// Filter parameter files from converted noise (conventions and sources in filter_export.hpp).
//
// Glossary: N white-noise density [unit/sqrt(Hz)], K bias random-walk density [unit/s/sqrt(Hz)],
// f_s IMU rate [Hz], dt_ekf PX4 EKF2 prediction interval [s].
#include "sigmatau/filter_export.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "json_text.hpp"
#include "sigmatau/display_units.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau {
namespace {

/// Documented PX4 parameter ranges and defaults (src/modules/ekf2/module.yaml,
/// params_gyro_bias.yaml, params_accel_bias.yaml; THEORY.md 5.5): values outside the range are
/// written but flagged, since PX4 clamps or rejects them. The defaults are a conservative tune
/// on purpose, robust to the IMU errors of a vehicle in flight rather than accurate (PX4-ECL
/// pull request 36, "EKF Tuning Update"), so they sit well above a still sensor's own noise.
struct Px4Param {
  const char* name;
  double min, max;
  double default_value;
};
constexpr Px4Param kPx4GyrNoise{"EKF2_GYR_NOISE", 1e-4, 0.1, 0.015};
constexpr Px4Param kPx4AccNoise{"EKF2_ACC_NOISE", 0.01, 1.0, 0.35};
constexpr Px4Param kPx4GyrBNoise{"EKF2_GYR_B_NOISE", 0.0, 0.01, 0.001};
constexpr Px4Param kPx4AccBNoise{"EKF2_ACC_B_NOISE", 0.0, 0.01, 0.003};
/// An interval ratio this close to n + 1/2 is a tie: PX4 rounds the ratio of EKF2_PREDICT_US to
/// its measured (averaged) IMU interval, which a tie leaves to the last digits of that average.
constexpr double kPx4TieTolerance = 1e-6;
/// OpenCV's cv::FileStorage (VINS-Fusion, OpenVINS) refuses a YAML file whose first line is not
/// this ("Input file is invalid", OpenCV 4.6).
constexpr const char* kOpenCvYamlLine = "%YAML:1.0\n";

/// %.7g, with a decimal point before any exponent: YAML 1.1 readers (PyYAML's safe_load in
/// Kalibr) take "1e-05" for a string and only "1.0e-05" for a number.
std::string num(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.7g", v);
  std::string text = buffer;
  const auto e = text.find('e');
  if (e != std::string::npos && text.find('.') == std::string::npos) text.insert(e, ".0");
  return text;
}

bool uniform(const Eigen::Vector3d& v) { return v(0) == v(1) && v(1) == v(2); }

/// One number per triad: the largest axis (conservative), with a note when the axes differ.
double worst(const Eigen::Vector3d& v, std::string& notes, const std::string& what) {
  if (!uniform(v)) notes += "# " + what + ": axes differ, the largest axis is written\n";
  return v.maxCoeff();
}

/// "327.7 s" on every axis, or "327.7 s (x), 327.7 s (y), 163.8 s (z)".
std::string per_axis_seconds(const Eigen::Vector3d& v) {
  if (uniform(v)) return num(v(0)) + " s";
  return num(v(0)) + " s (x), " + num(v(1)) + " s (y), " + num(v(2)) + " s (z)";
}

/// The header's notes (DiscreteNoise::notes and rate_note), in order.
std::vector<std::string> notes_of(const DiscreteNoise& n) {
  std::vector<std::string> notes = n.notes;
  if (!n.rate_note.empty()) notes.push_back(n.rate_note);
  return notes;
}

/// "accelerometer_noise_density, gyroscope_random_walk"
std::string joined_keys(const std::vector<MissingFilterValue>& missing) {
  std::string keys;
  for (const auto& m : missing) keys += (keys.empty() ? "" : ", ") + m.key;
  return keys;
}

/// A file's header: `format_line` (what the file is for), what makes the values untrustworthy
/// (missing keys, a rejected fit, units), the source, the settings, the notes and where the bias
/// came from.
std::string header(const DiscreteNoise& n, const std::string& format_line, ExportFormat format) {
  std::ostringstream o;
  o << "# " << format_line << "\n";
  // First, before any number: what makes the values untrustworthy (a missing key, a rejected
  // fit, units).
  if (const auto missing = missing_filter_values(n, format); !missing.empty()) {
    o << "# WARNING: incomplete: " << joined_keys(missing) << " not in the input; "
      << missing_key_consequence(format) << ": add them before use\n";
  }
  for (const auto& w : n.warnings) o << "# WARNING: " << w << "\n";
  o << "# written by sigmatau from " << (n.source.empty() ? "given noise terms" : n.source)
    << "\n";
  o << "# IMU rate " << num(n.options.rate_hz) << " Hz; density convention "
    << to_string(n.options.convention) << "; inflation factor " << num(n.options.inflate)
    << "; bias model " << to_string(n.options.bias_model) << "\n";
  for (const auto& note : notes_of(n)) o << "# note: " << note << "\n";
  for (const auto* t : {n.gyro ? &*n.gyro : nullptr, n.accel ? &*n.accel : nullptr}) {
    // An upper bound standing in for a term the fit did not detect is not a measurement.
    if (t && t->bias && t->bias_from_upper_bound) {
      o << "# " << to_string(t->sensor) << " bias: " << t->bias_origin << "\n";
    }
    if (!t || !t->bias || t->bias->source != BiasSource::bias_stability) continue;
    const std::string sensor(to_string(t->sensor));
    if (t->bias->model == BiasModel::random_walk) {
      o << "# " << sensor << " bias random walk from the bias stability B by the rule of thumb "
        << "K = B_ds / sqrt(T_ref), B_ds the bias stability (ADEV floor 0.664 B), T_ref = " << num(t->bias->t_ref_s)
        << " s (convert --tref): not a measured K\n";
      if (!t->bias_note.empty()) o << "# " << sensor << " bias: " << t->bias_note << "\n";
    } else {
      o << "# " << sensor << " bias Gauss-Markov from the bias stability B, matched at the ADEV "
        << "minimum at tau = " << per_axis_seconds(t->bias->tau_min_s) << ": "
        << t->bias->tau_min_origin << "\n";
    }
  }
  return o.str();
}

/// Continuous densities per triad for the Kalibr-style formats; "" when absent.
struct Densities {
  bool white = false, bias = false;
  double n = 0, k = 0;
};

Densities densities(const TriadDiscrete* t, std::string& notes, const std::string& name) {
  Densities d;
  if (!t) return d;
  if (t->white) {
    d.white = true;
    d.n = worst(t->white->density, notes, name + " noise density");
  }
  if (t->bias) {
    d.bias = true;
    d.k = worst(t->bias->random_walk_density, notes, name + " random walk");
    if (t->bias->model == BiasModel::gauss_markov) {
      notes += "# " + name +
               " bias: Gauss-Markov has no counterpart here; the random walk with the same "
               "per-step variance is written\n";
    }
  }
  return d;
}

void require_any(const DiscreteNoise& n) {
  if (!n.gyro && !n.accel) throw Error("nothing to export: neither gyro nor accel noise given");
}

std::string kalibr_like(const DiscreteNoise& n, bool openvins, const ExportOptions& options) {
  std::string notes;
  const Densities g = densities(n.gyro ? &*n.gyro : nullptr, notes, "gyroscope");
  const Densities a = densities(n.accel ? &*n.accel : nullptr, notes, "accelerometer");
  std::ostringstream o;
  const std::string indent = openvins ? "  " : "";
  if (openvins) o << kOpenCvYamlLine;
  o << header(n,
              openvins ? "OpenVINS kalibr_imu_chain.yaml (continuous-time densities)"
                       : "Kalibr imu.yaml (continuous-time densities)",
              openvins ? ExportFormat::openvins : ExportFormat::kalibr);
  o << notes;
  auto line = [&](const char* key, bool present, double v, std::string_view unit) {
    if (present) {
      o << indent << key << ": " << num(v) << "  # [" << unit << "]\n";
    } else {
      o << indent << "# " << key << ": not given; " << (openvins ? "OpenVINS" : "Kalibr")
        << " needs it: add it before use\n";
    }
  };
  if (openvins) {
    o << "imu0:\n"
      << "  T_i_b:  # identity: IMU frame = body frame (replace with your calibration)\n"
      << "    - [1.0, 0.0, 0.0, 0.0]\n    - [0.0, 1.0, 0.0, 0.0]\n"
      << "    - [0.0, 0.0, 1.0, 0.0]\n    - [0.0, 0.0, 0.0, 1.0]\n";
  } else {
    o << "rostopic: " << options.rostopic << "\n";
    o << "update_rate: " << num(n.options.rate_hz) << "  # [Hz]\n";
  }
  // Kalibr's densities are the continuous-time N and K, in their SI units.
  line("accelerometer_noise_density", a.white, a.n, si_unit(NoiseTerm::white, Sensor::accel));
  line("accelerometer_random_walk", a.bias, a.k,
       si_unit(NoiseTerm::rate_random_walk, Sensor::accel));
  line("gyroscope_noise_density", g.white, g.n, si_unit(NoiseTerm::white, Sensor::gyro));
  line("gyroscope_random_walk", g.bias, g.k, si_unit(NoiseTerm::rate_random_walk, Sensor::gyro));
  if (openvins) {
    o << "  rostopic: " << options.rostopic << "\n";
    o << "  time_offset: 0.0\n";
    o << "  update_rate: " << num(n.options.rate_hz) << "  # [Hz]\n";
    // OpenVINS reads the IMU intrinsics from this block too and stops when one is missing
    // (ov_msckf VioManagerOptions.h); identities are "no intrinsic calibration".
    o << "  model: \"kalibr\"  # identity intrinsics below: replace with your calibration\n";
    const char* identity = "    - [1.0, 0.0, 0.0]\n    - [0.0, 1.0, 0.0]\n    - [0.0, 0.0, 1.0]\n";
    for (const char* key : {"Tw", "R_IMUtoGYRO", "Ta", "R_IMUtoACC"}) {
      o << "  " << key << ":\n" << identity;
    }
    o << "  Tg:\n    - [0.0, 0.0, 0.0]\n    - [0.0, 0.0, 0.0]\n    - [0.0, 0.0, 0.0]\n";
  }
  return o.str();
}

std::string vins(const DiscreteNoise& n) {
  std::string notes;
  const Densities g = densities(n.gyro ? &*n.gyro : nullptr, notes, "gyroscope");
  const Densities a = densities(n.accel ? &*n.accel : nullptr, notes, "accelerometer");
  const double fs = n.options.rate_hz;
  std::ostringstream o;
  // VINS-Fusion reads its config with cv::FileStorage: the YAML line first, or OpenCV refuses
  // the file; of two equal keys OpenCV keeps the first, so appended lines would change nothing.
  o << kOpenCvYamlLine;
  o << header(n,
              "VINS-Fusion / VINS-Mono IMU noise: replace the values of acc_n, gyr_n, acc_w and "
              "gyr_w in your config yaml with these",
              ExportFormat::vins_fusion);
  o << "# do not append these lines to the config: of two equal keys OpenCV keeps the first, so "
       "the old values would stay in force\n";
  o << "# midpoint propagation: Var(dtheta) = 0.5 gyr_n^2 dt^2, Var(db) = gyr_w^2 dt^2 per IMU "
       "step dt = 1/f_s,\n"
    << "# so gyr_n = N sqrt(2 f_s) and gyr_w = K sqrt(f_s) (accelerometer likewise)\n";
  o << notes;
  auto line = [&](const char* key, bool present, double v, const char* unit, const char* what) {
    if (present) {
      o << key << ": " << num(v) << "  # [" << unit << "] " << what << "\n";
    } else {
      o << "# " << key << ": not given; VINS-Fusion would read 0 (a singular IMU covariance): "
        << "add it before use\n";
    }
  };
  line("acc_n", a.white, a.n * std::sqrt(2 * fs), "m/s^2", "accelerometer measurement noise");
  line("gyr_n", g.white, g.n * std::sqrt(2 * fs), "rad/s", "gyroscope measurement noise");
  line("acc_w", a.bias, a.k * std::sqrt(fs), "m/s^3", "accelerometer bias random walk");
  line("gyr_w", g.bias, g.k * std::sqrt(fs), "rad/s^2", "gyroscope bias random walk");
  return o.str();
}

std::string gtsam(const DiscreteNoise& n) {
  std::ostringstream o;
  const double fs = n.options.rate_hz;
  o << header(n,
              "GTSAM PreintegrationParams / PreintegrationCombinedParams (continuous-time "
              "covariances)",
              ExportFormat::gtsam);
  o << "# GTSAM reads no file: copy each matrix into its setter, e.g. "
       "params->setGyroscopeCovariance(...), setAccelerometerCovariance, setBiasOmegaCovariance, "
       "setBiasAccCovariance\n"
       "# GTSAM multiplies the measurement covariances by 1/dt and the bias covariances by dt "
       "itself\n"
       "# a plain ImuFactor with a BetweenFactor on the bias needs the discrete K^2 x (time "
       "between its keys) instead\n";
  auto matrix = [&](const char* key, const Eigen::Matrix3d* m, const char* unit,
                    const char* what) {
    if (!m) {
      o << "# " << key << ": not given; GTSAM would keep its identity default\n";
      return;
    }
    o << key << ":  # [" << unit << "] " << what << "\n";
    for (int i = 0; i < 3; ++i) {
      o << "  - [" << num((*m)(i, 0)) << ", " << num((*m)(i, 1)) << ", " << num((*m)(i, 2))
        << "]\n";
    }
  };
  // Continuous covariances from the discrete ones: white Q_d = Q_c f_s, bias Q_d = Q_c / f_s.
  std::optional<Eigen::Matrix3d> gw, aw, gb, ab;
  std::string notes;
  if (n.gyro && n.gyro->white) gw = n.gyro->white->q / fs;
  if (n.accel && n.accel->white) aw = n.accel->white->q / fs;
  if (n.gyro && n.gyro->bias) gb = n.gyro->bias->q * fs;
  if (n.accel && n.accel->bias) ab = n.accel->bias->q * fs;
  for (const auto* t : {n.gyro ? &*n.gyro : nullptr, n.accel ? &*n.accel : nullptr}) {
    if (t && t->bias && t->bias->model == BiasModel::gauss_markov) {
      notes += "# " + std::string(to_string(t->sensor)) +
               " bias: Gauss-Markov has no counterpart here; the random walk with the same "
               "per-step variance is written\n";
    }
  }
  o << notes;
  matrix("gyroscopeCovariance", gw ? &*gw : nullptr, "(rad/s)^2/Hz", "N^2 (white noise)");
  matrix("accelerometerCovariance", aw ? &*aw : nullptr, "(m/s^2)^2/Hz", "N^2 (white noise)");
  matrix("biasOmegaCovariance", gb ? &*gb : nullptr, "(rad/s^2)^2/Hz",
         "K^2 (gyro bias random walk, CombinedImuFactor)");
  matrix("biasAccCovariance", ab ? &*ab : nullptr, "(m/s^3)^2/Hz",
         "K^2 (accelerometer bias random walk, CombinedImuFactor)");
  o << "# integrationCovariance is not a property of the IMU: choose it for your integration "
       "error\n";
  return o.str();
}

std::string px4(const DiscreteNoise& n, const ExportOptions& options) {
  const double fs = n.options.rate_hz;
  const double dt = px4_prediction_interval(options.px4_predict_interval_s, fs);
  const double requested_us = std::round(options.px4_predict_interval_s * 1e6);
  const double intervals = std::round(dt * fs);
  std::string notes;
  const Densities g = densities(n.gyro ? &*n.gyro : nullptr, notes, "gyroscope");
  const Densities a = densities(n.accel ? &*n.accel : nullptr, notes, "accelerometer");
  std::ostringstream o;
  o << header(n, "PX4 EKF2 IMU noise parameters (nsh / startup script)", ExportFormat::px4);
  o << "# EKF2 predicts every whole number of IMU intervals nearest to EKF2_PREDICT_US, at least "
       "one (ImuDownSampler): EKF2_PREDICT_US = "
    << num(requested_us) << " us at " << num(fs) << " Hz gives " << num(intervals)
    << (intervals == 1 ? " interval" : " intervals") << ", dt = " << num(dt) << " s\n"
    << "# (the IMU rate is the rate EKF2 receives, IMU_INTEG_RATE, not the sensor's output "
       "rate)\n";
  const double ratio = options.px4_predict_interval_s * fs;
  if (std::abs(ratio - std::floor(ratio) - 0.5) < kPx4TieTolerance) {
    o << "# note: EKF2_PREDICT_US is halfway between " << num(std::floor(ratio)) << " and "
      << num(std::floor(ratio) + 1)
      << " IMU intervals: PX4's choice then depends on the IMU interval it measures; set it "
         "to a whole number of intervals\n";
  }
  o << "# EKF2 adds (dt x NOISE)^2 per step: NOISE = N / sqrt(dt), B_NOISE = K / sqrt(dt)\n";
  o << notes;
  const double root = std::sqrt(dt);
  struct Line {
    const Px4Param& param;
    bool present;
    double value;
    const char* unit;
  };
  const Line lines[] = {{kPx4GyrNoise, g.white, g.n / root, "rad/s"},
                        {kPx4AccNoise, a.white, a.n / root, "m/s^2"},
                        {kPx4GyrBNoise, g.bias, g.k / root, "rad/s^2"},
                        {kPx4AccBNoise, a.bias, a.k / root, "m/s^3"}};
  // PX4's defaults against these values: how far a bench measurement is from a flight tune.
  std::string ratios;
  for (const Line& l : lines) {
    if (!l.present || !(l.value > 0)) continue;
    char text[96];
    std::snprintf(text, sizeof text, "%s %s %.3gx", ratios.empty() ? "" : ",", l.param.name,
                  l.param.default_value / l.value);
    ratios += text;
  }
  if (!ratios.empty()) {
    o << "# PX4's defaults are this many times the values below:" << ratios
      << ". They are set high on purpose, for the vibration and other errors of a vehicle in "
         "flight that a still log does not show; these values are the sensor's own noise, "
         "times the inflation factor "
      << num(n.options.inflate)
      << ": raise the factor for flight, or EKF2 will trust the IMU too much\n";
  }
  for (const Line& l : lines) {
    if (!l.present) {
      o << "# " << l.param.name << ": not given; PX4 would keep its default "
        << num(l.param.default_value) << "\n";
      continue;
    }
    o << "param set " << l.param.name << " " << num(l.value) << "  # [" << l.unit << "]";
    if (!(l.value >= l.param.min && l.value <= l.param.max)) {
      o << " outside the documented range " << num(l.param.min) << " .. " << num(l.param.max);
    }
    o << "\n";
  }
  return o.str();
}

nlohmann::json vector_or_scalar(const Eigen::Vector3d& v) {
  if (uniform(v)) return v(0);
  return nlohmann::json::array({v(0), v(1), v(2)});
}

nlohmann::json matrix_json(const Eigen::Matrix3d& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (int i = 0; i < 3; ++i) rows.push_back({m(i, 0), m(i, 1), m(i, 2)});
  return rows;
}

std::string json(const DiscreteNoise& n) {
  nlohmann::json doc;
  doc["rate_hz"] = n.options.rate_hz;
  doc["density_convention"] = std::string(to_string(n.options.convention));
  doc["inflate"] = n.options.inflate;
  doc["source"] = n.source;
  // The text formats' header comments: a rejected fit, implausible units, the method, terms
  // left out, a rate above the log's.
  if (!n.warnings.empty()) doc["warnings"] = n.warnings;
  if (const auto notes = notes_of(n); !notes.empty()) doc["notes"] = notes;
  for (const auto* t : {n.gyro ? &*n.gyro : nullptr, n.accel ? &*n.accel : nullptr}) {
    if (!t) continue;
    // One unit per field: the sample's unit, its square, and the densities N and K in their SI
    // units (si_unit).
    const std::string unit = t->sensor == Sensor::gyro ? "rad/s" : "m/s^2";
    const std::string squared = "(" + unit + ")^2";
    const std::string white_unit(si_unit(NoiseTerm::white, t->sensor));
    const std::string walk_unit(si_unit(NoiseTerm::rate_random_walk, t->sensor));
    nlohmann::json sensor = nlohmann::json::object();
    if (t->white) {
      const auto& w = *t->white;
      sensor["white_noise"] = {{"density", vector_or_scalar(w.density)},
                               {"variance_per_sample", vector_or_scalar(w.variance_per_sample)},
                               {"sigma_per_sample", vector_or_scalar(w.sigma_per_sample)},
                               {"Q", matrix_json(w.q)},
                               {"units", {{"density", white_unit},
                                          {"variance_per_sample", squared},
                                          {"sigma_per_sample", unit},
                                          {"Q", squared}}}};
    }
    if (t->bias) {
      const auto& b = *t->bias;
      nlohmann::json bias = {{"model", std::string(to_string(b.model))},
                             {"source", std::string(to_string(b.source))},
                             {"variance_per_step", vector_or_scalar(b.variance_per_step)},
                             {"sigma_per_step", vector_or_scalar(b.sigma_per_step)},
                             {"random_walk_density", vector_or_scalar(b.random_walk_density)},
                             {"Q", matrix_json(b.q)},
                             {"units", {{"variance_per_step", squared},
                                        {"sigma_per_step", unit},
                                        {"random_walk_density", walk_unit},
                                        {"Q", squared}}}};
      if (t->bias_from_upper_bound) bias["origin"] = t->bias_origin;
      if (b.model == BiasModel::random_walk) {
        if (b.source == BiasSource::bias_stability) bias["t_ref_s"] = b.t_ref_s;
      } else {
        bias["phi"] = vector_or_scalar(b.phi);
        bias["tau_c_s"] = vector_or_scalar(b.tau_c_s);
        bias["sigma"] = vector_or_scalar(b.sigma);
        bias["units"]["sigma"] = unit;
        bias["units"]["tau_c_s"] = "s";
        if (b.source == BiasSource::bias_stability) {
          bias["tau_min_s"] = vector_or_scalar(b.tau_min_s);
          bias["tau_min_origin"] = b.tau_min_origin;
        }
      }
      sensor["bias"] = bias;
    }
    doc[std::string(to_string(t->sensor))] = sensor;
  }
  return detail::json_text(doc, 2) + "\n";
}

}  // namespace

ExportFormat parse_export_format(std::string_view text) {
  if (text == "kalibr") return ExportFormat::kalibr;
  if (text == "openvins") return ExportFormat::openvins;
  if (text == "vins-fusion" || text == "vins") return ExportFormat::vins_fusion;
  if (text == "gtsam") return ExportFormat::gtsam;
  if (text == "px4") return ExportFormat::px4;
  if (text == "json") return ExportFormat::json;
  throw Error("export format: found \"" + std::string(text) +
              "\", expected kalibr, openvins, vins-fusion, gtsam, px4 or json");
}

std::string_view to_string(ExportFormat format) {
  switch (format) {
    case ExportFormat::kalibr: return "kalibr";
    case ExportFormat::openvins: return "openvins";
    case ExportFormat::vins_fusion: return "vins-fusion";
    case ExportFormat::gtsam: return "gtsam";
    case ExportFormat::px4: return "px4";
    case ExportFormat::json: return "json";
  }
  return "?";
}

double px4_prediction_interval(double predict_interval_s, double imu_rate_hz) {
  if (!(imu_rate_hz > 0) || !std::isfinite(imu_rate_hz)) {
    throw Error("PX4 export: IMU rate must be > 0 Hz, found " + num(imu_rate_hz));
  }
  const double us = predict_interval_s * 1e6;
  if (!(us >= kPx4PredictMinUs && us <= kPx4PredictMaxUs)) {
    throw Error("PX4 prediction interval EKF2_PREDICT_US: found " + num(us) + " us, expected " +
                num(kPx4PredictMinUs) + " to " + num(kPx4PredictMaxUs) +
                " us (PX4's documented range)");
  }
  // A parameter of type int32: 1e-6 us of round-off from a unit conversion is not a fraction.
  if (!(std::abs(us - std::round(us)) <= 1e-6 * us)) {
    throw Error("PX4 prediction interval EKF2_PREDICT_US: found " + num(us) +
                " us, expected a whole number of microseconds (an int32 parameter)");
  }
  const double imu_interval_s = 1.0 / imu_rate_hz;
  // roundf rounds halves away from zero, as std::round does.
  const double intervals = std::max(std::round(std::round(us) * 1e-6 / imu_interval_s), 1.0);
  return intervals * imu_interval_s;
}

std::vector<MissingFilterValue> missing_filter_values(const DiscreteNoise& noise,
                                                      ExportFormat format) {
  // The format's key for (sensor, bias): accel N, accel bias, gyro N, gyro bias.
  std::array<const char*, 4> keys{};
  switch (format) {
    case ExportFormat::kalibr:
    case ExportFormat::openvins:
      keys = {"accelerometer_noise_density", "accelerometer_random_walk",
              "gyroscope_noise_density", "gyroscope_random_walk"};
      break;
    case ExportFormat::vins_fusion:
      keys = {"acc_n", "acc_w", "gyr_n", "gyr_w"};
      break;
    case ExportFormat::gtsam:
      keys = {"accelerometerCovariance", "biasAccCovariance", "gyroscopeCovariance",
              "biasOmegaCovariance"};
      break;
    case ExportFormat::px4:
      keys = {kPx4AccNoise.name, kPx4AccBNoise.name, kPx4GyrNoise.name, kPx4GyrBNoise.name};
      break;
    case ExportFormat::json:
      return {};  // a sensor not given is absent there, never zero
  }
  std::vector<MissingFilterValue> missing;
  std::size_t i = 0;
  for (const Sensor sensor : {Sensor::accel, Sensor::gyro}) {
    const TriadDiscrete* t = noise.triad(sensor);
    for (const bool bias : {false, true}) {
      const bool present = t && (bias ? t->bias.has_value() : t->white.has_value());
      if (!present) missing.push_back({sensor, bias, keys[i]});
      ++i;
    }
  }
  return missing;
}

std::vector<std::string> missing_filter_keys(const DiscreteNoise& noise, ExportFormat format) {
  std::vector<std::string> keys;
  for (const auto& m : missing_filter_values(noise, format)) keys.push_back(m.key);
  return keys;
}

std::string missing_values_text(const std::vector<MissingFilterValue>& missing) {
  std::string text;
  for (const Sensor sensor : {Sensor::accel, Sensor::gyro}) {
    bool white = false, bias = false;
    for (const auto& m : missing) {
      if (m.sensor == sensor) (m.bias ? bias : white) = true;
    }
    if (!white && !bias) continue;
    text += std::string(text.empty() ? "" : ", ") +
            (sensor == Sensor::gyro ? "gyroscope " : "accelerometer ") +
            (white && bias ? "white noise and bias" : (white ? "white noise" : "bias"));
  }
  return text;
}

std::string_view missing_key_consequence(ExportFormat format) {
  switch (format) {
    case ExportFormat::kalibr: return "Kalibr stops on a missing key";
    case ExportFormat::openvins: return "OpenVINS stops on a missing key";
    case ExportFormat::vins_fusion:
      return "VINS-Fusion does not refuse the file: it reads 0 for a missing key and its IMU "
             "factor then inverts a singular covariance";
    case ExportFormat::gtsam: return "GTSAM keeps an identity covariance where none is set";
    case ExportFormat::px4:
      return "PX4 keeps its own default for a parameter not set (a flight tune, far above a "
             "sensor's noise), so the set would be mixed";
    case ExportFormat::json: return "";
  }
  return "";
}

std::string export_filter_config(const DiscreteNoise& noise, ExportFormat format,
                                 const ExportOptions& options) {
  require_any(noise);
  switch (format) {
    case ExportFormat::kalibr: return kalibr_like(noise, false, options);
    case ExportFormat::openvins: return kalibr_like(noise, true, options);
    case ExportFormat::vins_fusion: return vins(noise);
    case ExportFormat::gtsam: return gtsam(noise);
    case ExportFormat::px4: return px4(noise, options);
    case ExportFormat::json: return json(noise);
  }
  throw Error("unknown export format");
}

}  // namespace sigmatau
