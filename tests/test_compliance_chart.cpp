// The compliance chart's layout (plot.hpp, plots/compliance.gp): laid out from its labels, so a
// long label never squeezes the plot area (issue 28: on the ADIS16405 log against the ADIS16448
// sheet the plot was a strip of about 60 px, its x labels on each other, the caption cut off).
// The rendered charts are also checked in Chromium (tests/cli/compliance_chart.cmake): with
// SIGMATAU_CHART_DIR set, the charts drawn here are left there for that check.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "sigmatau/plot.hpp"
#include "temp_dir.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

/// `count` rows with labels of the kind that squeezed the plot: sensor, term, axis, limit kind,
/// "fit rejected", "not detected"; every third row undetected (an arrow), ratios over 0.01-100.
CompliancePlot long_label_chart(int count) {
  CompliancePlot plot;
  plot.title = "Compliance with a made-up sheet";
  plot.caption =
      "bar: 68.3 % confidence interval; arrow: a term not detected, at most its upper bound "
      "(the arrow's start)";
  const char* terms[] = {"white noise", "bias instability", "rate random walk"};
  for (int i = 0; i < count; ++i) {
    ComplianceRow r;
    r.label = std::string(i % 2 ? "accel " : "gyro ") + terms[i % 3] + " " +
              static_cast<char>('x' + i % 3) + " (typ), fit rejected" +
              (i % 3 == 2 ? ", not detected" : "") + " #" + std::to_string(i);
    const double ratio = std::pow(10.0, -2 + 4.0 * i / (count - 1));
    r.ratio = ratio;
    r.ratio_low = ratio / 1.2;
    r.ratio_high = ratio * 1.2;
    r.verdict = ratio < 1 ? "pass" : "fail";
    r.detected = i % 3 != 2;
    plot.rows.push_back(r);
  }
  return plot;
}

/// The width of an SVG's viewBox, 0 when it has none.
double view_box_width(const std::string& svg) {
  std::smatch m;
  if (!std::regex_search(svg, m, std::regex(R"re(viewBox="0 0 ([0-9.]+) [0-9.]+")re"))) return 0;
  return std::stod(m[1]);
}

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Renders `plot` to NAME.svg in a fresh directory, also copied to $SIGMATAU_CHART_DIR when set.
std::string render(const CompliancePlot& plot, const std::string& name) {
  const sigmatau::test::TempDir dir("compliance_chart");
  const auto path = dir.file(name + ".svg");
  render_compliance_plot(plot, path, false);
  if (const char* keep = std::getenv("SIGMATAU_CHART_DIR")) {
    std::filesystem::create_directories(keep);
    std::filesystem::copy_file(path, std::filesystem::path(keep) / (name + ".svg"),
                               std::filesystem::copy_options::overwrite_existing);
  }
  return read_file(path);
}

}  // namespace

TEST_CASE("the chart's x range holds the tip of every bound's arrow") {
  // A bound at 0.4 of the limit is drawn as an arrow to 0.4 / 1.8: the range used to start at
  // 0.4 / 1.5, so the arrow's head was cut off and only its shaft's end showed.
  CompliancePlot plot;
  plot.rows = {{"a", 3, 2.5, 4, "fail"}, {"b", 0.4, 0.4, 0.4, "pass", false}};
  const auto [low, high] = compliance_x_range(plot);
  CHECK(low <= 0.4 / 1.8 / 1.5 * (1 + 1e-12));  // the tip, with the range's own 1.5x margin
  CHECK(high == doctest::Approx(4 * 1.5).epsilon(1e-12));
}

TEST_CASE("the chart widens with its labels instead of squeezing the plot area") {
  if (!gnuplot_available()) {
    MESSAGE("SKIPPED: gnuplot not installed");
    return;
  }
  // Short labels: the usual 1100-px canvas.
  CompliancePlot short_labels;
  short_labels.rows = {{"gyro N x (typ)", 0.8, 0.7, 0.9, "pass"}};
  CHECK(view_box_width(render(short_labels, "short_labels")) == 1100);
  // 36 rows with labels of up to 64 characters: the canvas holds the labels (0.6 em of 16 px a
  // character, compliance.gp) beside a plot area of 62 such characters, 595 px.
  const CompliancePlot chart = long_label_chart(36);
  std::size_t longest = 0;
  for (const auto& r : chart.rows) longest = std::max(longest, r.label.size());
  const std::string svg = render(chart, "long_labels_36_rows");
  CHECK(view_box_width(svg) >= (static_cast<double>(longest) + 8) * 0.6 * 16 + 62 * 0.6 * 16 - 1);
  // The caption (104 characters) is wrapped into lines of at most 60, each its own text.
  CHECK(svg.find(">bar: 68.3 % confidence interval; arrow: a term not detected,<") !=
        std::string::npos);
  CHECK(svg.find(">at most its upper bound (the arrow's start)<") != std::string::npos);
  // Over four decades the 2 and 5 steps are not labelled (they would crowd): only decades.
  CHECK(svg.find("> 0.05<") == std::string::npos);
  CHECK(svg.find("> 0.01<") != std::string::npos);
  CHECK(svg.find("> 100<") != std::string::npos);
}
