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
