#pragma once
// Private to the report (report.cpp, report_common.cpp, report_plots.cpp, report_filter.cpp):
// what the text tables, the plots and the filter part share when they read results.json. Not
// installed.

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

/// `s` with &, <, > and " escaped for HTML text and attribute values.
std::string html_escape(const std::string& s);

/// `text` (lines indented with spaces: results.json's filter "explain", a filter file) as a
/// <pre> of class "lines `css_class`" that wraps at the page's width: each line, with its newline,
/// escaped in a block <span> whose wrapped continuation is indented past the line's own
/// indentation, so nothing scrolls sideways or is cut off and a wrapped line is not read as a
/// new one. Removing the span tags gives `text` escaped (a copy gives `text`). (report_filter.cpp)
std::string wrapped_lines_html(const std::string& text, const std::string& css_class);

/// The "Filter tuning" section of report.html: per rate of results.json's "filter" section the
/// files written for that rate, each a collapsed <details> whose summary gives its name as
/// written beside report.html, what it is for and its size in bytes, and whose body its text,
/// escaped; then the rate's arithmetic (wrapped_lines_html). A file the section names but `files`
/// (name -> text) lacks is marked missing; a file `files` holds that no rate names is shown last.
/// Empty without either.
std::string filter_section_html(const json& results,
                                const std::map<std::string, std::string>& files);

/// One line for report.html's summary: every filter file by name, each a link to its text under
/// "Filter tuning", a missing one marked; empty when no file is named or given.
std::string filter_files_line_html(const json& results,
                                   const std::map<std::string, std::string>& files);

/// summary.md's "Filter files" part: each file by rate with what it is for, a missing one marked
/// as in filter_section_html. Empty when no file is named or given.
std::string filter_section_markdown(const json& results,
                                    const std::map<std::string, std::string>& files);

/// One warning per file results.json's "filter" section names that `files` lacks.
std::vector<std::string> missing_filter_files(const json& results,
                                              const std::map<std::string, std::string>& files);

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
