// The report's plots: results.json -> ADEV, PSD, dynamic ADEV and compliance plots (plot.hpp),
// in data-sheet display units, rendered with gnuplot (report_common.hpp, render_plots).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

#include "report_common.hpp"
#include "scratch_dir.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/plot.hpp"
#include "sigmatau/units.hpp"

namespace sigmatau::report_detail {
namespace {

std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Strips an XML prolog so an SVG can be inlined in HTML.
std::string inline_svg(std::string svg) {
  const auto start = svg.find("<svg");
  return start == std::string::npos ? svg : svg.substr(start);
}

/// The key of the sheet's white-noise line on an ADEV plot, named after the field the line came
/// from (the compliance item's spec_field: ARW / VRW are preferred to a noise density, as in
/// triad_from_data_sheet), "data sheet white noise" when no item says.
std::string white_line_name(const json& results, const std::string& sensor) {
  if (results.contains("compliance") && results["compliance"].is_object() &&
      results["compliance"].contains("items")) {
    for (const auto& item : results["compliance"]["items"]) {
      if (item.value("sensor", "") != sensor || item.value("quantity", "") != "white_noise") continue;
      const std::string field = item.value("spec_field", "");
      if (field == "angle_random_walk") return "data sheet ARW";
      if (field == "velocity_random_walk") return "data sheet VRW";
      if (field == "noise_density") return "data sheet noise density";
    }
  }
  return "data sheet white noise";
}

/// The colour of a fitted term's asymptote on an ADEV plot: one per term, none of them the
/// channels' (blue, red, green) or the data sheet's lines (black, dark grey).
std::string term_color(const std::string& term) {
  if (term == "N") return "#17becf";  // cyan
  if (term == "B") return "#9467bd";  // purple
  if (term == "K") return "#8c564b";  // brown
  if (term == "Q") return "#e377c2";  // pink
  if (term == "R") return "#bcbd22";  // olive
  // One per Gauss-Markov entry of a sum (analysis_results: "GM1", "GM2", "GM3").
  if (term == "GM1") return "#ff7f0e";  // orange
  if (term == "GM2") return "#c49c00";  // dark yellow
  if (term == "GM3") return "#7b4173";  // plum
  return "#999999";
}

DeviationPlot deviation_plot(const json& results, const std::string& sensor) {
  const DisplayUnits u = display_units(sensor);
  DeviationPlot plot;
  std::set<std::string> keyed_terms;
  std::string statistic = "OADEV";
  std::size_t index = 0;
  for (const auto& channel : results["channels"]) {
    if (channel.value("sensor", "") != sensor || channel["allan"].empty()) continue;
    const json& curve = channel["allan"][0];
    statistic.clear();
    for (char c : curve.value("statistic", std::string("oadev"))) statistic += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    PlotCurve pc;
    pc.name = channel.value("name", "?");
    static const char* kColors[] = {"#1f77b4", "#d62728", "#2ca02c"};
    pc.color = kColors[index % 3];
    for (const auto& p : curve["points"]) {
      if (p["dev"].is_null()) continue;
      pc.x.push_back(p["tau"].get<double>());
      pc.y.push_back(in_unit(p["dev"].get<double>(), u.deviation));
      pc.low.push_back(p["ci_low"].is_null() ? 0.0 : in_unit(p["ci_low"].get<double>(), u.deviation));
      pc.high.push_back(p["ci_high"].is_null() ? 0.0 : in_unit(p["ci_high"].get<double>(), u.deviation));
    }
    plot.curves.push_back(pc);
    if (const json* fit = find_fit(results, pc.name); fit && fit->contains("model_adev")) {
      const json& model = (*fit)["model_adev"];
      PlotCurve line;
      line.name = pc.name + " fit";
      line.color = pc.color;
      line.x = model["tau"].get<std::vector<double>>();
      for (double v : model["adev"].get<std::vector<double>>()) line.y.push_back(in_unit(v, u.deviation));
      plot.lines.push_back(line);
      if (fit->contains("terms_adev")) {
        for (const auto& [term, values] : (*fit)["terms_adev"].items()) {
          PlotCurve t;
          // One colour per term, keyed the first time any channel has it (a K kept only on gz
          // was drawn but had no key entry when the key came from the first channel alone).
          t.name = keyed_terms.insert(term).second ? term + " term" : "";
          t.color = term_color(term);
          t.x = model["tau"].get<std::vector<double>>();
          for (double v : values.get<std::vector<double>>()) t.y.push_back(in_unit(v, u.deviation));
          plot.lines.push_back(t);
        }
      }
      if (fit->contains("readouts")) {
        PlotCurve markers;
        markers.name = keyed_terms.insert("read-off").second ? "read-off points" : "";
        markers.color = pc.color;
        for (const auto& r : (*fit)["readouts"]) {
          markers.x.push_back(r["tau"].get<double>());
          markers.y.push_back(in_unit(r["adev"].get<double>(), u.deviation));
        }
        plot.markers.push_back(markers);
      }
    }
    ++index;
  }
  if (results.contains("spec_lines") && results["spec_lines"].contains(sensor)) {
    const json& lines = results["spec_lines"][sensor];
    std::vector<double> taus;
    if (!plot.curves.empty()) taus = {plot.curves.front().x.front(), plot.curves.front().x.back()};
    if (lines.contains("white") && taus.size() == 2) {
      PlotCurve l;
      l.name = white_line_name(results, sensor);
      l.color = "#000000";
      const double n = lines["white"].get<double>();
      l.x = taus;
      for (double t : taus) l.y.push_back(in_unit(n / std::sqrt(t), u.deviation));
      plot.lines.push_back(l);
    }
    if (lines.contains("bias_floor") && taus.size() == 2) {
      PlotCurve l;
      l.name = "data sheet bias instability";
      l.color = "#555555";
      const double floor = lines["bias_floor"].get<double>();
      l.x = taus;
      l.y = {in_unit(floor, u.deviation), in_unit(floor, u.deviation)};
      plot.lines.push_back(l);
    }
  }
  plot.title = std::string(sensor == "gyro" ? "Gyroscope" : "Accelerometer") + " " + statistic +
               " (" + fmt(100 * results.value("confidence", 0.683), 3) + " % bands)";
  plot.y_label = statistic + " [" + u.deviation + "]";
  return plot;
}

SpectrumPlot spectrum_plot(const json& results, const std::string& sensor) {
  const DisplayUnits u = display_units(sensor);
  SpectrumPlot plot;
  plot.title = std::string(sensor == "gyro" ? "Gyroscope" : "Accelerometer") +
               " PSD (one-sided, Welch)";
  plot.y_label = "PSD [" + u.psd + "]";
  const double psd_factor = parse_unit(u.psd).factor;
  const double density_factor = parse_unit(u.density).factor;
  std::size_t index = 0;
  for (const auto& channel : results["channels"]) {
    if (channel.value("sensor", "") != sensor || !channel.contains("psd")) continue;
    const json& psd = channel["psd"];
    static const char* kColors[] = {"#1f77b4", "#d62728", "#2ca02c"};
    PlotCurve pc;
    pc.name = channel.value("name", "?");
    pc.color = kColors[index % 3];
    pc.x = psd["frequency"].get<std::vector<double>>();
    for (double v : psd["psd"].get<std::vector<double>>()) pc.y.push_back(v / psd_factor);
    plot.curves.push_back(pc);
    if (psd.contains("noise_density")) {
      const json& nd = psd["noise_density"];
      const double level = std::pow(nd["one_sided_asd"].get<double>(), 2) / psd_factor;
      PlotCurve line;
      line.name = pc.name + " N = " + fmt(nd["value"].get<double>() / density_factor, 3) + " " + u.density;
      line.color = pc.color;
      line.x = nd["band_hz"].get<std::vector<double>>();
      line.y = {level, level};
      plot.lines.push_back(line);
    }
    ++index;
  }
  if (results.contains("spec_lines") && results["spec_lines"].contains(sensor) &&
      results["spec_lines"][sensor].contains("white") && !plot.curves.empty()) {
    const double n = results["spec_lines"][sensor]["white"].get<double>();
    PlotCurve line;
    line.name = "data sheet (one-sided level 2 N^2)";
    line.color = "#000000";
    line.x = {plot.curves.front().x.front(), plot.curves.front().x.back()};
    line.y = {2 * n * n / psd_factor, 2 * n * n / psd_factor};
    plot.lines.push_back(line);
  }
  return plot;
}

/// Dynamic ADEV: one curve per time window of one channel, coloured from early (blue) to late
/// (red), so a change of the noise during the run shows as curves that do not coincide.
DeviationPlot dynamic_plot(const json& channel) {
  const DisplayUnits u = display_units(channel.value("sensor", ""));
  DeviationPlot plot;
  plot.title = "Dynamic OADEV of " + channel.value("name", std::string("?")) + " (windows of " +
               fmt(channel["dynamic"].value("window_s", 0.0) / 60.0, 3) + " min)";
  plot.y_label = "OADEV [" + (u.deviation.empty() ? std::string("SI") : u.deviation) + "]";
  const auto& windows = channel["dynamic"]["windows"];
  const std::size_t n = windows.size();
  for (std::size_t w = 0; w < n; ++w) {
    PlotCurve c;
    c.name = fmt(windows[w]["start_s"].get<double>() / 60.0, 3) + "-" +
             fmt(windows[w]["end_s"].get<double>() / 60.0, 3) + " min";
    const double f = n > 1 ? static_cast<double>(w) / static_cast<double>(n - 1) : 0.0;
    char color[8];
    std::snprintf(color, sizeof color, "#%02x%02x%02x", static_cast<int>(40 + 200 * f), 60,
                  static_cast<int>(240 - 200 * f));
    c.color = color;
    c.x = windows[w]["tau"].get<std::vector<double>>();
    for (double v : windows[w]["oadev"].get<std::vector<double>>()) c.y.push_back(in_unit(v, u.deviation));
    plot.curves.push_back(c);
  }
  return plot;
}

CompliancePlot compliance_plot(const json& results) {
  CompliancePlot plot;
  plot.title = "Compliance with " + results["compliance"]["spec"].value("part", std::string("data sheet"));
  plot.caption = "bar: " + fmt(100 * results.value("confidence", 0.683), 3) +
                 " % confidence interval; arrow: a term not detected, at most its upper bound (the arrow's start)";
  for (const auto& item : results["compliance"]["items"]) {
    const std::string verdict = item.value("verdict", "");
    if (verdict == "not specified") continue;
    ComplianceRow row;
    // The label says which limit it is (typ or max) and what the verdict rests on.
    row.label = item_label(item) + (item.value("limit_is_typical", false) ? " (typ)" : " (max)");
    if (item.value("fit_rejected", false)) row.label += ", fit rejected";
    if (item.value("from_curve_readings", false)) row.label += ", read-out";
    row.verdict = verdict;
    if (undetected(item)) {
      // Only a bound: an arrow pointing left from bound / limit.
      row.ratio = row.ratio_low = row.ratio_high = item_number(item, "margin_upper");
      row.detected = false;
      row.label += ", not detected";
      if (std::isfinite(row.ratio)) plot.rows.push_back(row);  // no bound, nothing to draw
      continue;
    }
    row.ratio = item["margin"].get<double>();
    row.ratio_high = item["margin_upper"].get<double>();
    if (item.contains("margin_low") && item["margin_low"].is_number()) {
      row.ratio_low = item["margin_low"].get<double>();
    } else {  // older files: from the interval of the value
      const double value = item["value"].get<double>();
      const double low = item["ci_low"].get<double>();
      row.ratio_low = value != 0 ? row.ratio * std::abs(low / value) : row.ratio;
    }
    if (row.ratio_low > row.ratio) row.ratio_low = row.ratio;
    plot.rows.push_back(row);
  }
  return plot;
}

}  // namespace

/// Renders every plot twice when needed: SVG for the HTML, and the requested file format.
PlotSet render_plots(const json& results, const ReportOptions& options) {
  PlotSet set;
  if (!options.plots) return set;
  if (!gnuplot_available()) {
    set.warnings.push_back("gnuplot not found: plots left out (install it with: apt-get install gnuplot-nox)");
    return set;
  }
  // In $TMPDIR, removed on any exception (a json one from an odd results.json too) and on a
  // signal.
  detail::ScratchDir scratch_dir("sigmatau-report-");
  const std::filesystem::path& scratch = scratch_dir.path();
  const std::string ext = options.plot_format == PlotFormat::svg   ? ".svg"
                          : options.plot_format == PlotFormat::png ? ".png"
                                                                   : ".pdf";
  auto render = [&](const std::string& name, auto&& draw) {
    try {
      draw(scratch / (name + ".svg"));
      set.svgs[name] = inline_svg(read_file(scratch / (name + ".svg")));
      if (options.plot_format == PlotFormat::svg) {
        set.files[name + ext] = read_file(scratch / (name + ".svg"));
      } else {
        draw(scratch / (name + ext));
        set.files[name + ext] = read_file(scratch / (name + ext));
      }
    } catch (const Error& e) {
      set.warnings.push_back("plot " + name + " failed: " + e.what());
    }
  };
  for (const std::string sensor : {"gyro", "accel"}) {
    bool present = false;
    for (const auto& c : results["channels"]) present = present || c.value("sensor", "") == sensor;
    if (!present) continue;
    const DeviationPlot adev = deviation_plot(results, sensor);
    if (!adev.curves.empty()) {
      render("adev_" + sensor, [&](const std::filesystem::path& p) { render_deviation_plot(adev, p, true); });
    }
    const SpectrumPlot psd = spectrum_plot(results, sensor);
    if (!psd.curves.empty()) {
      render("psd_" + sensor, [&](const std::filesystem::path& p) { render_spectrum_plot(psd, p, true); });
    }
  }
  for (const auto& channel : results["channels"]) {
    if (!channel.contains("dynamic") || channel["dynamic"]["windows"].empty()) continue;
    const DeviationPlot plot = dynamic_plot(channel);
    render("dynamic_" + channel.value("name", std::string("channel")),
           [&](const std::filesystem::path& p) { render_deviation_plot(plot, p, true); });
  }
  if (results.contains("compliance") && !results["compliance"].is_null()) {
    const CompliancePlot chart = compliance_plot(results);
    if (!chart.rows.empty()) {
      render("compliance", [&](const std::filesystem::path& p) { render_compliance_plot(chart, p, true); });
    }
  }
  return set;
}

}  // namespace sigmatau::report_detail
