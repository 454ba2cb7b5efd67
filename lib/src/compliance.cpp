// Compliance verdicts: measured parameters against data-sheet limits (see compliance.hpp).
#include "sigmatau/compliance.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "sigmatau/error.hpp"

namespace sigmatau {
namespace {

struct Candidate {
  SpecField field;
  double limit_factor;  // limit_si = printed value_si * limit_factor
  const char* rule;
};

/// The data-sheet fields a measured quantity is compared with, in order of preference.
std::vector<Candidate> candidates(MeasuredQuantity q, DensityConvention convention) {
  const bool one_sided = convention == DensityConvention::one_sided;
  switch (q) {
    case MeasuredQuantity::white_noise:
      return {{SpecField::random_walk, 1.0, "measured N against the printed random walk (ARW/VRW)"},
              {SpecField::noise_density, one_sided ? 1.0 / std::sqrt(2.0) : 1.0,
               one_sided ? "measured N against printed noise density / sqrt(2) (one-sided convention)"
                         : "measured N against printed noise density (two-sided convention: N = ND)"}};
    case MeasuredQuantity::bias_instability:
      return {{SpecField::bias_instability, 1.0,
               "ADEV floor 0.664 B against the printed in-run bias stability"}};
    case MeasuredQuantity::rate_random_walk:
      return {{SpecField::rate_random_walk, 1.0, "measured K against the printed rate random walk"}};
    case MeasuredQuantity::bias:
      return {{SpecField::initial_bias, 1.0, "|b| against the printed initial bias / zero offset"}};
    case MeasuredQuantity::scale_factor_error:
      return {{SpecField::sensitivity_error, 1.0, "|s| against the printed sensitivity tolerance"}};
    case MeasuredQuantity::cross_axis:
      return {{SpecField::cross_axis_sensitivity, 1.0, "|m| against the printed cross-axis sensitivity"},
              {SpecField::misalignment, 1.0,
               "|m| against the printed misalignment angle (small-angle: rad = ratio)"}};
    case MeasuredQuantity::bias_temperature_coefficient:
      return {{SpecField::bias_temperature_coefficient, 1.0,
               "|db/dT| against the printed bias temperature coefficient"}};
  }
  return {};
}

/// The estimate and its upper bound as compared with the limit. A term not detected has no
/// estimate (NaN) and its one-sided upper bound in place of the interval's upper end.
std::pair<double, double> as_compared(const MeasuredParameter& p) {
  if (!p.detected) {
    const double bound = std::abs(p.upper_bound);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (p.quantity == MeasuredQuantity::bias_instability) return {nan, kFlickerFloorFactor * bound};
    return {nan, bound};
  }
  switch (p.quantity) {
    case MeasuredQuantity::bias_instability:
      return {kFlickerFloorFactor * p.value, kFlickerFloorFactor * p.ci_high};
    case MeasuredQuantity::bias:
    case MeasuredQuantity::scale_factor_error:
    case MeasuredQuantity::cross_axis:
    case MeasuredQuantity::bias_temperature_coefficient:
      return {std::abs(p.value), std::max(std::abs(p.ci_low), std::abs(p.ci_high))};
    default:
      return {p.value, p.ci_high};
  }
}

std::string_view field_key(Sensor sensor, SpecField field) {
  const SpecFieldInfo* info = spec_field_info(sensor, field);
  return info ? info->key : std::string_view("?");
}

}  // namespace

std::string_view to_string(MeasuredQuantity quantity) {
  switch (quantity) {
    case MeasuredQuantity::white_noise: return "white_noise";
    case MeasuredQuantity::bias_instability: return "bias_instability";
    case MeasuredQuantity::rate_random_walk: return "rate_random_walk";
    case MeasuredQuantity::bias: return "bias";
    case MeasuredQuantity::scale_factor_error: return "scale_factor_error";
    case MeasuredQuantity::cross_axis: return "cross_axis";
    case MeasuredQuantity::bias_temperature_coefficient: return "bias_temperature_coefficient";
  }
  return "?";
}

std::string_view to_string(Verdict verdict) {
  switch (verdict) {
    case Verdict::pass: return "pass";
    case Verdict::marginal: return "marginal";
    case Verdict::fail: return "fail";
    case Verdict::inconclusive: return "inconclusive";
    case Verdict::not_specified: return "not specified";
  }
  return "?";
}

std::vector<ComplianceItem> check_compliance(const std::vector<MeasuredParameter>& measured,
                                             const DataSheet& sheet,
                                             const ComplianceOptions& options) {
  std::vector<ComplianceItem> items;
  for (const auto& p : measured) {
    const SensorSheet* section = sheet.sensor(p.sensor);
    bool found = false;
    if (section) {
      for (const auto& candidate : candidates(p.quantity, options.convention)) {
        const SpecValue* value = section->find(candidate.field);
        if (!value || !value->limit()) continue;
        const PrintedValue& limit = *value->limit();
        ComplianceItem item;
        item.measured = p;
        item.spec_field = std::string(field_key(p.sensor, candidate.field));
        item.limit_text = limit.text;
        item.limit_unit = limit.unit;
        item.limit_is_typical = value->limit_is_typical();
        item.limit_si = std::abs(limit.value_si) * candidate.limit_factor;
        std::tie(item.compared, item.compared_upper) = as_compared(p);
        item.rule = candidate.rule;
        if (item.limit_is_typical) item.rule += " (no max printed: typical value used)";
        if (!(item.limit_si > 0)) continue;  // a zero limit cannot be a ratio
        item.margin = item.compared / item.limit_si;
        item.margin_upper = item.compared_upper / item.limit_si;
        if (!p.detected) {
          // Only a bound: within the limit it shows the term is small enough; beyond it the log
          // cannot tell (a longer one would), which is not evidence of a failure. A NaN bound
          // is inconclusive too.
          item.rule += "; not detected by the fit: its one-sided upper bound against the limit";
          item.verdict = item.compared_upper <= item.limit_si ? Verdict::pass : Verdict::inconclusive;
        } else if (!(item.compared <= item.limit_si)) {
          item.verdict = Verdict::fail;  // NaN estimates fail too
        } else if (item.compared_upper <= item.limit_si) {
          item.verdict = Verdict::pass;
        } else {
          item.verdict = Verdict::marginal;
        }
        items.push_back(std::move(item));
        found = true;
        break;  // the preferred field decides; a sheet printing both ARW and ND uses ARW
      }
    }
    // A term neither printed on the sheet nor detected in the log says nothing: no row.
    if (!found && p.detected) {
      ComplianceItem item;
      item.measured = p;
      item.verdict = Verdict::not_specified;
      std::tie(item.compared, item.compared_upper) = as_compared(p);
      items.push_back(std::move(item));
    }
  }
  return items;
}

bool any_failed(const std::vector<ComplianceItem>& items) {
  return std::any_of(items.begin(), items.end(),
                     [](const ComplianceItem& i) { return i.verdict == Verdict::fail; });
}

std::string overall_verdict(const std::vector<ComplianceItem>& items) {
  int pass = 0, marginal = 0, fail = 0, inconclusive = 0;
  for (const auto& item : items) {
    pass += item.verdict == Verdict::pass;
    marginal += item.verdict == Verdict::marginal;
    fail += item.verdict == Verdict::fail;
    inconclusive += item.verdict == Verdict::inconclusive;
  }
  if (fail > 0) return "fail";
  if (marginal > 0) return "marginal";
  if (inconclusive > 0) return "inconclusive";
  return pass > 0 ? "all pass" : "nothing to check";
}

std::string compliance_json(const std::vector<ComplianceItem>& items, const DataSheet& sheet,
                            const ComplianceOptions& options) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& item : items) {
    nlohmann::json j = {{"sensor", std::string(to_string(item.measured.sensor))},
                        {"quantity", std::string(to_string(item.measured.quantity))},
                        {"axis", item.measured.axis},
                        {"detected", item.measured.detected}};
    // The measured side as a fit result gives it: an interval, or only an upper bound.
    if (item.measured.detected) {
      j["value"] = item.measured.value;
      j["ci_low"] = item.measured.ci_low;
      j["ci_high"] = item.measured.ci_high;
    } else {
      j["upper_bound"] = item.measured.upper_bound;
    }
    j["verdict"] = std::string(to_string(item.verdict));
    if (item.verdict != Verdict::not_specified) {
      j["spec_field"] = item.spec_field;
      j["limit_text"] = item.limit_text;
      j["limit_is_typical"] = item.limit_is_typical;
      j["limit_si"] = item.limit_si;
      if (item.measured.detected) j["compared"] = item.compared;
      j["compared_upper"] = item.compared_upper;
      if (item.measured.detected) j["margin"] = item.margin;
      j["margin_upper"] = item.margin_upper;
      j["rule"] = item.rule;
    }
    list.push_back(j);
  }
  const nlohmann::json doc = {
      {"spec", {{"name", sheet.name}, {"part", sheet.part}, {"manufacturer", sheet.manufacturer}}},
      {"density_convention", std::string(to_string(options.convention))},
      {"verdict", overall_verdict(items)},
      {"failed", any_failed(items)},
      {"items", list}};
  return doc.dump(1);
}

namespace {

using nlohmann::json;

std::string axis_letter(const std::string& name, const std::string& file) {
  if (!name.empty()) {
    const char c = static_cast<char>(std::tolower(static_cast<unsigned char>(name.back())));
    if (c == 'x' || c == 'y' || c == 'z') return std::string(1, c);
  }
  throw Error(file + ": channel \"" + name + "\" does not end in x, y or z (cannot tell its axis)");
}

Sensor sensor_of(const json& channel, const std::string& name, const std::string& file) {
  const std::string quantity = channel.value("quantity", "");
  if (quantity == "angular_rate") return Sensor::gyro;
  if (quantity == "specific_force" || quantity == "acceleration") return Sensor::accel;
  if (!name.empty() && (name[0] == 'g' || name[0] == 'G' || name[0] == 'w')) return Sensor::gyro;
  if (!name.empty() && (name[0] == 'a' || name[0] == 'A')) return Sensor::accel;
  throw Error(file + ": channel \"" + name + "\" has no quantity and its name does not say gyro (g..) or accelerometer (a..)");
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
    const Sensor sensor = sensor_of(channel, name, file);
    const std::string axis = axis_letter(name, file);
    if (!channel.contains("parameters")) continue;
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
                                                      : bound.get<double>()});
        continue;
      }
      out.push_back({sensor, quantity, axis, number(p, "value", where), number(p, "ci_low", where),
                     number(p, "ci_high", where)});
    }
  }
}

void read_triad_calibration(const json& triad, Sensor sensor, const std::string& file,
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
  if (triad.contains("misalignment")) {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        if (i == j) continue;
        const json& m = triad["misalignment"].at(i).at(j);
        if (m.is_null()) continue;  // not identifiable
        const double v = m.get<double>();
        double lo = v, hi = v;
        if (triad.contains("misalignment_ci") && !triad["misalignment_ci"].at(i).at(j).is_null()) {
          lo = triad["misalignment_ci"].at(i).at(j).at(0).get<double>();
          hi = triad["misalignment_ci"].at(i).at(j).at(1).get<double>();
        }
        out.push_back({sensor, MeasuredQuantity::cross_axis,
                       std::string(kAxes[i]) + kAxes[j], v, lo, hi});
      }
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
  (void)where;
}

void read_calibration(const json& doc, const std::string& file, std::vector<MeasuredParameter>& out) {
  if (doc.contains("accelerometer")) read_triad_calibration(doc["accelerometer"], Sensor::accel, file, out);
  if (doc.contains("gyroscope")) read_triad_calibration(doc["gyroscope"], Sensor::gyro, file, out);
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
