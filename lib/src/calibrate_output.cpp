// Calibration results as JSON (SI) and as a table in data-sheet units (calibrate.hpp).
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <sstream>

#include "json_text.hpp"
#include "sigmatau/calibrate.hpp"
#include "sigmatau/calibrate_checks.hpp"
#include "sigmatau/units.hpp"

namespace sigmatau {
namespace {

using json = nlohmann::json;

/// Data-sheet units: deg/s per rad/s, mg per m/s^2 (1 g = standard gravity, as data sheets mean
/// it).
constexpr double kDegPerRad = kDegreesPerRadian;
constexpr double kMgPerMps2 = 1000 / kStandardGravity;

json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json matrix_json(const Eigen::MatrixXd& m) {
  json j = json::array();
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    json row = json::array();
    for (Eigen::Index k = 0; k < m.cols(); ++k) row.push_back(number(m(i, k)));
    j.push_back(row);
  }
  return j;
}

json ci_json(const CalibratedValue& v) { return {v.ci_low, v.ci_high}; }

/// How the Earth rate entered the gyroscope's bias: fitted with it as the Earth rate of the first
/// static interval, carried into the others by the attitudes from the integrated rotations
/// ("heading"), or its unknown part taken as independent noise per interval ("noise").
void earth_rate_json(const TriadCalibration& gyro, json& j) {
  if (!gyro.earth_rate) {
    j["earth_rate_model"] = "noise";
    return;
  }
  const Eigen::Vector3d& w = *gyro.earth_rate;
  j["earth_rate_model"] = "heading";
  j["earth_rate_first_interval"] = {w[0], w[1], w[2]};
  j["earth_rate_first_interval_se"] = {std::sqrt(gyro.earth_rate_covariance(0, 0)),
                                       std::sqrt(gyro.earth_rate_covariance(1, 1)),
                                       std::sqrt(gyro.earth_rate_covariance(2, 2))};
  j["earth_rate_norm"] = w.norm();
}

json triad_json(const TriadCalibration& t, const char* unit, double confidence) {
  json j;
  j["unit"] = unit;
  j["confidence"] = confidence;
  j["matrix_estimated"] = t.matrix_estimated;
  if (!t.note.empty()) j["note"] = t.note;
  json bias = json::array(), bias_ci = json::array(), bias_se = json::array();
  for (const auto& b : t.bias) {
    bias.push_back(b.value);
    bias_ci.push_back(ci_json(b));
    bias_se.push_back(b.standard_error);
  }
  j["bias"] = bias;
  j["bias_ci"] = bias_ci;
  j["bias_se"] = bias_se;
  j["bias_norm"] = std::hypot(t.bias[0].value, t.bias[1].value, t.bias[2].value);
  if (t.matrix_estimated) {
    j["matrix"] = matrix_json(t.matrix);
    j["matrix_se"] = matrix_json(t.matrix_se);
    json s = json::array(), s_ci = json::array(), s_se = json::array(), pct = json::array();
    for (const auto& v : t.scale_factor) {
      s.push_back(v.value);
      s_ci.push_back(ci_json(v));
      s_se.push_back(v.standard_error);
      pct.push_back(100 * v.value);
    }
    j["scale_factor_error"] = s;
    j["scale_factor_error_ci"] = s_ci;
    j["scale_factor_error_se"] = s_se;
    j["gain_error_percent"] = pct;
    json m = json::array(), m_ci = json::array(), m_se = json::array(), cross = json::array();
    for (int r = 0; r < 3; ++r) {
      json row = json::array(), row_ci = json::array(), row_se = json::array(), row_pct = json::array();
      for (int c = 0; c < 3; ++c) {
        const auto& v = t.misalignment[static_cast<std::size_t>(r)][static_cast<std::size_t>(c)];
        row.push_back(v ? json(v->value) : (r == c ? json(0.0) : json(nullptr)));
        row_ci.push_back(v ? ci_json(*v) : json(nullptr));
        row_se.push_back(v ? json(v->standard_error) : json(nullptr));
        row_pct.push_back(v ? json(100 * v->value) : json(nullptr));
      }
      m.push_back(row);
      m_ci.push_back(row_ci);
      m_se.push_back(row_se);
      cross.push_back(row_pct);
    }
    j["misalignment"] = m;
    j["misalignment_ci"] = m_ci;
    j["misalignment_se"] = m_se;
    j["cross_axis_percent"] = cross;
    j["invariant"] = matrix_json(t.invariant);
  } else {
    j["matrix"] = nullptr;
  }
  j["parameters"] = t.parameter_names;
  j["covariance"] = matrix_json(t.covariance);
  j["static_intervals"] = t.static_intervals;
  if (t.rotations) j["rotations"] = t.rotations;
  j["residual_rms"] = t.residual_rms;
  j["chi2"] = t.chi2;
  j["dof"] = t.dof;
  j["covariance_scale"] = t.covariance_scale;
  if (t.temperature) {
    json axes = json::array();
    for (const auto& a : *t.temperature) {
      json e{{"degree", a.degree},
             {"linear", a.linear.value},
             {"linear_ci", ci_json(a.linear)},
             {"linear_se", a.linear.standard_error},
             {"aicc_linear", number(a.aicc_linear)},
             {"aicc_quadratic", number(a.aicc_quadratic)}};
      if (a.quadratic) {
        e["quadratic"] = a.quadratic->value;
        e["quadratic_ci"] = ci_json(*a.quadratic);
        e["quadratic_se"] = a.quadratic->standard_error;
      }
      axes.push_back(e);
    }
    j["temperature_coefficients"] = axes;
    j["temperature_unit"] = std::string(unit) + "/K";
  }
  return j;
}

}  // namespace

std::string calibration_json(const CalibrationResult& r) {
  json doc;
  doc["tool"] = "sigmatau";
  doc["version"] = SIGMATAU_VERSION;
  doc["gravity"] = r.gravity;
  doc["orientations"] = r.orientations;
  doc["confidence"] = r.confidence;
  doc["model"] = "y = A x + b(T) + v, A = I + T; compensated x = A^-1 (y - b(T)); "
                 "b(T) = b + c1 (T - T0) + c2 (T - T0)^2";
  doc["accelerometer"] = triad_json(r.accel, "m/s^2", r.confidence);
  doc["accelerometer"]["convention"] =
      "A lower triangular: frame x along the x sensing axis, y in the x-y sensing plane; "
      "identifiable: s_x, s_y, s_z, m_yx, m_zx, m_zy, b; m_xy, m_xz, m_yz fixed at 0 (null)";
  // The temperature at which each bias holds: T0 with a temperature model, else the mean.
  const auto bias_at = [&](const TriadCalibration& t, json& j) {
    if (r.has_temperature)
      j["bias_temperature_k"] = t.temperature ? r.reference_temperature_k : mean_interval_temperature_k(r);
  };
  bias_at(r.accel, doc["accelerometer"]);
  if (r.gyro) {
    doc["gyroscope"] = triad_json(*r.gyro, "rad/s", r.confidence);
    earth_rate_json(*r.gyro, doc["gyroscope"]);
    bias_at(*r.gyro, doc["gyroscope"]);
    doc["gyroscope"]["convention"] =
        "all 9 terms of A, in the accelerometer frame (see accelerometer.convention)";
  }
  json intervals = json::array();
  for (const auto& s : r.detection.intervals) {
    json e{{"first", s.first}, {"last", s.last}, {"start_s", s.start_s}, {"end_s", s.end_s},
           {"accel_mean", {s.accel_mean[0], s.accel_mean[1], s.accel_mean[2]}},
           {"accel_se",
            {std::sqrt(s.accel_cov(0, 0)), std::sqrt(s.accel_cov(1, 1)), std::sqrt(s.accel_cov(2, 2))}}};
    if (r.gyro) {
      e["gyro_mean"] = {s.gyro_mean[0], s.gyro_mean[1], s.gyro_mean[2]};
      e["gyro_se"] = {std::sqrt(s.gyro_cov(0, 0)), std::sqrt(s.gyro_cov(1, 1)), std::sqrt(s.gyro_cov(2, 2))};
    }
    if (r.has_temperature) e["temperature_k"] = s.temperature_k;
    intervals.push_back(e);
  }
  doc["detector"] = {{"window_samples", r.detection.window_samples},
                     {"threshold_factor", kStaticThresholdFactor},
                     {"accel_floor", r.detection.accel_floor},
                     {"accel_threshold", r.detection.accel_threshold},
                     {"gyro_floor", r.detection.gyro_floor},
                     {"gyro_threshold", r.detection.gyro_threshold},
                     {"noise_inflation", r.detection.noise_inflation},
                     {"intervals", intervals}};
  if (r.has_temperature) {
    doc["temperature"] = {{"reference_k", r.reference_temperature_k},
                          {"min_k", r.temperature_min_k},
                          {"max_k", r.temperature_max_k},
                          {"mean_k", mean_interval_temperature_k(r)},
                          {"modelled", r.accel.temperature.has_value() ||
                                           (r.gyro && r.gyro->temperature.has_value())}};
  }
  const std::vector<std::string> notes = calibration_notes(r);
  if (!notes.empty()) doc["notes"] = notes;
  return detail::json_text(doc, 2) + "\n";
}

std::string calibration_table(const CalibrationResult& r) {
  std::ostringstream out;
  char line[256];
  std::snprintf(line, sizeof line,
                "# %zu static intervals, %d orientations, gravity %.6g m/s^2, %g%% intervals\n",
                r.detection.intervals.size(), r.orientations, r.gravity, 100 * r.confidence);
  out << line;
  if (r.has_temperature) {
    std::snprintf(line, sizeof line,
                  "# temperature %.2f to %.2f degC over the static intervals (mean %.2f degC)\n",
                  r.temperature_min_k - 273.15, r.temperature_max_k - 273.15,
                  mean_interval_temperature_k(r) - 273.15);
    out << line;
  }
  const auto triad = [&](const TriadCalibration& t, const char* name, const char* unit, double k,
                         const char* tunit) {
    out << "\n" << name << "\n";
    if (t.matrix_estimated) {
      out << "  A = I + T:\n";
      for (int i = 0; i < 3; ++i) {
        std::snprintf(line, sizeof line, "    %12.8f %12.8f %12.8f\n", t.matrix(i, 0),
                      t.matrix(i, 1), t.matrix(i, 2));
        out << line;
      }
      for (int i = 0; i < 3; ++i) {
        const auto& s = t.scale_factor[static_cast<std::size_t>(i)];
        std::snprintf(line, sizeof line, "  gain error %c      %+9.4f %%  [%+9.4f, %+9.4f]\n",
                      "xyz"[i], 100 * s.value, 100 * s.ci_low, 100 * s.ci_high);
        out << line;
      }
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const auto& m = t.misalignment[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
          if (i == j || !m) continue;
          std::snprintf(line, sizeof line, "  cross-axis %c%c     %+9.4f %%  [%+9.4f, %+9.4f]\n",
                        "xyz"[i], "xyz"[j], 100 * m->value, 100 * m->ci_low, 100 * m->ci_high);
          out << line;
        }
    } else {
      out << "  matrix not estimated (see the notes below)\n";
    }
    // At which temperature the bias holds: T0 with a temperature model, else the log's mean.
    if (t.temperature)
      std::snprintf(line, sizeof line, "  bias b at T0 = %.2f degC (temperature model below):\n",
                    r.reference_temperature_k - 273.15);
    else if (r.has_temperature)
      std::snprintf(line, sizeof line,
                    "  bias b at the log's mean temperature %.2f degC (no temperature model):\n",
                    mean_interval_temperature_k(r) - 273.15);
    else
      std::snprintf(line, sizeof line, "  bias b (no temperature column):\n");
    out << line;
    for (int i = 0; i < 3; ++i) {
      const auto& b = t.bias[static_cast<std::size_t>(i)];
      std::snprintf(line, sizeof line, "  bias %c            %+11.5g %s  [%+11.5g, %+11.5g]\n",
                    "xyz"[i], k * b.value, unit, k * b.ci_low, k * b.ci_high);
      out << line;
    }
    std::snprintf(line, sizeof line, "  |b|               %11.5g %s\n",
                  k * std::hypot(t.bias[0].value, t.bias[1].value, t.bias[2].value), unit);
    out << line;
    if (r.gyro && &t == &*r.gyro) {
      if (t.earth_rate) {
        std::snprintf(line, sizeof line,
                      "  Earth rate: fitted with the bias, turned into each rest by the integrated "
                      "rotations: |w| = %.4g deg/h (the Earth turns at 15.04)\n",
                      t.earth_rate->norm() * kDegPerRad * 3600);
      } else {
        std::snprintf(line, sizeof line,
                      "  Earth rate: its unknown part taken as noise in each rest (wider bias "
                      "intervals)\n");
      }
      out << line;
    }
    if (t.temperature)
      for (int i = 0; i < 3; ++i) {
        const auto& a = (*t.temperature)[static_cast<std::size_t>(i)];
        std::snprintf(line, sizeof line, "  bias tempco %c     %+11.5g %s  [%+11.5g, %+11.5g]%s\n",
                      "xyz"[i], k * a.linear.value, tunit, k * a.linear.ci_low, k * a.linear.ci_high,
                      a.degree == 2 ? " (+ quadratic term)" : "");
        out << line;
      }
    std::snprintf(line, sizeof line, "  residual rms %.4g, chi2/dof %.4g/%d\n", t.residual_rms,
                  t.chi2, t.dof);
    out << line;
  };
  triad(r.accel, "accelerometer (m_xy, m_xz, m_yz not identifiable: 0 by convention)", "mg",
        kMgPerMps2, "mg/degC");
  if (r.gyro) triad(*r.gyro, "gyroscope (in the accelerometer frame)", "deg/s", kDegPerRad, "deg/s/degC");
  const bool modelled = r.accel.temperature || (r.gyro && r.gyro->temperature);
  if (modelled) {
    out << "\ncompensation: x = A^-1 (y - b(T)), b(T) = b + c1 (T - T0) [+ c2 (T - T0)^2]";
    std::snprintf(line, sizeof line, ", T0 = %.2f degC", r.reference_temperature_k - 273.15);
    out << line;
    if (!r.accel.temperature || (r.gyro && !r.gyro->temperature))
      out << " (c1 = c2 = 0 for the " << (r.accel.temperature ? "gyroscope" : "accelerometer")
          << ", whose b holds at the mean temperature)";
  } else {
    out << "\ncompensation: x = A^-1 (y - b)";
  }
  out << "\n";
  const std::vector<std::string> notes = calibration_notes(r);
  if (!notes.empty()) {
    out << "\nnotes:\n";
    for (const auto& n : notes) out << "  " << n << "\n";
  }
  return out.str();
}

}  // namespace sigmatau
