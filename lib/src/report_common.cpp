// Helpers shared by the report's text (report.cpp) and its plots (report_plots.cpp): display
// units, number formatting, reading results.json (report_common.hpp).
#include "report_common.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

#include "sigmatau/display_units.hpp"
#include "sigmatau/units.hpp"

namespace sigmatau::report_detail {

DisplayUnits display_units(const std::string& sensor) {
  if (sensor != "gyro" && sensor != "accel") return {"", "", "", "", "", "", "", ""};
  const Sensor s = sensor == "gyro" ? Sensor::gyro : Sensor::accel;
  const auto unit = [&](NoiseTerm term) { return std::string(display_unit(term, s)); };
  const bool gyro = s == Sensor::gyro;
  return {unit(NoiseTerm::bias_instability), unit(NoiseTerm::white),
          unit(NoiseTerm::bias_instability), unit(NoiseTerm::rate_random_walk),
          unit(NoiseTerm::rate_ramp), unit(NoiseTerm::quantization),
          gyro ? "(deg/s)^2/Hz" : "(m/s^2)^2/Hz", gyro ? "deg/s/sqrt(Hz)" : "ug/sqrt(Hz)"};
}

/// SI value -> value in `unit` (empty unit: unchanged).
double in_unit(double si, const std::string& unit) {
  if (unit.empty()) return si;
  return si / parse_unit(unit).factor;
}

std::string fmt(double v, int digits) {
  if (!std::isfinite(v)) return "n/a";
  char b[48];
  std::snprintf(b, sizeof b, "%.*g", digits, v);
  return b;
}

/// "bias_instability" -> "bias instability" for people.
std::string spaced(std::string s) {
  for (char& c : s) {
    if (c == '_') c = ' ';
  }
  return s;
}

const json* find_fit(const json& results, const std::string& channel) {
  if (!results.contains("fit") || !results["fit"].contains("channels")) return nullptr;
  for (const auto& c : results["fit"]["channels"]) {
    if (c.value("name", "") == channel) return &c;
  }
  return nullptr;
}

/// "value [low, high] unit" of a fitted parameter, or "< bound unit" for an upper bound.
std::string parameter_text(const json& p, const std::string& unit) {
  if (p.contains("value")) {
    return fmt(in_unit(p["value"].get<double>(), unit)) + " [" +
           fmt(in_unit(p["ci_low"].get<double>(), unit)) + ", " +
           fmt(in_unit(p["ci_high"].get<double>(), unit)) + "] " + unit;
  }
  if (p.contains("upper_bound")) return "< " + fmt(in_unit(p["upper_bound"].get<double>(), unit), 3) + " " + unit;
  return "";
}

/// A number of a compliance item, NaN when absent or null (JSON has no NaN).
double item_number(const json& item, const char* key) {
  if (!item.contains(key) || !item[key].is_number()) return std::numeric_limits<double>::quiet_NaN();
  return item[key].get<double>();
}

/// True when the item's term was not detected (only an upper bound; older files lack the key).
bool undetected(const json& item) { return !item.value("detected", true); }

/// "gyro white noise x": the row's name. An accelerometer's K and R are named after
/// acceleration (IEEE 1293), as in `fit`, not "rate random walk".
std::string item_label(const json& item) {
  const std::string sensor = item.value("sensor", "");
  std::string quantity = spaced(item.value("quantity", ""));
  if (sensor == "accel" && quantity.rfind("rate ", 0) == 0) quantity = "acceleration " + quantity.substr(5);
  return sensor + " " + quantity + " " + item.value("axis", "");
}

}  // namespace sigmatau::report_detail
