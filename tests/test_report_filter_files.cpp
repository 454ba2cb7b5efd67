// The report's "Filter tuning" part (review F, finding 15): the arithmetic wraps line by line
// instead of scrolling sideways, each filter file results.json names is listed by its name as
// written, said what it is for and shown, escaped; summary.md names the files; a file the report
// is not given is said to be missing, in the page and as a warning.
#include <algorithm>
#include <nlohmann/json.hpp>
#include <regex>
#include <string>

#include "sigmatau/report.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

/// The arithmetic of one rate: a long bias line (review F: its end was cut off on screen) and
/// characters HTML must escape.
const std::string kExplain =
    "gyro: f_s = 200 Hz (T_s = 0.005 s)\n"
    "  bias: from the noise-term fit; B on axis z: not detected, its upper bound used; K on axis "
    "x: not detected, its upper bound used; K on axis y: not detected, its upper bound used\n"
    "    x: Q_bb = K^2 T_s < 1e-12 & \"per step\"\n";

/// A results.json with one gyro channel and a filter section at 200 Hz naming `names`.
std::string results_naming(const std::vector<std::string>& names) {
  const nlohmann::json results = {
      {"tool", "sigmatau"},
      {"version", "test"},
      {"input", {{"path", "log.csv"}}},
      {"channels", {{{"name", "gx"}, {"sensor", "gyro"}}}},
      {"filter", {{{"rate_hz", 200.0}, {"explain", kExplain}, {"files", names}}}}};
  return results.dump();
}

/// The Kalibr file as filter_export writes it, with text HTML must escape.
const std::string kKalibr =
    "# Kalibr imu.yaml (continuous-time densities)\n"
    "# note: gyro K < 2e-7 & accel \"largest axis\" > 1e-5\n"
    "rostopic: /imu0\n"
    "update_rate: 200  # [Hz]\n";

const std::string kJson = "{\n  \"rate_hz\": 200.0\n}\n";

/// report.html with the per-line spans of the wrapped text blocks removed: what the browser's
/// text of a block is (the spans add no characters).
std::string without_line_spans(const std::string& html) {
  static const std::regex span(
      R"(<span style="padding-left:[0-9]+ch;text-indent:-[0-9]+ch">|</span>)");
  return std::regex_replace(html, span, "");
}

std::string escaped(std::string s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("the report names each filter file as written and shows its text, escaped") {
  ReportOptions options;
  options.plots = false;
  const std::map<std::string, std::string> files = {{"kalibr_imu_200Hz.yaml", kKalibr},
                                                    {"filter_200Hz.json", kJson}};
  const ReportFiles report =
      build_report(results_naming({"filter_200Hz.json", "kalibr_imu_200Hz.yaml"}), options, files);
  const std::string& html = report.files.at("report.html");
  const std::string text = without_line_spans(html);
  CHECK(contains(text, escaped(kKalibr)));
  CHECK(contains(text, escaped(kJson)));
  CHECK_FALSE(contains(html, "gyro K < 2e-7"));  // never raw
  // Named as written, with what the file is for (its own first comment line) and its size.
  CHECK(contains(
      html, "<code>kalibr_imu_200Hz.yaml</code>: Kalibr imu.yaml (continuous-time densities)"));
  CHECK(contains(html, "(" + std::to_string(kKalibr.size()) + " bytes)"));
  CHECK(contains(html, "<code>filter_200Hz.json</code>: sigmatau's JSON"));
  // Collapsed: a <details> without `open`.
  CHECK(contains(html, "<details class=\"file\" id=\"file-kalibr_imu_200Hz.yaml\"><summary>"));
  CHECK(report.warnings.empty());
  CHECK_FALSE(contains(html, "class=\"file missing\""));
  // The summary at the top names them too, each a link to its text.
  const auto line = html.find("<p id=\"filter-files\">");
  REQUIRE(line != std::string::npos);
  CHECK(line < html.find("<h2 id=\"filter\">"));
  CHECK(html.find("<a href=\"#file-kalibr_imu_200Hz.yaml\"><code>kalibr_imu_200Hz.yaml</code></a>",
                  line) != std::string::npos);

  const std::string& md = report.files.at("summary.md");
  CHECK(contains(md, "## Filter files"));
  CHECK(contains(md, "- `kalibr_imu_200Hz.yaml`: Kalibr imu.yaml (continuous-time densities)\n"));
  CHECK(contains(md, "- `filter_200Hz.json`: sigmatau's JSON"));
}

TEST_CASE("the filter arithmetic wraps line by line with a hanging indent instead of scrolling") {
  ReportOptions options;
  options.plots = false;
  const ReportFiles report = build_report(results_naming({}), options, {});
  const std::string& html = report.files.at("report.html");
  // The whole arithmetic, escaped, in one block; no sideways scrolling anywhere.
  CHECK(contains(without_line_spans(html), escaped(kExplain)));
  CHECK_FALSE(contains(html, "overflow-x"));
  CHECK(contains(html, "white-space:pre-wrap"));
  // Each line is a block of its own; a wrapped continuation of the 2-space-indented bias line
  // starts 4 characters past that indentation (2 + 4 = 6), of the 4-space one at 8.
  CHECK(contains(
      html, "<span style=\"padding-left:6ch;text-indent:-6ch\">  bias: from the noise-term fit;"));
  CHECK(contains(
      html, "<span style=\"padding-left:8ch;text-indent:-8ch\">    x: Q_bb = K^2 T_s &lt; 1e-12"));
  CHECK(contains(html, "pre.lines>span{display:block}"));
}

TEST_CASE("a filter file results.json names but the report is not given is reported missing") {
  ReportOptions options;
  options.plots = false;
  const std::map<std::string, std::string> files = {{"kalibr_imu_200Hz.yaml", kKalibr}};
  const ReportFiles report = build_report(
      results_naming({"kalibr_imu_200Hz.yaml", "px4_ekf2_200Hz.params"}), options, files);
  const std::string& html = report.files.at("report.html");
  CHECK(contains(html, "<p class=\"file missing\"><code>px4_ekf2_200Hz.params</code>: missing"));
  CHECK(contains(html, "<code>px4_ekf2_200Hz.params</code></a> <strong>(missing)</strong>"));
  REQUIRE(report.warnings.size() == 1);
  CHECK(contains(report.warnings[0],
                 "px4_ekf2_200Hz.params (at 200 Hz) is named in results.json but "
                 "was not given to the report"));
  // In the banner's count and the Warnings list of both pages.
  CHECK(contains(html, "<strong>Warning:</strong> 1 warning"));
  CHECK(contains(html, "<li>filter file px4_ekf2_200Hz.params"));
  const std::string& md = report.files.at("summary.md");
  CHECK(contains(md, "- `px4_ekf2_200Hz.params`: **missing: results.json names it"));
  CHECK(contains(md, "- filter file px4_ekf2_200Hz.params"));
  // The file that was given is still shown.
  CHECK(contains(without_line_spans(html), escaped(kKalibr)));

  // Without any files, every named one is missing.
  const ReportFiles none = build_report(results_naming({"kalibr_imu_200Hz.yaml"}), options);
  CHECK(none.warnings.size() == 1);
}

TEST_CASE("a filter file given but named by no rate is still shown; no filter, no section") {
  ReportOptions options;
  options.plots = false;
  const ReportFiles extra =
      build_report(results_naming({}), options, {{"gtsam_200Hz.txt", "# GTSAM x\n"}});
  const std::string& html = extra.files.at("report.html");
  CHECK(contains(html, "<h3>files results.json does not name</h3>"));
  CHECK(contains(html, "<code>gtsam_200Hz.txt</code>: GTSAM x"));
  CHECK(contains(extra.files.at("summary.md"), "- `gtsam_200Hz.txt`: GTSAM x"));

  nlohmann::json plain = nlohmann::json::parse(results_naming({}));
  plain.erase("filter");
  const ReportFiles without = build_report(plain.dump(), options);
  CHECK_FALSE(contains(without.files.at("report.html"), "Filter tuning"));
  CHECK_FALSE(contains(without.files.at("report.html"), "id=\"filter-files\""));
  CHECK_FALSE(contains(without.files.at("summary.md"), "## Filter files"));
  CHECK(without.warnings.empty());
}
