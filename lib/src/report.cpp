// results.json -> summary.md, report.html (inline SVG) and plot files. Presentation only: every
// number comes from results.json; units are converted for display with units.hpp. The plots are
// built in report_plots.cpp, the helpers both share in report_common.cpp.
#include "sigmatau/report.hpp"

#include <nlohmann/json.hpp>
#include <unistd.h>

#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "report_common.hpp"
#include "sigmatau/compliance.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/fit.hpp"
#include "sigmatau/output_file.hpp"
#include "sigmatau/units.hpp"

namespace sigmatau {
namespace {

using namespace report_detail;

/// True when some checked compliance item was judged against a typical value (no max printed).
bool typical_limit_used(const json& compliance) {
  for (const auto& item : compliance["items"]) {
    if (item.value("verdict", "") != "not specified" && item.value("limit_is_typical", false)) {
      return true;
    }
  }
  return false;
}

/// The verdict rule, said under each compliance table, with how strong a pass is.
std::string verdict_rule(const json& results) {
  const double confidence = results.value("confidence", 0.683);
  const std::string note = gate_confidence_note(confidence);
  return "pass: the upper bound of the " + fmt(100 * confidence, 3) +
         " % interval is within the limit; marginal: the estimate is within the limit but its "
         "bound is not; fail: the estimate exceeds the limit; " + kWithinUncertaintyNote + "." +
         (note.empty() ? std::string() : " " + note);
}

/// True when some compliance row rests on a rejected fit (see compliance.hpp, fit_rejected).
bool any_fit_rejected(const json& compliance) {
  for (const auto& item : compliance["items"]) {
    if (item.value("fit_rejected", false)) return true;
  }
  return false;
}

/// True when some compliance row is a curve read-out (compliance.hpp, from_curve_readings).
bool any_curve_reading(const json& compliance) {
  for (const auto& item : compliance["items"]) {
    if (item.value("from_curve_readings", false)) return true;
  }
  return false;
}

/// The verdict cell: "fail", "fail (within uncertainty)", "pass (fit rejected, p = 0)".
std::string verdict_cell(const json& item) {
  return verdict_text(item.value("verdict", ""), item.value("within_uncertainty", false),
                      item_number(item, "fit_p_value"), item.value("from_curve_readings", false));
}

/// Channels whose joint fit was rejected (p below kMisfitPValue), in results.json's order.
std::vector<std::string> rejected_fits(const json& results) {
  std::vector<std::string> names;
  if (!results.contains("fit") || !results["fit"].contains("channels")) return names;
  for (const auto& fit : results["fit"]["channels"]) {
    if (fit.contains("p_value") && fit["p_value"].is_number() &&
        fit["p_value"].get<double>() < kMisfitPValue) {
      names.push_back(fit.value("name", "?"));
    }
  }
  return names;
}

/// Warnings that say the declared unit is implausible (data_checks.hpp): the channels they name.
std::vector<std::string> implausible_units(const std::vector<std::string>& warnings) {
  std::vector<std::string> names;
  for (const auto& w : warnings) {
    if (w.find("the data look like") == std::string::npos &&
        w.find("is not near 1 g") == std::string::npos) {
      continue;
    }
    names.push_back(w.substr(0, w.find(':')));
  }
  return names;
}

/// Channels with an outlier warning (data_checks.hpp: "<channel>: N samples beyond k robust
/// sigma of their ...").
std::vector<std::string> outlier_channels(const std::vector<std::string>& warnings) {
  std::vector<std::string> names;
  for (const auto& w : warnings) {
    if (w.find(" robust sigma of their ") == std::string::npos) continue;
    names.push_back(w.substr(0, w.find(':')));
  }
  return names;
}

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const auto& n : names) text += (text.empty() ? "" : ", ") + n;
  return text;
}

/// The banner at the top of the report when there are warnings: their count and the most
/// serious kinds (a rejected fit, implausible units), in plain text (the caller escapes it).
std::string warning_banner(const json& results, const std::vector<std::string>& warnings) {
  std::string text = std::to_string(warnings.size()) + (warnings.size() == 1 ? " warning" : " warnings");
  const auto rejected = rejected_fits(results);
  const auto units = implausible_units(warnings);
  if (!rejected.empty()) {
    text += "; fit rejected for " + joined(rejected) +
            ": no model of the noise terms describes the curve (p < 0.001), so their terms, "
            "the filter values and any verdict from them are not to be trusted";
  }
  if (!units.empty()) {
    text += "; implausible units for " + joined(units) +
            ": the values look like another unit, so every number from them is off by that factor";
  }
  if (const auto spikes = outlier_channels(warnings); !spikes.empty()) {
    text += "; outliers in " + joined(spikes) +
            ": they raise the short-tau deviation and N, and nothing was removed";
  }
  return text + ".";
}

/// The measured side of a compliance row in the limit's printed unit, with its interval:
/// "0.007001 [0.006994, 0.007008] °/s/√Hz", "0.664 B = 8.18 [7.72, 8.71] °/h" (the floor the
/// sheet prints), "< 1.044 °/h" for a term not detected. SI when the unit does not convert.
std::string measured_cell(const json& item) {
  const std::string unit = item.value("limit_unit", "");
  double factor = 1;
  std::string shown = unit;
  try {
    factor = unit.empty() ? 1 : parse_unit(unit).factor;
  } catch (const Error&) {
    shown.clear();
  }
  if (shown.empty()) shown = "SI";
  const std::string quantity = item.value("quantity", "");
  const std::string prefix = quantity == "bias_instability" ? "0.664 B " : "";
  const bool magnitude = quantity != "white_noise" && quantity != "bias_instability" &&
                         quantity != "rate_random_walk";
  if (!undetected(item) && !item.contains("compared")) return "";  // an older file
  if (undetected(item)) {
    return "not detected: " + prefix + "< " + fmt(item_number(item, "compared_upper") / factor) + " " + shown;
  }
  std::string text = (prefix.empty() ? "" : prefix + "= ") + (magnitude ? "|x| " : "") +
                     fmt(item_number(item, "compared") / factor);
  if (item.contains("compared_low")) {
    text += " [" + fmt(item_number(item, "compared_low") / factor) + ", " +
            fmt(item_number(item, "compared_upper") / factor) + "]";
  }
  return text + " " + shown;
}

/// Under the summary table: B beside the floor a data sheet prints (a STIM300 at its typical
/// 0.5 deg/h fits as B = 0.75 deg/h, which read as 50 % over the sheet).
constexpr const char* kBiasFloorNote =
    "B is the bias-instability coefficient; data sheets print its ADEV floor 0.664 B as the bias "
    "stability, and the compliance rows compare that floor.";

/// Said under a compliance table with an inconclusive item.
constexpr const char* kInconclusiveNote =
    "Inconclusive: the fit did not detect the term, and its upper bound exceeds the limit, so "
    "this log can neither pass nor fail it; a longer log bounds it more tightly. A term not "
    "detected whose bound is within the limit passes.";

bool any_inconclusive(const json& compliance) {
  for (const auto& item : compliance["items"]) {
    if (item.value("verdict", "") == "inconclusive") return true;
  }
  return false;
}

/// The limit as printed, with how it was scaled for the comparison when it was ("/√2" for a
/// one-sided density, "×2" for a per-axis misalignment against an axis pair).
std::string limit_cell(const json& item) {
  const std::string text = item.value("limit_text", "");
  if (text.empty()) return "";  // not specified: no limit
  const std::string scaled = item.value("limit_factor_text", "");
  const std::string kind = !item.contains("limit_is_typical") ? ""
                           : item.value("limit_is_typical", false) ? " (typ)"
                                                                   : " (max)";
  return text + (scaled.empty() ? "" : " " + scaled) + kind;
}

/// A term the fit measured but the sheet does not print: its value and interval in the usual
/// data-sheet unit (the row used to be empty).
std::string unspecified_measurement(const json& item) {
  const DisplayUnits u = display_units(item.value("sensor", ""));
  const std::string quantity = item.value("quantity", "");
  const std::string unit = quantity == "white_noise"        ? u.white
                           : quantity == "bias_instability" ? u.bias
                           : quantity == "rate_random_walk" ? u.walk
                                                            : std::string();
  if (!item.contains("value") || !item["value"].is_number()) return "";
  // B is shown as the floor 0.664 B a sheet would print, beside the other rows' floors.
  const double scale = quantity == "bias_instability" ? kFlickerFloorFactor : 1.0;
  std::string text = (scale != 1.0 ? "0.664 B = " : "") + fmt(scale * in_unit(item["value"].get<double>(), unit));
  if (item.contains("ci_low") && item.contains("ci_high") && item["ci_low"].is_number() &&
      item["ci_high"].is_number()) {
    text += " [" + fmt(scale * in_unit(item["ci_low"].get<double>(), unit)) + ", " +
            fmt(scale * in_unit(item["ci_high"].get<double>(), unit)) + "]";
  }
  return text + (unit.empty() ? " (SI)" : " " + unit) + " measured; the sheet prints no limit";
}

/// The "measured / limit" cell of the compliance tables.
std::string margin_cell(const json& item) {
  if (item.value("verdict", "") == "not specified") return "";
  if (undetected(item)) return "< " + format_ratio(item_number(item, "margin_upper")) + " (not detected)";
  if (!item.contains("margin")) return "";
  const std::string estimate = format_ratio(item_number(item, "margin"));
  const std::string upper = format_ratio(item_number(item, "margin_upper"));
  // Older files have no lower bound: the upper one alone.
  if (!item.contains("margin_low")) return estimate + " (upper " + upper + ")";
  return estimate + " [" + format_ratio(item_number(item, "margin_low")) + ", " + upper + "]";
}

std::string verdict_class(const std::string& verdict) {
  if (verdict == "pass") return "pass";
  if (verdict == "marginal") return "marginal";
  if (verdict == "fail") return "fail";
  if (verdict == "inconclusive") return "inconclusive";
  return "na";
}

/// " (floor 0.664 B = 8.18 [7.72, 8.71])", or " (floor 0.664 B < 1.04)" for a bound: B's ADEV
/// floor, the figure a data sheet prints as bias stability, in B's unit.
std::string floor_text(const json& b, const std::string& unit) {
  const double f = kFlickerFloorFactor;
  if (b.contains("value")) {
    return " (floor 0.664 B = " + fmt(f * in_unit(b["value"].get<double>(), unit)) + " [" +
           fmt(f * in_unit(b["ci_low"].get<double>(), unit)) + ", " +
           fmt(f * in_unit(b["ci_high"].get<double>(), unit)) + "])";
  }
  if (b.contains("upper_bound") && b["upper_bound"].is_number()) {
    return " (floor 0.664 B < " + fmt(f * in_unit(b["upper_bound"].get<double>(), unit), 4) + ")";
  }
  return "";
}

/// Whether any channel's fit keeps `term` ("Q", "R"): the parameter table shows its column then.
bool any_fit_keeps(const json& results, const char* term) {
  if (!results.contains("fit") || !results["fit"].contains("channels")) return false;
  for (const auto& fit : results["fit"]["channels"]) {
    if (fit.contains("parameters") && fit["parameters"].contains(term) &&
        fit["parameters"][term].contains("value")) {
      return true;
    }
  }
  return false;
}

/// A table as plain text cells, rendered alike to summary.md and report.html.
struct TextTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;
};

/// The per-channel parameter table: the channel, its fitted N, B, K (Q and R when some channel
/// keeps them) in data-sheet units, and the noise density read from its PSD.
TextTable parameter_table(const json& results) {
  const bool spec = results.contains("compliance") && !results["compliance"].is_null();
  std::vector<const char*> terms = {"N", "B", "K"};
  for (const char* optional : {"Q", "R"}) {
    if (any_fit_keeps(results, optional)) terms.push_back(optional);
  }
  TextTable table;
  table.header = {"channel"};
  table.header.insert(table.header.end(), terms.begin(), terms.end());
  table.header.push_back("noise density (PSD)");
  for (const auto& channel : results["channels"]) {
    const DisplayUnits u = display_units(channel.value("sensor", ""));
    const std::map<std::string, std::string> units = {
        {"N", u.white}, {"B", u.bias}, {"K", u.walk}, {"Q", u.quantization}, {"R", u.ramp}};
    const json* fit = find_fit(results, channel.value("name", ""));
    std::vector<std::string> row = {channel.value("name", "")};
    for (const char* key : terms) {
      std::string text;
      if (fit && fit->contains("parameters") && (*fit)["parameters"].contains(key)) {
        text = parameter_text((*fit)["parameters"][key], units.at(key));
        // With a data sheet, B also as the floor the sheet prints, so the number beside the
        // verdict is the one compared (a coefficient of 12.3 deg/h read as 54 % over a sheet's
        // 8 deg/h).
        if (spec && std::string(key) == "B" && !text.empty()) text += floor_text((*fit)["parameters"]["B"], u.bias);
      }
      row.push_back(text);
    }
    std::string density;
    if (channel.contains("psd") && channel["psd"].contains("noise_density")) {
      density = parameter_text(channel["psd"]["noise_density"], u.density);
    }
    row.push_back(density);
    table.rows.push_back(std::move(row));
  }
  return table;
}

std::string markdown_table(const TextTable& table) {
  std::ostringstream md;
  md << "|";
  for (const auto& cell : table.header) md << " " << cell << " |";
  md << "\n|";
  for (std::size_t i = 0; i < table.header.size(); ++i) md << "---|";
  md << "\n";
  for (const auto& row : table.rows) {
    md << "|";
    for (const auto& cell : row) md << " " << cell << " |";
    md << "\n";
  }
  return md.str();
}

std::string html_table(const TextTable& table) {
  std::ostringstream h;
  h << "<table><tr>";
  for (const auto& cell : table.header) h << "<th>" << html_escape(cell) << "</th>";
  h << "</tr>\n";
  for (const auto& row : table.rows) {
    h << "<tr>";
    for (const auto& cell : row) h << "<td>" << html_escape(cell) << "</td>";
    h << "</tr>\n";
  }
  h << "</table>";
  return h.str();
}

std::string summary_markdown(const json& results, const std::map<std::string, std::string>& filter_files,
                             const std::vector<std::string>& warnings) {
  std::ostringstream md;
  const json& input = results["input"];
  md << "# sigmatau report\n\n";
  if (!warnings.empty()) {
    md << "> **Warning:** " << warning_banner(results, warnings) << " See [Warnings](#warnings).\n\n";
  }
  md << "- input: `" << input.value("path", "") << "` (" << input.value("samples", 0) << " samples at "
     << fmt(input.value("rate_hz", 0.0)) << " Hz, " << fmt(input.value("duration_s", 0.0) / 3600.0, 3)
     << " h)\n";
  if (input.contains("trim")) md << "- warm-up: " << input["trim"].value("reason", "") << "\n";
  if (results.contains("compliance") && !results["compliance"].is_null()) {
    md << "- data sheet: " << results["compliance"]["spec"].value("manufacturer", "") << " "
       << results["compliance"]["spec"].value("part", "") << ": **"
       << results["compliance"].value("verdict", "") << "**"
       << (typical_limit_used(results["compliance"]) ? std::string(" (") + kTypicalLimitNote + ")" : "")
       << "\n";
  }
  md << "\n" << markdown_table(parameter_table(results));
  md << "\n" << kBiasFloorNote << "\n";
  if (results.contains("compliance") && !results["compliance"].is_null()) {
    md << "\n| parameter | verdict | measured [interval] | limit | measured / limit [interval] |\n"
          "|---|---|---|---|---|\n";
    for (const auto& item : results["compliance"]["items"]) {
      const bool specified = item.value("verdict", "") != "not specified";
      md << "| " << item_label(item) << " | " << verdict_cell(item) << " | "
         << (specified ? measured_cell(item) : unspecified_measurement(item)) << " | "
         << limit_cell(item) << " | " << margin_cell(item) << " |\n";
    }
    md << "\n" << verdict_rule(results) << "\n";
    if (any_fit_rejected(results["compliance"])) md << "\n" << kFitRejectedNote << ".\n";
    if (any_curve_reading(results["compliance"])) md << "\n" << kCurveReadingNote << ".\n";
    if (any_inconclusive(results["compliance"])) md << "\n" << kInconclusiveNote << "\n";
  }
  md << filter_section_markdown(results, filter_files);
  if (!warnings.empty()) {
    md << "\n## Warnings\n";
    for (const auto& w : warnings) md << "- " << w << "\n";
  }
  md << "\nGenerated by sigmatau " << results.value("version", "") << "; all numbers in results.json (SI).\n";
  return md.str();
}

constexpr const char* kStyle = R"css(
body{font-family:Helvetica,Arial,sans-serif;max-width:1150px;margin:2em auto;padding:0 1em;color:#222}
h1{font-size:1.8em;margin-bottom:.2em}h2{border-bottom:2px solid #ddd;padding-bottom:.2em;margin-top:1.6em}
table{border-collapse:collapse;margin:.6em 0;font-size:.95em}td,th{border:1px solid #ccc;padding:.3em .6em;text-align:left}
th{background:#f3f3f3}.pass{background:#dff3df}.marginal{background:#fff1cc}.fail{background:#f8d7d7}.inconclusive{background:#e4e8f0}.na{color:#888}
.verdict{font-size:1.3em;font-weight:bold;padding:.3em .8em;display:inline-block;border-radius:4px}
.plot svg{width:100%;height:auto}
pre{background:#f7f7f7;padding:.8em;font-size:.85em;white-space:pre-wrap;overflow-wrap:anywhere}
pre.lines>span{display:block}
.files{margin:.6em 0 1em}.file{margin:.25em 0}.file summary{cursor:pointer}.file pre{margin:.3em 0 .8em}
.file.missing{background:#f8d7d7;padding:.2em .4em}
.muted{color:#666;font-size:.9em}
.banner{background:#fff1cc;border:2px solid #e6a000;border-radius:4px;padding:.6em .9em;margin:1em 0})css";

std::string report_html(const json& results, const PlotSet& plots,
                        const std::map<std::string, std::string>& filter_files,
                        const std::vector<std::string>& warnings) {
  std::ostringstream h;
  const json& input = results["input"];
  h << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>sigmatau report: "
    << html_escape(input.value("path", "")) << "</title><style>" << kStyle << "</style></head><body>\n";
  h << "<h1>sigmatau report</h1><p class=\"muted\">" << html_escape(input.value("path", ""))
    << " &middot; sigmatau " << html_escape(results.value("version", "")) << " &middot; "
    << html_escape(results.value("created_utc", "")) << "</p>\n";

  if (!warnings.empty()) {
    h << "<div class=\"banner\" id=\"warning-banner\"><strong>Warning:</strong> "
      << html_escape(warning_banner(results, warnings))
      << " <a href=\"#warnings\">See the warnings.</a></div>\n";
  }

  // Summary and verdict.
  h << "<h2 id=\"summary\">Summary</h2>\n";
  if (results.contains("compliance") && !results["compliance"].is_null()) {
    const std::string verdict = results["compliance"].value("verdict", "");
    h << "<p>Data sheet " << html_escape(results["compliance"]["spec"].value("manufacturer", "")) << " "
      << html_escape(results["compliance"]["spec"].value("part", "")) << ": <span class=\"verdict "
      << verdict_class(verdict == "all pass"       ? "pass"
                       : verdict == "fail"         ? "fail"
                       : verdict == "inconclusive" ? "inconclusive"
                                                   : "marginal")
      << "\">" << html_escape(verdict) << "</span>"
      << (typical_limit_used(results["compliance"])
              ? " <span class=\"muted\">(" + html_escape(kTypicalLimitNote) + ")</span>"
              : std::string())
      << "</p>\n";
  }
  const bool show_q = any_fit_keeps(results, "Q"), show_r = any_fit_keeps(results, "R");
  h << html_table(parameter_table(results)) << "<p class=\"muted\">Intervals at " << fmt(100 * results.value("confidence", 0.683), 3)
    << " % confidence. N: angle/velocity random walk (white noise density, AVAR = N&sup2;/&tau;); "
       "B: bias instability coefficient (data sheets print its ADEV floor 0.664 B as the bias "
       "stability, and the compliance rows compare that floor); K: rate random walk"
    << (show_q ? "; Q: quantization (AVAR = 3 Q&sup2;/&tau;&sup2;)" : "")
    << (show_r ? "; R: rate ramp (AVAR = R&sup2; &tau;&sup2;/2)" : "")
    << ". Terms the data does not support are given as upper bounds (&lt;).</p>\n";
  h << filter_files_line_html(results, filter_files);

  // Compliance.
  if (results.contains("compliance") && !results["compliance"].is_null()) {
    h << "<h2 id=\"compliance\">Data-sheet compliance</h2>\n<table><tr><th>parameter</th><th>verdict</th>"
         "<th>measured [interval]</th><th>limit as printed</th><th>measured / limit [interval]</th>"
         "<th>rule</th></tr>\n";
    for (const auto& item : results["compliance"]["items"]) {
      const std::string verdict = item.value("verdict", "");
      const bool specified = verdict != "not specified";
      h << "<tr class=\"" << verdict_class(verdict) << "\"><td>" << html_escape(item_label(item))
        << "</td><td>" << html_escape(verdict_cell(item)) << "</td><td>"
        // A row the sheet has no limit for: what was measured, and that no limit is printed.
        << html_escape(specified ? measured_cell(item) : unspecified_measurement(item)) << "</td><td>"
        << html_escape(limit_cell(item)) << "</td><td>" << html_escape(margin_cell(item))
        << "</td><td>" << html_escape(item.value("rule", "")) << "</td></tr>\n";
    }
    h << "</table>\n<p class=\"muted\">" << html_escape(verdict_rule(results)) << "</p>\n";
    if (any_fit_rejected(results["compliance"])) {
      h << "<p class=\"muted\">" << html_escape(kFitRejectedNote) << ".</p>\n";
    }
    if (any_curve_reading(results["compliance"])) {
      h << "<p class=\"muted\">" << html_escape(kCurveReadingNote) << ".</p>\n";
    }
    if (any_inconclusive(results["compliance"])) {
      h << "<p class=\"muted\">" << html_escape(kInconclusiveNote) << "</p>\n";
    }
    if (plots.svgs.count("compliance")) h << "<div class=\"plot\">" << plots.svgs.at("compliance") << "</div>\n";
  }

  // Plots.
  h << "<h2 id=\"plots\">Allan deviation and PSD</h2>\n";
  for (const std::string name : {"adev_gyro", "psd_gyro", "adev_accel", "psd_accel"}) {
    if (plots.svgs.count(name)) h << "<div class=\"plot\" id=\"plot-" << name << "\">" << plots.svgs.at(name) << "</div>\n";
  }
  if (plots.svgs.empty()) h << "<p class=\"muted\">No plots (see warnings).</p>\n";
  bool dynamic_heading = false;
  for (const auto& [name, svg] : plots.svgs) {
    if (name.rfind("dynamic_", 0) != 0) continue;
    if (!dynamic_heading) {
      h << "<h2 id=\"dynamic\">Dynamic Allan deviation</h2><p class=\"muted\">OADEV over "
           "half-overlapping windows, early (blue) to late (red): curves that do not coincide "
           "mean the noise changed during the run.</p>\n";
      dynamic_heading = true;
    }
    h << "<div class=\"plot\" id=\"plot-" << name << "\">" << svg << "</div>\n";
  }

  // Filter tuning: the arithmetic and the files written (report_filter.cpp).
  h << filter_section_html(results, filter_files);

  // Provenance.
  h << "<h2 id=\"provenance\">Input and provenance</h2><table>\n";
  h << "<tr><th>file</th><td>" << html_escape(input.value("path", "")) << "</td></tr>\n";
  if (input.contains("bytes")) h << "<tr><th>size</th><td>" << input["bytes"].get<std::int64_t>() << " bytes</td></tr>\n";
  if (input.contains("crc32")) h << "<tr><th>CRC-32</th><td>" << html_escape(input["crc32"].get<std::string>()) << "</td></tr>\n";
  h << "<tr><th>samples</th><td>" << input.value("samples", 0) << "</td></tr>\n";
  h << "<tr><th>rate</th><td>" << fmt(input.value("rate_hz", 0.0), 8) << " Hz</td></tr>\n";
  h << "<tr><th>duration</th><td>" << fmt(input.value("duration_s", 0.0), 6) << " s</td></tr>\n";
  if (input.contains("timing") && !input["timing"].is_null()) {
    const json& t = input["timing"];
    h << "<tr><th>time stamps</th><td>jitter " << fmt(t.value("jitter_s", 0.0), 3) << " s, "
      << t["gaps"].size() << " gaps, " << t.value("non_increasing", 0) << " non-increasing</td></tr>\n";
  }
  if (input.contains("trim")) h << "<tr><th>warm-up</th><td>" << html_escape(input["trim"].value("reason", "")) << "</td></tr>\n";
  h << "<tr><th>tool</th><td>sigmatau " << html_escape(results.value("version", "")) << "</td></tr>\n</table>\n";

  if (!warnings.empty()) {
    h << "<h2 id=\"warnings\">Warnings</h2><ul>\n";
    for (const auto& w : warnings) h << "<li>" << html_escape(w) << "</li>\n";
    h << "</ul>\n";
  }
  h << "</body></html>\n";
  return h.str();
}

}  // namespace

ReportFiles build_report(const std::string& results_json, const ReportOptions& options,
                         const std::map<std::string, std::string>& filter_files) {
  json results;
  try {
    results = json::parse(results_json);
  } catch (const json::parse_error& e) {
    throw Error(std::string("results.json is not valid JSON: ") + e.what());
  }
  if (results.value("tool", "") != "sigmatau" || !results.contains("channels") || !results.contains("input")) {
    throw Error("not a sigmatau analyze result (expected \"tool\": \"sigmatau\", \"input\" and \"channels\")");
  }
  ReportFiles out;
  PlotSet plots;
  try {
    plots = render_plots(results, options);
  } catch (const json::exception& e) {
    throw Error(std::string("results.json has an unexpected layout: ") + e.what());
  }
  std::vector<std::string> warnings;
  if (results.contains("warnings")) {
    for (const auto& w : results["warnings"]) warnings.push_back(w.get<std::string>());
  }
  warnings.insert(warnings.end(), plots.warnings.begin(), plots.warnings.end());
  out.warnings = plots.warnings;
  for (const auto& w : missing_filter_files(results, filter_files)) {
    warnings.push_back(w);
    out.warnings.push_back(w);
  }
  out.files = plots.files;
  out.files["summary.md"] = summary_markdown(results, filter_files, warnings);
  out.files["report.html"] = report_html(results, plots, filter_files, warnings);
  return out;
}

void write_output_directory(const std::filesystem::path& requested, const ReportFiles& files,
                            bool overwrite) {
  write_directory_atomically(requested, files.files, overwrite);
}

}  // namespace sigmatau
