// Driving gnuplot: data files in a private temporary directory, variables passed with -e,
// output rendered to a temporary file and moved into place atomically.
#include "sigmatau/plot.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <random>
#include <sstream>
#include <vector>

#include "sigmatau/error.hpp"
#include "sigmatau/output_file.hpp"
#include "sigmatau/resources.hpp"
#include "sigmatau/text_encoding.hpp"
#include "scratch_dir.hpp"

extern char** environ;

namespace sigmatau {
namespace {

/// Text for a plot: UTF-8 (what the SVG, PNG and PDF terminals write), a name that is not
/// read as Windows-1252 (text_encoding.hpp) so that the SVG stays well-formed XML.
std::string plot_text(std::string_view text) {
  return is_utf8(text) ? std::string(text) : utf8_from_windows1252(text);
}

/// A gnuplot single-quoted string literal ('' stands for one quote).
std::string gnuplot_string(std::string_view raw) {
  const std::string text = plot_text(raw);
  std::string s = "'";
  for (char c : text) {
    if (c == '\'') s += "''";
    else if (c == '\n') s += ' ';
    else s += c;
  }
  return s + "'";
}

/// A number for gnuplot -e, as a float literal (gnuplot divides integers as integers).
std::string gnuplot_number(double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.10e", value);
  return text;
}

std::string terminal_for(PlotFormat format) {
  switch (format) {
    case PlotFormat::svg: return "svg";
    case PlotFormat::png: return "pngcairo";
    case PlotFormat::pdf: return "pdfcairo";
  }
  return "svg";
}

using detail::ScratchDir;

/// The palette for curves without their own colour (colour-blind-safe "tab10" order).
constexpr const char* kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                    "#9467bd", "#8c564b", "#e377c2", "#17becf"};

std::string colors_of(const std::vector<PlotCurve>& curves) {
  std::string colors;
  for (std::size_t i = 0; i < curves.size(); ++i) {
    if (!colors.empty()) colors += ' ';
    colors += curves[i].color.empty() ? kPalette[i % std::size(kPalette)] : curves[i].color;
  }
  return colors.empty() ? "#000000" : colors;
}

/// One block per curve: a quoted title line, then "x y [low high]" rows; points that a log axis
/// cannot show are left out.
void write_blocks(const std::filesystem::path& file, const std::vector<PlotCurve>& curves,
                  bool with_band) {
  std::ofstream out(file);
  out.precision(10);
  for (const auto& curve : curves) {
    std::string title;
    for (char c : plot_text(curve.name)) title += (c == '"' || c == '\\' || c == '\n') ? ' ' : c;
    out << '"' << title << "\"" << (with_band ? " 0 0 0" : " 0") << '\n';
    for (std::size_t i = 0; i < curve.x.size(); ++i) {
      const double x = curve.x[i], y = curve.y[i];
      if (!(x > 0 && y > 0 && std::isfinite(x) && std::isfinite(y))) continue;
      out << x << ' ' << y;
      if (with_band) {
        const bool has_band = i < curve.low.size() && i < curve.high.size() &&
                              curve.low[i] > 0 && std::isfinite(curve.high[i]);
        out << ' ' << (has_band ? curve.low[i] : y) << ' ' << (has_band ? curve.high[i] : y);
      }
      out << '\n';
    }
    out << "\n\n";
  }
  if (!out) throw Error("cannot write plot data to " + file.string());
}

void run_gnuplot(const std::string& script_name, const std::string& assignments,
                 const std::filesystem::path& rendered, ScratchDir& scratch) {
  if (!gnuplot_available()) {
    throw Error("gnuplot not found; install it with: apt-get install gnuplot-nox");
  }
  const auto script = resource_dir("plots") / script_name;
  if (!std::filesystem::exists(script)) throw Error("plot template missing: " + script.string());
  const auto log = scratch.file("gnuplot.log");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  std::string program = "gnuplot";
  std::string flag = "-e";
  std::string script_path = script.string();
  char* argv[] = {program.data(), flag.data(), const_cast<char*>(assignments.c_str()),
                  script_path.data(), nullptr};
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) throw Error("cannot run gnuplot: " + std::string(std::strerror(spawned)));
  {
    // Killed on a signal, so that it writes nothing into the scratch directory after it was
    // removed. Waited for without reaping: the table lets go of the PID while the child is a
    // zombie, whose PID no other process can have yet.
    const KillOnInterrupt child(pid);
    siginfo_t info{};
    while (::waitid(P_PID, static_cast<id_t>(pid), &info, WEXITED | WNOWAIT) != 0 &&
           errno == EINTR) {
    }
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  std::ifstream in(log);
  std::string messages((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !std::filesystem::exists(rendered)) {
    throw Error("gnuplot failed on " + script.string() + ": " + messages.substr(0, 400));
  }
}

/// "; ymin=...; ymax=..." for a y range, "" for {0, 0} (the template then autoscales).
std::string y_range_assignments(const std::pair<double, double>& range) {
  if (!(range.first > 0 && range.second > range.first)) return "";
  return "; ymin=" + gnuplot_number(range.first) + "; ymax=" + gnuplot_number(range.second);
}

void move_into_place(const std::filesystem::path& rendered, const std::filesystem::path& output,
                     bool overwrite) {
  std::ifstream in(rendered, std::ios::binary);
  std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  write_file_atomically(output, content, overwrite);
}

}  // namespace

PlotFormat parse_plot_format(std::string_view text) {
  if (text == "svg") return PlotFormat::svg;
  if (text == "png") return PlotFormat::png;
  if (text == "pdf") return PlotFormat::pdf;
  throw Error("unknown plot format \"" + std::string(text) + "\"; expected svg, png or pdf");
}

PlotFormat plot_format_for(const std::filesystem::path& path) {
  const auto ext = path.extension().string();
  if (ext.size() < 2) throw Error(path.string() + ": plot file name needs .svg, .png or .pdf");
  return parse_plot_format(ext.substr(1));
}

bool gnuplot_available() {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::stringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (!dir.empty() && ::access((std::filesystem::path(dir) / "gnuplot").c_str(), X_OK) == 0) return true;
  }
  return false;
}

void render_deviation_plot(const DeviationPlot& plot, const std::filesystem::path& output,
                           bool overwrite) {
  const PlotFormat format = plot_format_for(output);
  check_can_write(output, overwrite);
  if (plot.curves.empty()) throw Error("nothing to plot");
  ScratchDir scratch;
  const auto data = scratch.file("adev.dat");
  const auto lines = scratch.file("lines.dat");
  const auto markers = scratch.file("markers.dat");
  const auto rendered = scratch.file("plot" + output.extension().string());
  write_blocks(data, plot.curves, true);
  write_blocks(lines, plot.lines, false);
  write_blocks(markers, plot.markers, false);
  const std::string assignments =
      "datafile=" + gnuplot_string(data.string()) + "; linefile=" + gnuplot_string(lines.string()) +
      "; markerfile=" + gnuplot_string(markers.string()) +
      "; outfile=" + gnuplot_string(rendered.string()) +
      "; term=" + gnuplot_string(terminal_for(format)) + "; title_text=" + gnuplot_string(plot.title) +
      "; ylabel_text=" + gnuplot_string(plot.y_label) +
      "; nchannels=" + std::to_string(plot.curves.size()) + "; colors=" + gnuplot_string(colors_of(plot.curves)) +
      "; nlines=" + std::to_string(plot.lines.size()) + "; linecolors=" + gnuplot_string(colors_of(plot.lines)) +
      "; nmarkers=" + std::to_string(plot.markers.size()) +
      "; markercolors=" + gnuplot_string(colors_of(plot.markers)) + y_range_assignments(decade_y_range(plot));
  run_gnuplot("adev.gp", assignments, rendered, scratch);
  move_into_place(rendered, output, overwrite);
}

void render_spectrum_plot(const SpectrumPlot& plot, const std::filesystem::path& output,
                          bool overwrite) {
  const PlotFormat format = plot_format_for(output);
  check_can_write(output, overwrite);
  if (plot.curves.empty()) throw Error("nothing to plot");
  ScratchDir scratch;
  const auto data = scratch.file("psd.dat");
  const auto lines = scratch.file("lines.dat");
  const auto rendered = scratch.file("plot" + output.extension().string());
  write_blocks(data, plot.curves, false);
  write_blocks(lines, plot.lines, false);
  const std::string assignments =
      "datafile=" + gnuplot_string(data.string()) + "; linefile=" + gnuplot_string(lines.string()) +
      "; outfile=" + gnuplot_string(rendered.string()) +
      "; term=" + gnuplot_string(terminal_for(format)) + "; title_text=" + gnuplot_string(plot.title) +
      "; ylabel_text=" + gnuplot_string(plot.y_label) +
      "; nchannels=" + std::to_string(plot.curves.size()) + "; colors=" + gnuplot_string(colors_of(plot.curves)) +
      "; nlines=" + std::to_string(plot.lines.size()) + "; linecolors=" + gnuplot_string(colors_of(plot.lines)) +
      y_range_assignments(decade_y_range(plot));
  run_gnuplot("psd.gp", assignments, rendered, scratch);
  move_into_place(rendered, output, overwrite);
}

std::pair<double, double> compliance_x_range(const CompliancePlot& plot) {
  constexpr double kMargin = 1.5;
  // compliance.gp draws a bound as an arrow from the bound to bound / 1.8 (its `shaft`).
  constexpr double kBoundArrowTip = 1 / 1.8;
  double low = 1, high = 1;  // the limit line is always in view
  for (const auto& r : plot.rows) {
    const double tip = r.detected ? r.ratio_high : r.ratio_high * kBoundArrowTip;
    for (const double v : {r.ratio, r.ratio_low, r.ratio_high, tip}) {
      if (!(v > 0) || !std::isfinite(v)) continue;
      low = std::min(low, v);
      high = std::max(high, v);
    }
  }
  low /= kMargin;
  high *= kMargin;
  // The labels nearest 1 (compliance.gp) are 0.5 and 2: show one of them, with a little room so
  // that its label is not on the frame.
  constexpr double kBelow = 0.5, kAbove = 2, kRoom = 1.1;
  if (low > kBelow && high < kAbove) {
    if (low / kBelow <= kAbove / high) {
      low = kBelow / kRoom;
    } else {
      high = kAbove * kRoom;
    }
  }
  return {low, high};
}

namespace {

/// Extends [low, high] by the positive, finite values of `values`.
void extend(double& low, double& high, const std::vector<double>& values) {
  for (const double v : values) {
    if (!(v > 0) || !std::isfinite(v)) continue;
    low = std::min(low, v);
    high = std::max(high, v);
  }
}

/// [low, high] widened outward to powers of ten, at least one decade apart; {0, 0} when empty.
std::pair<double, double> to_decades(double low, double high) {
  if (!(low <= high) || !std::isfinite(low) || !std::isfinite(high)) return {0, 0};
  double lo = std::floor(std::log10(low));
  double hi = std::ceil(std::log10(high));
  if (hi <= lo) hi = lo + 1;  // a value at an exact power of ten, or a constant curve
  return {std::pow(10.0, lo), std::pow(10.0, hi)};
}

}  // namespace

std::pair<double, double> decade_y_range(const DeviationPlot& plot) {
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (const auto& c : plot.curves) {
    extend(low, high, c.y);
    extend(low, high, c.low);
    extend(low, high, c.high);
  }
  for (const auto& c : plot.lines) extend(low, high, c.y);
  for (const auto& c : plot.markers) extend(low, high, c.y);
  return to_decades(low, high);
}

std::pair<double, double> decade_y_range(const SpectrumPlot& plot) {
  double low = std::numeric_limits<double>::infinity();
  double high = -low;
  for (const auto& c : plot.curves) extend(low, high, c.y);
  for (const auto& c : plot.lines) extend(low, high, c.y);
  return to_decades(low, high);
}

namespace {

/// Characters in a UTF-8 string (code points; every one counted as one character's width).
std::size_t utf8_length(const std::string& text) {
  return static_cast<std::size_t>(std::count_if(
      text.begin(), text.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

/// `text` broken between words into lines of at most `width` characters (a longer word stays
/// whole on its line).
std::vector<std::string> wrap_words(const std::string& text, std::size_t width) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = text.find(' ', begin);
    if (end == std::string::npos) end = text.size();
    const std::string word = text.substr(begin, end - begin);
    if (!line.empty() && utf8_length(line) + 1 + utf8_length(word) > width) {
      lines.push_back(line);
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
    begin = end + 1;
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

/// Characters per caption line of the compliance chart: compliance.gp gives the plot area at
/// least plot_chars (60) characters' width, and the caption is centred under it.
constexpr std::size_t kCaptionLineChars = 60;
/// Caption lines compliance.gp takes (caption1..3).
constexpr std::size_t kCaptionLines = 3;
/// Decades of the x axis up to which its 2 and 5 steps are labelled too: beyond, they crowd
/// (a 2-5-10 step is 0.3-0.4 decade; at 3 decades on the 60-character plot area that is about
/// 7 characters, the width of a label such as "0.002").
constexpr double kStepDecades = 3;

}  // namespace

void render_compliance_plot(const CompliancePlot& plot, const std::filesystem::path& output,
                            bool overwrite) {
  const PlotFormat format = plot_format_for(output);
  check_can_write(output, overwrite);
  if (plot.rows.empty()) throw Error("nothing to plot");
  ScratchDir scratch;
  const auto data = scratch.file("compliance.dat");
  const auto rendered = scratch.file("plot" + output.extension().string());
  {
    std::ofstream out(data);
    out.precision(10);
    for (std::size_t i = 0; i < plot.rows.size(); ++i) {
      const auto& r = plot.rows[i];
      const char* color = r.verdict == "pass"           ? "0x2ca02c"
                          : r.verdict == "marginal"     ? "0xe6a000"
                          : r.verdict == "inconclusive" ? "0x7f7f7f"
                                                        : "0xd62728";
      std::string label;
      for (char c : plot_text(r.label)) label += (c == '"') ? ' ' : c;
      // Reversed rows so the first item is at the top.
      out << (plot.rows.size() - 1 - i) << ' ' << r.ratio << ' ' << r.ratio_low << ' '
          << r.ratio_high << ' ' << color << " \"" << label << "\" " << (r.detected ? 1 : 0) << "\n";
    }
  }
  const auto undetected = std::count_if(plot.rows.begin(), plot.rows.end(),
                                        [](const ComplianceRow& r) { return !r.detected; });
  const std::string caption =
      plot.caption.empty() ? "bar: confidence interval" : plot.caption;
  const auto x_range = compliance_x_range(plot);
  // The template lays the chart out from the longest label (its width in characters) and
  // centres the caption, wrapped, under a plot area at least kCaptionLineChars wide.
  std::size_t label_chars = 0;
  for (const auto& r : plot.rows) label_chars = std::max(label_chars, utf8_length(r.label));
  std::vector<std::string> caption_lines = wrap_words(caption, kCaptionLineChars);
  if (caption_lines.size() > kCaptionLines) {  // the rest on the last line, which may be long
    for (std::size_t i = kCaptionLines; i < caption_lines.size(); ++i) {
      caption_lines[kCaptionLines - 1] += " " + caption_lines[i];
    }
    caption_lines.resize(kCaptionLines);
  }
  std::string caption_assignments = "; ncaption=" + std::to_string(caption_lines.size());
  for (std::size_t i = 0; i < kCaptionLines; ++i) {
    caption_assignments += "; caption" + std::to_string(i + 1) + "=" +
                           gnuplot_string(i < caption_lines.size() ? caption_lines[i] : "");
  }
  const bool label_steps = std::log10(x_range.second / x_range.first) <= kStepDecades;
  const std::string assignments =
      "datafile=" + gnuplot_string(data.string()) + "; outfile=" + gnuplot_string(rendered.string()) +
      "; term=" + gnuplot_string(terminal_for(format)) + "; title_text=" + gnuplot_string(plot.title) +
      caption_assignments + "; nundetected=" + std::to_string(undetected) +
      "; nrows=" + std::to_string(plot.rows.size()) + "; xmin=" + gnuplot_number(x_range.first) +
      "; xmax=" + gnuplot_number(x_range.second) + "; label_chars=" + std::to_string(label_chars) +
      "; label_steps=" + (label_steps ? "1" : "0");
  run_gnuplot("compliance.gp", assignments, rendered, scratch);
  move_into_place(rendered, output, overwrite);
}

}  // namespace sigmatau
