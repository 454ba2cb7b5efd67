// The report's parameter table: Q and R get columns when some channel's fit keeps them
// (regression: a quantization the fit kept on every gyro axis of a real log never appeared).
#include <nlohmann/json.hpp>

#include <string>

#include "sigmatau/report.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

/// A results.json with one gyro channel whose fit keeps N and, when `with_q`, Q.
std::string results_with(bool with_q) {
  nlohmann::json parameters = {
      {"N", {{"value", 4e-5}, {"ci_low", 3.9e-5}, {"ci_high", 4.1e-5}}},
      {"B", {{"upper_bound", 1e-5}}},
      {"K", {{"upper_bound", 1e-6}}},
      {"R", {{"upper_bound", 1e-7}}}};
  parameters["Q"] = with_q ? nlohmann::json{{"value", 3e-6}, {"ci_low", 2.9e-6}, {"ci_high", 3.1e-6}}
                           : nlohmann::json{{"upper_bound", 3e-6}};
  const nlohmann::json results = {
      {"tool", "sigmatau"},
      {"version", "test"},
      {"input", {{"path", "log.csv"}}},
      {"channels", {{{"name", "gx"}, {"sensor", "gyro"}}}},
      {"fit", {{"channels", {{{"name", "gx"}, {"parameters", parameters}}}}}}};
  return results.dump();
}

}  // namespace

TEST_CASE("a kept Q gets its column in summary.md and report.html; R, not kept, gets none") {
  ReportOptions options;
  options.plots = false;
  const ReportFiles kept = build_report(results_with(true), options);
  const std::string& md = kept.files.at("summary.md");
  CHECK(md.find("| channel | N | B | K | Q | noise density (PSD) |") != std::string::npos);
  CHECK(md.find("arcsec") != std::string::npos);  // Q in data-sheet units
  CHECK(kept.files.at("report.html").find("<th>Q</th>") != std::string::npos);
  CHECK(kept.files.at("report.html").find("<th>R</th>") == std::string::npos);

  const ReportFiles bound = build_report(results_with(false), options);
  CHECK(bound.files.at("summary.md").find("| channel | N | B | K | noise density (PSD) |") !=
        std::string::npos);
  CHECK(bound.files.at("report.html").find("<th>Q</th>") == std::string::npos);
}

TEST_CASE("the summary says B is the coefficient and the sheet's bias stability its floor") {
  // A STIM300 at its typical 0.5 deg/h fits as B = 0.75 deg/h: without the note the table read
  // as 50 % over the sheet while the compliance row (which compares 0.664 B) passed.
  ReportOptions options;
  options.plots = false;
  const ReportFiles files = build_report(results_with(false), options);
  CHECK(files.files.at("summary.md").find("data sheets print its ADEV floor 0.664 B as the bias "
                                          "stability") != std::string::npos);
  CHECK(files.files.at("report.html").find("data sheets print its ADEV floor 0.664 B as the bias "
                                           "stability") != std::string::npos);
}

TEST_CASE("a measured term the sheet does not print shows its value; an accelerometer's K is named after acceleration") {
  // The demo's accelerometer z keeps a K the STIM300 sheet has no line for: its row was empty,
  // and named "accel rate random walk z".
  nlohmann::json results = nlohmann::json::parse(results_with(false));
  results["channels"] = {{{"name", "az"}, {"sensor", "accel"}}};
  nlohmann::json item = {{"sensor", "accel"},     {"quantity", "rate_random_walk"},
                         {"axis", "z"},            {"verdict", "not specified"},
                         {"detected", true},       {"value", 1.5e-5},
                         {"ci_low", 1.2e-5},       {"ci_high", 3.7e-5}};
  results["compliance"] = nlohmann::json::object();
  results["compliance"]["spec"] = {{"manufacturer", "Test"}, {"part", "T-1"}};
  results["compliance"]["verdict"] = "pass";
  results["compliance"]["items"] = nlohmann::json::array({item});
  ReportOptions options;
  options.plots = false;
  const ReportFiles files = build_report(results.dump(), options);
  const std::string& md = files.files.at("summary.md");
  CHECK(md.find("| accel acceleration random walk z | not specified | 1.5e-05 [1.2e-05, 3.7e-05] "
                "m/s^3/sqrt(Hz) measured; the sheet prints no limit |") != std::string::npos);
  CHECK(md.find("rate random walk") == std::string::npos);
  CHECK(files.files.at("report.html").find("accel acceleration random walk z") != std::string::npos);
  // In the HTML it stands in the measured column, with no limit or ratio beside it.
  CHECK(files.files.at("report.html").find("<td>not specified</td><td>1.5e-05 [1.2e-05, 3.7e-05] "
                                           "m/s^3/sqrt(Hz) measured; the sheet prints no limit</td><td></td><td></td>") !=
        std::string::npos);
}
