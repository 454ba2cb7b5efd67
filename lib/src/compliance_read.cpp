// Measured parameters from sigmatau result files (fit, calibrate, analyze), for the compliance
// check (see compliance.hpp, measured_parameters_from_json).
#include <boost/math/distributions/normal.hpp>
#include <cctype>
#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <tuple>
#include <utility>

#include "json_fields.hpp"
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

using detail::JsonField;
using detail::NumberRule;

/// `array[index]` as a finite number (a bias, a scale-factor error, a matrix entry: any sign).
/// Throws Error naming the field when `array` is too short or the element is not one.
double finite_at(const json& array, std::size_t index, const JsonField& field) {
  if (!array.is_array() || index >= array.size()) {
    throw Error(field.message("expected an array of at least " + std::to_string(index + 1) +
                              " numbers, got " + detail::json_shown(array)));
  }
  const json& v = array[index];
  if (!v.is_number() || !std::isfinite(v.get<double>())) {
    throw Error(field.at(index).message("expected a finite number, got " + detail::json_shown(v)));
  }
  return v.get<double>();
}

/// `array[index]` as an interval [low, high] of finite numbers with low <= high.
std::pair<double, double> interval_at(const json& array, std::size_t index,
                                      const JsonField& field) {
  if (!array.is_array() || index >= array.size()) {
    throw Error(field.message("expected an array of at least " + std::to_string(index + 1) +
                              " intervals, got " + detail::json_shown(array)));
  }
  const JsonField here = field.at(index);
  const double low = finite_at(array[index], 0, here), high = finite_at(array[index], 1, here);
  if (!(low <= high)) {
    throw Error(here.message("expected [low, high] with low <= high, got " +
                             detail::json_shown(array[index])));
  }
  return {low, high};
}

void read_fit(const json& doc, const JsonField& at, std::vector<MeasuredParameter>& out) {
  static const std::pair<const char*, MeasuredQuantity> kTerms[] = {
      {"N", MeasuredQuantity::white_noise},
      {"B", MeasuredQuantity::bias_instability},
      {"K", MeasuredQuantity::rate_random_walk}};
  const json& channels = doc.at("channels");
  if (!channels.is_array()) {
    throw Error(
        at.at("channels").message("expected an array, got " + detail::json_shown(channels)));
  }
  for (std::size_t index = 0; index < channels.size(); ++index) {
    const json& channel = channels[index];
    const JsonField here = at.at("channels").at(index);
    if (!channel.is_object()) {
      throw Error(here.message("expected an object, got " + detail::json_shown(channel)));
    }
    const std::string name = detail::optional_text(channel, "name", here).value_or("");
    const JsonField named = here.named(name);
    detail::optional_text(channel, "quantity", named);
    const ChannelRole role = role_of(channel, name, at.file);
    const Sensor sensor = role.sensor;
    const std::string axis(1, static_cast<char>('x' + role.axis));
    if (!channel.contains("parameters")) continue;
    // A joint fit's p value (a slopes fit has none): a rejected fit marks its verdicts.
    const std::optional<double> p =
        detail::optional_number(channel, "p_value", named, NumberRule::probability, true);
    const std::string method = detail::optional_text(channel, "method", named).value_or("joint");
    const double p_value = p && method == "joint" ? *p : std::numeric_limits<double>::quiet_NaN();
    // The curve's read-outs standing in for a rejected or contradicted joint fit (fit JSON
    // "reported_from": "curve_readings").
    const bool readings = detail::optional_text(channel, "reported_from", named).value_or("") == "curve_readings";
    for (const auto& [key, quantity] : kTerms) {
      const std::optional<detail::FitTermFields> term =
          detail::fit_term_fields(channel["parameters"], key, named.at("parameters"));
      if (!term) continue;
      const std::string where = at.file + ": " + name + "." + key;
      if (!term->value) {
        // The fit left the term out and gives only its upper bound: checked by that bound
        // (null: none could be computed).
        if (!channel["parameters"][key].contains("upper_bound")) continue;
        out.push_back(
            {.sensor = sensor,
             .quantity = quantity,
             .axis = axis,
             .detected = false,
             .upper_bound = term->upper_bound.value_or(std::numeric_limits<double>::quiet_NaN()),
             .fit_p_value = p_value,
             .from_curve_readings = readings});
        continue;
      }
      for (const auto& [bound, name_of_bound] :
           {std::pair{term->ci_low, "ci_low"}, std::pair{term->ci_high, "ci_high"}}) {
        if (!bound) throw Error(where + ": missing number \"" + name_of_bound + "\"");
      }
      out.push_back({.sensor = sensor,
                     .quantity = quantity,
                     .axis = axis,
                     .value = *term->value,
                     .ci_low = *term->ci_low,
                     .ci_high = *term->ci_high,
                     .fit_p_value = p_value,
                     .from_curve_readings = readings});
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
std::optional<TriadMatrix> triad_matrix(const json& triad, const JsonField& field) {
  if (!triad.contains("matrix") || !triad["matrix"].is_array()) return std::nullopt;
  TriadMatrix t;
  for (std::size_t i = 0; i < 3; ++i) {
    if (triad["matrix"].size() <= i) {
      throw Error(field.at("matrix").message("expected 3 rows, got " +
                                             detail::json_shown(triad["matrix"])));
    }
    for (std::size_t j = 0; j < 3; ++j) {
      t.a(static_cast<int>(i), static_cast<int>(j)) =
          finite_at(triad["matrix"][i], j, field.at("matrix").at(i));
    }
  }
  if (triad.contains("parameters") && triad.contains("covariance")) {
    const auto& names = triad["parameters"];
    const auto& cov = triad["covariance"];
    for (std::size_t p = 0; p < names.size(); ++p) {
      if (!names[p].is_string()) {
        throw Error(field.at("parameters")
                        .at(p)
                        .message("expected a text, got " + detail::json_shown(names[p])));
      }
      const int ep = matrix_entry(names[p].get<std::string>());
      if (ep < 0) continue;
      for (std::size_t q = 0; q < names.size(); ++q) {
        if (!names[q].is_string()) continue;  // refused in its own row
        const int eq = matrix_entry(names[q].get<std::string>());
        if (eq < 0) continue;
        const JsonField row = field.at("covariance").at(p);
        if (!cov.is_array() || cov.size() <= p) {
          throw Error(field.at("covariance")
                          .message("expected a row per parameter, got " + detail::json_shown(cov)));
        }
        const double c = finite_at(cov[p], q, row);
        if (p == q && !(c >= 0)) {
          throw Error(
              row.at(q).message("expected a variance >= 0, got " + detail::json_shown(cov[p][q])));
        }
        t.covariance(ep, eq) = c;
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
double interval_z(const json& section, const JsonField& field) {
  const double confidence =
      detail::optional_number(section, "confidence", field, NumberRule::confidence_level)
          .value_or(0.95);
  return boost::math::quantile(boost::math::normal(), (1 + confidence) / 2);
}

/// Reads one triad's parameters; returns its sensing matrix when the result holds it. The
/// cross-axis terms are not read one by one: they depend on the calibration frame, so only the
/// triad's non-orthogonality (frame-free) is checked.
std::optional<TriadMatrix> read_triad_calibration(const json& triad, Sensor sensor,
                                                  const JsonField& field,
                                                  std::vector<MeasuredParameter>& out) {
  static const char* kAxes[] = {"x", "y", "z"};
  if (!triad.is_object()) {
    throw Error(field.message("expected an object, got " + detail::json_shown(triad)));
  }
  // A value per axis, and its interval when the result gives one ("bias", "bias_ci").
  const auto per_axis = [&](const char* key, const char* ci_key, MeasuredQuantity quantity) {
    if (!triad.contains(key)) return;
    for (std::size_t i = 0; i < 3; ++i) {
      const double v = finite_at(triad[key], i, field.at(key));
      double lo = v, hi = v;
      if (triad.contains(ci_key))
        std::tie(lo, hi) = interval_at(triad[ci_key], i, field.at(ci_key));
      out.push_back({sensor, quantity, kAxes[i], v, lo, hi});
    }
  };
  per_axis("bias", "bias_ci", MeasuredQuantity::bias);
  per_axis("scale_factor_error", "scale_factor_error_ci", MeasuredQuantity::scale_factor_error);
  if (triad.contains("temperature_coefficients")) {
    const json& axes = triad["temperature_coefficients"];
    const JsonField at = field.at("temperature_coefficients");
    if (!axes.is_array())
      throw Error(at.message("expected an array, got " + detail::json_shown(axes)));
    for (std::size_t i = 0; i < 3 && i < axes.size(); ++i) {
      const json& a = axes[i];
      if (!a.is_object() || !a.contains("linear") || a["linear"].is_null()) continue;
      const double c = *detail::optional_number(a, "linear", at.at(i), NumberRule::finite);
      double lo = c, hi = c;
      if (a.contains("linear_ci") && a["linear_ci"].is_array()) {
        lo = finite_at(a["linear_ci"], 0, at.at(i).at("linear_ci"));
        hi = finite_at(a["linear_ci"], 1, at.at(i).at("linear_ci"));
        if (!(lo <= hi)) {
          throw Error(at.at(i)
                          .at("linear_ci")
                          .message("expected [low, high] with low <= high, got " +
                                   detail::json_shown(a["linear_ci"])));
        }
      }
      out.push_back({sensor, MeasuredQuantity::bias_temperature_coefficient, kAxes[i], c, lo, hi});
    }
  }
  const std::optional<TriadMatrix> matrix = triad_matrix(triad, field);
  if (matrix) {
    const double z = interval_z(triad, field);
    static const int kPairs[3][2] = {{0, 1}, {0, 2}, {1, 2}};
    for (const auto& pair : kPairs) {
      out.push_back(angle(sensor, MeasuredQuantity::non_orthogonality,
                          std::string(kAxes[pair[0]]) + kAxes[pair[1]],
                          non_orthogonality(*matrix, pair[0], pair[1]), z));
    }
  }
  return matrix;
}

void read_calibration(const json& doc, const JsonField& field,
                      std::vector<MeasuredParameter>& out) {
  std::optional<TriadMatrix> accel, gyro;
  if (doc.contains("accelerometer")) {
    accel =
        read_triad_calibration(doc["accelerometer"], Sensor::accel, field.at("accelerometer"), out);
  }
  if (doc.contains("gyroscope")) {
    gyro = read_triad_calibration(doc["gyroscope"], Sensor::gyro, field.at("gyroscope"), out);
  }
  if (accel && gyro) {
    // Both written in the accelerometer frame (calibrate.hpp): their relative rotation is
    // reported beside the verdicts.
    const double z = interval_z(doc["gyroscope"], field.at("gyroscope"));
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
  } catch (const json::exception& e) {  // a parse error, or a number too large (1e999)
    throw Error(file + ": not valid JSON (" + e.what() + ")");
  }
  std::vector<MeasuredParameter> out;
  const JsonField top{file, ""};
  try {
    // The level of the intervals, when given: what the verdicts' wording rests on.
    detail::optional_number(doc, "confidence", top, NumberRule::confidence_level);
    // An analyze results.json has top-level "channels" too (curves, no "parameters"): read_fit
    // skips channels without parameters, so its "fit" section is what counts there.
    if (doc.contains("channels") && !doc.contains("fit")) read_fit(doc, top, out);
    if (doc.contains("accelerometer") || doc.contains("gyroscope")) read_calibration(doc, top, out);
    if (doc.contains("fit") && doc["fit"].contains("channels")) {
      detail::optional_number(doc["fit"], "confidence", top.at("fit"),
                              NumberRule::confidence_level);
      read_fit(doc["fit"], top.at("fit"), out);
    }
    if (doc.contains("calibration"))
      read_calibration(doc["calibration"], top.at("calibration"), out);
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
