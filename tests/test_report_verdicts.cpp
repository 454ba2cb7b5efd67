// The report's compliance section reads honestly (review E, A3-A5): ratios near 1 keep their
// digits, typ and max limits are marked, a typ limit is said not to be a guarantee, the verdict
// rule says how strong a pass is, and the ADEV plot names the sheet's white-noise field.
#include <nlohmann/json.hpp>

#include <cmath>
#include <string>

#include "sigmatau/compliance.hpp"
#include "sigmatau/plot.hpp"
#include "sigmatau/report.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

/// A compliance item as results.json holds it (only the keys the report reads).
nlohmann::json item(const std::string& sensor, const std::string& quantity, const std::string& verdict,
                    double margin, double margin_upper, const std::string& field,
                    const std::string& limit_text, bool typical) {
  return {{"sensor", sensor},       {"quantity", quantity},         {"axis", "x"},
          {"detected", true},       {"value", 1e-4},                {"ci_low", 0.9e-4},
          {"ci_high", 1.1e-4},      {"verdict", verdict},           {"spec_field", field},
          {"limit_text", limit_text}, {"limit_is_typical", typical}, {"margin", margin},
          {"margin_upper", margin_upper}};
}

/// A results.json with a gyro and an accelerometer channel (ADEV points), the sheet's white
/// lines, and `items` as its compliance.
nlohmann::json results_with(const nlohmann::json& items) {
  nlohmann::json points = nlohmann::json::array();
  for (const double tau : {0.01, 0.1, 1.0, 10.0}) {
    const double dev = 1e-4 / std::sqrt(tau);
    points.push_back({{"tau", tau}, {"dev", dev}, {"ci_low", 0.9 * dev}, {"ci_high", 1.1 * dev}});
  }
  const nlohmann::json allan = {{{"statistic", "oadev"}, {"points", points}}};
  nlohmann::json results = {
      {"tool", "sigmatau"},
      {"version", "test"},
      {"confidence", 0.683},
      {"input", {{"path", "log.csv"}}},
      {"channels",
       {{{"name", "gx"}, {"sensor", "gyro"}, {"allan", allan}},
        {{"name", "ax"}, {"sensor", "accel"}, {"allan", allan}}}},
      {"spec_lines", {{"gyro", {{"white", 1e-4}}}, {"accel", {{"white", 1e-4}}}}}};
  results["compliance"] = {{"spec", {{"manufacturer", "Test"}, {"part", "T-1"}}},
                           {"verdict", "fail"},
                           {"items", items}};
  return results;
}

}  // namespace

TEST_CASE("a fail by 0.13 % reads 1.001, not 1; typ and max limits are marked") {
  // ADIS16470 at its typical ARW: the summary row read "fail | 1 | 1".
  const nlohmann::json items = {
      item("gyro", "white_noise", "fail", 1.0013, 1.0042, "angle_random_walk", "0.34 °/√hr", true),
      item("accel", "bias_instability", "pass", 0.5, 0.61, "bias_instability", "15 µg", false)};
  ReportOptions options;
  options.plots = false;
  const ReportFiles files = build_report(results_with(items).dump(), options);
  const std::string& md = files.files.at("summary.md");
  // (These items have no lower bound, as files before it had: the upper one alone.)
  CHECK(md.find("| gyro white noise x | fail |  | 0.34 °/√hr (typ) | 1.001 (upper 1.004) |") != std::string::npos);
  CHECK(md.find("| accel bias instability x | pass |  | 15 µg (max) | 0.500 (upper 0.610) |") != std::string::npos);
  const std::string& html = files.files.at("report.html");
  CHECK(html.find("<td>0.34 °/√hr (typ)</td><td>1.001 (upper 1.004)</td>") != std::string::npos);
  CHECK(html.find("<td>15 µg (max)</td>") != std::string::npos);
}

TEST_CASE("a typical limit is said not to be a guarantee, once, beside the verdict") {
  // json::array: a braced list of one json is that json itself under clang (an array under GCC).
  const nlohmann::json typ = nlohmann::json::array(
      {item("gyro", "white_noise", "fail", 1.0013, 1.0042, "angle_random_walk", "0.34 °/√hr", true)});
  ReportOptions options;
  options.plots = false;
  const ReportFiles files = build_report(results_with(typ).dump(), options);
  const std::string& md = files.files.at("summary.md");
  const std::string note = kTypicalLimitNote;
  CHECK(md.find("**fail** (" + note + ")") != std::string::npos);
  CHECK(md.find(note) == md.rfind(note));  // once
  CHECK(files.files.at("report.html").find(note) != std::string::npos);

  // Only max limits: no such note.
  const nlohmann::json max = nlohmann::json::array(
      {item("accel", "bias_instability", "pass", 0.5, 0.61, "bias_instability", "15 µg", false)});
  const ReportFiles max_files = build_report(results_with(max).dump(), options);
  CHECK(max_files.files.at("summary.md").find(note) == std::string::npos);
  CHECK(max_files.files.at("report.html").find(note) == std::string::npos);
}

TEST_CASE("the verdict rule under the compliance table advises --ci 0.95 for a gate") {
  const nlohmann::json items = nlohmann::json::array(
      {item("gyro", "white_noise", "pass", 0.8, 0.9, "noise_density", "0.014 °/s/√Hz", true)});
  ReportOptions options;
  options.plots = false;
  const ReportFiles files = build_report(results_with(items).dump(), options);
  for (const char* name : {"summary.md", "report.html"}) {
    CAPTURE(name);
    const std::string& text = files.files.at(name);
    CHECK(text.find("marginal: the estimate is within the limit but its bound is not") !=
          std::string::npos);
    CHECK(text.find("--ci 0.95") != std::string::npos);
    CHECK(text.find("68.3 % interval") != std::string::npos);
  }
  // A result already at 95 % gets the rule without the advice (it would be wrong there).
  nlohmann::json at95 = results_with(items);
  at95["confidence"] = 0.95;
  const ReportFiles files95 = build_report(at95.dump(), options);
  for (const char* name : {"summary.md", "report.html"}) {
    CAPTURE(name);
    const std::string& text = files95.files.at(name);
    CHECK(text.find("95 % interval is within the limit") != std::string::npos);
    CHECK(text.find("--ci 0.95") == std::string::npos);
  }
  CHECK(gate_confidence_note(0.683).find("At 68.3 % a pass") == 0);
  CHECK(gate_confidence_note(0.9).find("At 90 % a pass") == 0);
  CHECK(gate_confidence_note(0.95).empty());
  CHECK(gate_confidence_note(0.99).empty());
}

TEST_CASE("the ADEV plot names the sheet's white-noise line after the printed field") {
  // ADIS16448 / STIM300 print ARW and VRW: the legend said "data sheet noise density".
  if (!gnuplot_available()) {
    MESSAGE("gnuplot not found: plot legend check skipped");
    return;
  }
  const nlohmann::json items = {
      item("gyro", "white_noise", "pass", 0.8, 0.9, "angle_random_walk", "0.15 °/√hr", true),
      item("accel", "white_noise", "pass", 0.8, 0.9, "velocity_random_walk", "0.06 m/s/√hr", true)};
  ReportOptions options;
  options.plots = true;
  options.plot_format = PlotFormat::svg;
  const ReportFiles files = build_report(results_with(items).dump(), options);
  REQUIRE(files.files.count("adev_gyro.svg") == 1);
  REQUIRE(files.files.count("adev_accel.svg") == 1);
  CHECK(files.files.at("adev_gyro.svg").find("data sheet ARW") != std::string::npos);
  CHECK(files.files.at("adev_accel.svg").find("data sheet VRW") != std::string::npos);
  CHECK(files.files.at("adev_gyro.svg").find("data sheet noise density") == std::string::npos);

  const nlohmann::json density = nlohmann::json::array(
      {item("gyro", "white_noise", "pass", 0.8, 0.9, "noise_density", "0.014 °/s/√Hz", true)});
  const ReportFiles density_files = build_report(results_with(density).dump(), options);
  CHECK(density_files.files.at("adev_gyro.svg").find("data sheet noise density") !=
        std::string::npos);
}
