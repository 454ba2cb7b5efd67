// Measured parameters from sigmatau result files (fit, calibrate, analyze), for the compliance
// check (see compliance.hpp, measured_parameters_from_json).
#include <nlohmann/json.hpp>

#include <boost/math/distributions/normal.hpp>
#include <cctype>
#include <cmath>
#include <limits>
#include <optional>

#include "sigmatau/channel_names.hpp"
#include "sigmatau/compliance.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/triad_frames.hpp"

namespace sigmatau {
namespace {

using nlohmann::json;

/// Sensor and axis of a fit channel: its "quantity" when given (then the name's last letter is
/// the axis), else the name by the one column-name rule (classify_channel).
ChannelRole role_of(const json& channel, const std::string& name, const std::string& file) {
  const std::string quantity = channel.value("quantity", "");
  std::optional<Sensor> sensor;
  if (quantity == "angular_rate") sensor = Sensor::gyro;
  if (quantity == "specific_force" || quantity == "acceleration") sensor = Sensor::accel;
  if (sensor) {
    const char c = name.empty() ? '\0'
                                : static_cast<char>(std::tolower(static_cast<unsigned char>(name.back())));
    if (c != 'x' && c != 'y' && c != 'z') {
      throw Error(file + ": channel \"" + name + "\" does not end in x, y or z (cannot tell its axis)");
    }
    return {*sensor, c - 'x'};
  }
  if (const auto role = classify_channel(name)) return *role;
  throw Error(file + ": channel \"" + name +
              "\" has no quantity and its name does not say gyro (gx, gyro_x, wx, ...) or "
              "accelerometer (ax, accel_x, ...) with an axis x, y or z");
}

double number(const json& j, const char* key, const std::string& where) {
  if (!j.contains(key) || !j[key].is_number()) {
    throw Error(where + ": missing number \"" + key + "\"");
  }
  return j[key].get<double>();
}

void read_fit(const json& doc, const std::string& file, std::vector<MeasuredParameter>& out) {
  static const std::pair<const char*, MeasuredQuantity> kTerms[] = {
      {"N", MeasuredQuantity::white_noise},
      {"B", MeasuredQuantity::bias_instability},
      {"K", MeasuredQuantity::rate_random_walk}};
  for (const auto& channel : doc.at("channels")) {
    const std::string name = channel.value("name", "");
    const ChannelRole role = role_of(channel, name, file);
    const Sensor sensor = role.sensor;
    const std::string axis(1, static_cast<char>('x' + role.axis));
    if (!channel.contains("parameters")) continue;
    // A joint fit's p value (a slopes fit has none): a rejected fit marks its verdicts.
    const double p_value = channel.contains("p_value") && channel["p_value"].is_number() &&
                                   channel.value("method", "joint") == "joint"
                               ? channel["p_value"].get<double>()
                               : std::numeric_limits<double>::quiet_NaN();
    for (const auto& [key, quantity] : kTerms) {
      if (!channel["parameters"].contains(key)) continue;
      const json& p = channel["parameters"][key];
      const std::string where = file + ": " + name + "." + key;
      if (!p.contains("value")) {
        // The fit left the term out and gives only its upper bound: checked by that bound.
        if (!p.contains("upper_bound")) continue;
        const json& bound = p["upper_bound"];
        if (!bound.is_number() && !bound.is_null()) {
          throw Error(where + ": \"upper_bound\" is not a number");
        }
        out.push_back({.sensor = sensor,
                       .quantity = quantity,
                       .axis = axis,
                       .detected = false,
                       .upper_bound = bound.is_null() ? std::numeric_limits<double>::quiet_NaN()
                                                      : bound.get<double>(),
                       .fit_p_value = p_value});
        continue;
      }
      out.push_back({.sensor = sensor,
                     .quantity = quantity,
                     .axis = axis,
                     .value = number(p, "value", where),
                     .ci_low = number(p, "ci_low", where),
                     .ci_high = number(p, "ci_high", where),
                     .fit_p_value = p_value});
    }
  }
}

/// The index in A's row-major entries of a calibrate parameter ("s_x" = A_xx - 1, "m_yx" = A_yx,
/// "G_xy" = A_xy), or -1 for any other parameter (biases, temperature terms).
int matrix_entry(const std::string& name) {
  const auto axis = [](char c) { return c == 'x' ? 0 : c == 'y' ? 1 : c == 'z' ? 2 : -1; };
  if (name.size() == 3 && name[0] == 's' && name[1] == '_' && axis(name[2]) >= 0) {
    return 4 * axis(name[2]);
  }
  if (name.size() == 4 && (name[0] == 'm' || name[0] == 'G') && name[1] == '_' &&
      axis(name[2]) >= 0 && axis(name[3]) >= 0) {
    return 3 * axis(name[2]) + axis(name[3]);
  }
  return -1;
}

/// A triad's sensing matrix with the covariance of its entries, when the result holds it
/// ("matrix", and "parameters" with "covariance" for the uncertainty; without them the
/// covariance is zero and an interval is only its estimate, as for a bias without "bias_ci").
std::optional<TriadMatrix> triad_matrix(const json& triad) {
  if (!triad.contains("matrix") || !triad["matrix"].is_array()) return std::nullopt;
  TriadMatrix t;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) t.a(i, j) = triad["matrix"].at(i).at(j).get<double>();
  if (triad.contains("parameters") && triad.contains("covariance")) {
    const auto& names = triad["parameters"];
    const auto& cov = triad["covariance"];
    for (std::size_t p = 0; p < names.size(); ++p) {
      const int ep = matrix_entry(names.at(p).get<std::string>());
      if (ep < 0) continue;
      for (std::size_t q = 0; q < names.size(); ++q) {
        const int eq = matrix_entry(names.at(q).get<std::string>());
        if (eq >= 0) t.covariance(ep, eq) = cov.at(p).at(q).get<double>();
      }
    }
  }
  return t;
}

/// A measured angle with its interval at `z` standard errors.
MeasuredParameter angle(Sensor sensor, MeasuredQuantity quantity, std::string axis,
                        const AngleEstimate& e, double z) {
  return {sensor, quantity, std::move(axis), e.value, e.value - z * e.standard_error,
          e.value + z * e.standard_error};
}

/// Two-sided normal quantile of a result's "confidence" (calibrate's intervals are normal).
double interval_z(const json& section) {
  const double confidence = section.value("confidence", 0.95);
  if (!(confidence > 0 && confidence < 1)) throw Error("\"confidence\" is not in (0, 1)");
  return boost::math::quantile(boost::math::normal(), (1 + confidence) / 2);
}

/// Reads one triad's parameters; returns its sensing matrix when the result holds it. The
/// cross-axis terms are not read one by one: they depend on the calibration frame, so only the
/// triad's non-orthogonality (frame-free) is checked.
std::optional<TriadMatrix> read_triad_calibration(const json& triad, Sensor sensor,
                                                  const std::string& file,
                                                  std::vector<MeasuredParameter>& out) {
  static const char* kAxes[] = {"x", "y", "z"};
  const std::string where = file + ": " + (sensor == Sensor::gyro ? "gyroscope" : "accelerometer");
  if (triad.contains("bias")) {
    for (int i = 0; i < 3; ++i) {
      const double b = triad["bias"].at(i).get<double>();
      double lo = b, hi = b;
      if (triad.contains("bias_ci")) {
        lo = triad["bias_ci"].at(i).at(0).get<double>();
        hi = triad["bias_ci"].at(i).at(1).get<double>();
      }
      out.push_back({sensor, MeasuredQuantity::bias, kAxes[i], b, lo, hi});
    }
  }
  if (triad.contains("scale_factor_error")) {
    for (int i = 0; i < 3; ++i) {
      const double s = triad["scale_factor_error"].at(i).get<double>();
      double lo = s, hi = s;
      if (triad.contains("scale_factor_error_ci")) {
        lo = triad["scale_factor_error_ci"].at(i).at(0).get<double>();
        hi = triad["scale_factor_error_ci"].at(i).at(1).get<double>();
      }
      out.push_back({sensor, MeasuredQuantity::scale_factor_error, kAxes[i], s, lo, hi});
    }
  }
  if (triad.contains("temperature_coefficients")) {
    const json& axes = triad["temperature_coefficients"];
    for (int i = 0; i < 3 && i < static_cast<int>(axes.size()); ++i) {
      const json& a = axes.at(i);
      if (!a.contains("linear") || !a["linear"].is_number()) continue;
      const double c = a["linear"].get<double>();
      double lo = c, hi = c;
      if (a.contains("linear_ci") && a["linear_ci"].is_array()) {
        lo = a["linear_ci"].at(0).get<double>();
        hi = a["linear_ci"].at(1).get<double>();
      }
      out.push_back({sensor, MeasuredQuantity::bias_temperature_coefficient, kAxes[i], c, lo, hi});
    }
  }
  const std::optional<TriadMatrix> matrix = triad_matrix(triad);
  if (matrix) {
    double z = 0;
    try {
      z = interval_z(triad);
    } catch (const Error& e) {
      throw Error(where + ": " + e.what());
    }
    static const int kPairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
    for (const auto& pair : kPairs) {
      out.push_back(angle(sensor, MeasuredQuantity::non_orthogonality,
                          std::string(kAxes[pair[0]]) + kAxes[pair[1]],
                          non_orthogonality(*matrix, pair[0], pair[1]), z));
    }
  }
  return matrix;
}

void read_calibration(const json& doc, const std::string& file, std::vector<MeasuredParameter>& out) {
  std::optional<TriadMatrix> accel, gyro;
  if (doc.contains("accelerometer")) accel = read_triad_calibration(doc["accelerometer"], Sensor::accel, file, out);
  if (doc.contains("gyroscope")) gyro = read_triad_calibration(doc["gyroscope"], Sensor::gyro, file, out);
  if (accel && gyro) {
    // Both written in the accelerometer frame (calibrate.hpp): their relative rotation is
    // reported beside the verdicts.
    const double z = interval_z(doc["gyroscope"]);
    const auto phi = relative_rotation(*accel, *gyro);
    static const char* kComponents[] = {"x", "y", "z"};
    for (std::size_t k = 0; k < 3; ++k) {
      out.push_back(angle(Sensor::gyro, MeasuredQuantity::frame_rotation, kComponents[k], phi[k], z));
    }
  }
}

}  // namespace

std::vector<MeasuredParameter> measured_parameters_from_json(std::string_view json_text,
                                                             const std::string& file) {
  json doc;
  try {
    doc = json::parse(json_text);
  } catch (const json::parse_error& e) {
    throw Error(file + ": not valid JSON (" + e.what() + ")");
  }
  std::vector<MeasuredParameter> out;
  try {
    // An analyze results.json has top-level "channels" too (curves, no "parameters"): read_fit
    // skips channels without parameters, so its "fit" section is what counts there.
    if (doc.contains("channels") && !doc.contains("fit")) read_fit(doc, file, out);
    if (doc.contains("accelerometer") || doc.contains("gyroscope")) read_calibration(doc, file, out);
    if (doc.contains("fit") && doc["fit"].contains("channels")) read_fit(doc["fit"], file, out);
    if (doc.contains("calibration")) read_calibration(doc["calibration"], file, out);
  } catch (const json::exception& e) {
    throw Error(file + ": unexpected result layout (" + e.what() + ")");
  }
  if (out.empty() && !doc.contains("channels") && !doc.contains("accelerometer") &&
      !doc.contains("gyroscope") && !doc.contains("fit") && !doc.contains("calibration")) {
    throw Error(file + ": not a sigmatau fit, calibrate or analyze result (expected a "
                "\"channels\", \"accelerometer\"/\"gyroscope\", or \"fit\" key)");
  }
  return out;
}

}  // namespace sigmatau
