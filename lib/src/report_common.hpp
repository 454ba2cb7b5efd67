#pragma once
// Private to the report (report.cpp, report_common.cpp, report_plots.cpp): what the text tables
// and the plots share when they read results.json. Not installed.

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

#include "sigmatau/report.hpp"

namespace sigmatau::report_detail {

using nlohmann::json;

/// Display units per sensor, as data sheets print them.
struct DisplayUnits {
  std::string deviation;  ///< ADEV axis
  std::string white;      ///< N
  std::string bias;       ///< B
  std::string walk;       ///< K
  std::string ramp;       ///< R
  std::string quantization;  ///< Q
  std::string psd;        ///< PSD axis
  std::string density;    ///< noise density
};

/// The units of "gyro" or "accel"; all empty (SI) for another sensor.
DisplayUnits display_units(const std::string& sensor);

/// SI value -> value in `unit` (empty unit: unchanged).
double in_unit(double si, const std::string& unit);

/// `v` with `digits` significant digits ("%g"), "n/a" when not finite.
std::string fmt(double v, int digits = 4);

/// "bias_instability" -> "bias instability" for people.
std::string spaced(std::string s);

/// The fit of channel `channel` in results.json's "fit" section, nullptr when absent.
const json* find_fit(const json& results, const std::string& channel);

/// "value [low, high] unit" of a fitted parameter, or "< bound unit" for an upper bound.
std::string parameter_text(const json& p, const std::string& unit);

/// A number of a compliance item, NaN when absent or null (JSON has no NaN).
double item_number(const json& item, const char* key);

/// True when the item's term was not detected (only an upper bound; older files lack the key).
bool undetected(const json& item);

/// "gyro white noise x": a compliance row's name. An accelerometer's K and R are named after
/// acceleration (IEEE 1293), as in `fit`, not "rate random walk".
std::string item_label(const json& item);

/// The rendered plots of one report.
struct PlotSet {
  std::map<std::string, std::string> files;  ///< name -> content (in the chosen format)
  std::map<std::string, std::string> svgs;   ///< name -> inline SVG
  std::vector<std::string> warnings;         ///< plots that could not be drawn, and why
};

/// Renders every plot (ADEV, PSD per sensor, dynamic ADEV per channel, the compliance chart)
/// twice when needed: SVG for the HTML, and the requested file format. A plot gnuplot cannot
/// draw becomes a warning; no gnuplot, or options.plots false, gives no plots.
PlotSet render_plots(const json& results, const ReportOptions& options);

}  // namespace sigmatau::report_detail
