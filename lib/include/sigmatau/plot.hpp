#pragma once
/// \file plot.hpp
/// Plots: sigmatau writes the data files and runs gnuplot on the editable templates in plots/
/// (found with resource_dir("plots")). The plot file is written atomically.

#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace sigmatau {

enum class PlotFormat { svg, png, pdf };

/// "svg" | "png" | "pdf"; throws Error otherwise.
PlotFormat parse_plot_format(std::string_view text);
/// The format a file name asks for by its extension (.svg/.png/.pdf), else Error.
PlotFormat plot_format_for(const std::filesystem::path& path);

/// One curve with an optional band (empty low/high: no band).
struct PlotCurve {
  std::string name;
  std::string color;  ///< "#rrggbb"; empty: the palette colour of its index
  std::vector<double> x;
  std::vector<double> y;
  std::vector<double> low;
  std::vector<double> high;
};

/// ADEV-style plot: log-log curves of deviation against tau with confidence bands, plus dashed
/// lines (fitted model, each fitted term's asymptote, data-sheet lines) and marked points
/// (read-off points).
struct DeviationPlot {
  std::string title;
  std::string y_label;  ///< with its unit, e.g. "OADEV [deg/h]"
  std::vector<PlotCurve> curves;
  std::vector<PlotCurve> lines;    ///< drawn dashed, no band; name "" = no key entry
  std::vector<PlotCurve> markers;  ///< drawn as open points
};

/// Compliance chart: one row per checked parameter, measured / limit with its interval.
struct ComplianceRow {
  std::string label;
  double ratio = 0;        ///< estimate / limit
  double ratio_low = 0;    ///< lower bound / limit
  double ratio_high = 0;   ///< upper bound / limit
  std::string verdict;     ///< "pass" | "marginal" | "fail" | "inconclusive"
  /// false: the fit left the term out and only ratio_high (its one-sided upper bound / limit)
  /// is known; drawn as an arrow pointing left from the bound, not as a point.
  bool detected = true;
};
struct CompliancePlot {
  std::string title;
  /// What the bars and arrows are, shown under "measured / data-sheet limit" on the x axis; it
  /// should name the intervals' confidence level. Empty: "bar: confidence interval".
  std::string caption;
  std::vector<ComplianceRow> rows;
};

/// The x range of the compliance chart: every positive ratio and its interval, the tip of each
/// bound's arrow (bound / 1.8, compliance.gp), and always the limit line at 1, with a margin of
/// 1.5x on each side (log axis). Autoscaling put the axis
/// start at 1 when every item failed, so the limit line sat on the frame. When that holds no
/// labelled tick but 1 (every ratio within 0.75-1.33: the labels are 1-2-5 steps), it is
/// widened on the nearer side to show 0.5 or 2 as well.
std::pair<double, double> compliance_x_range(const CompliancePlot& plot);

/// PSD plot: log-log curves against frequency, with dashed lines (e.g. the noise density as a
/// one-sided PSD level over its band, the data sheet's level).
struct SpectrumPlot {
  std::string title;
  std::string y_label;
  std::vector<PlotCurve> curves;
  std::vector<PlotCurve> lines;
};

/// The y range of a log-log plot (deviation or PSD): every positive, finite y of the curves,
/// their bands, the lines and the markers, widened outward to whole decades and spanning at
/// least one, so that at least two labelled ticks (10^k) show. A curve spanning less than a
/// decade (a white-noise PSD) otherwise got one tick label, or several reading the same 10^k.
/// {0, 0} when there is no such point (gnuplot then autoscales). The templates (adev.gp,
/// psd.gp) also label the 2 and 5 steps of a range of a single decade.
std::pair<double, double> decade_y_range(const DeviationPlot& plot);
std::pair<double, double> decade_y_range(const SpectrumPlot& plot);

/// True when a `gnuplot` executable is on PATH.
bool gnuplot_available();

/// Render to `output` (format from its extension). Throws Error when gnuplot is missing
/// ("gnuplot not found; install it with: apt-get install gnuplot-nox"), fails, or the file
/// exists and `overwrite` is false. Points with a non-positive or non-finite value are left out
/// (log axes).
void render_deviation_plot(const DeviationPlot& plot, const std::filesystem::path& output,
                           bool overwrite);
void render_spectrum_plot(const SpectrumPlot& plot, const std::filesystem::path& output,
                          bool overwrite);
void render_compliance_plot(const CompliancePlot& plot, const std::filesystem::path& output,
                            bool overwrite);

}  // namespace sigmatau
