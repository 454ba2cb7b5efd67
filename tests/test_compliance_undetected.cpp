// Compliance of a noise term the fit left out (regression: such a data-sheet item used to vanish
// from `check` and `analyze --spec`). The term is checked by its one-sided upper bound alone:
// pass when the bound is within the limit, inconclusive when it is not, never fail.
#include <cmath>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <tuple>

#include "sigmatau/compliance.hpp"
#include "sigmatau/plot.hpp"
#include "sigmatau/report.hpp"
#include "sigmatau/spec.hpp"
#include "made_up_sheet.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

// A made-up sheet with round limits, so every ratio below can be checked by hand.
const std::string kSheet = test::made_up_sheet("T-2", R"(gyro:
  angle_random_walk:
    max: 0.2 °/√h
    source: ds
    page: 1
  bias_instability:
    max: 3 °/h
    source: ds
    page: 1
  rate_random_walk:
    max: 10 °/h/√h
    source: ds
    page: 1
)");

constexpr double kDegPerHour = std::numbers::pi / 180.0 / 3600.0;  // deg/h -> rad/s
constexpr double kBiasLimit = 3.0 * kDegPerHour;                   // printed floor [rad/s]
constexpr double kWalkLimit = 10.0 * kDegPerHour / 60.0;           // deg/h/sqrt(h) -> SI

// Ratios of products of exact decimal inputs: only rounding separates them from the hand value.
constexpr double kRoundingTolerance = 1e-12;

MeasuredParameter undetected(MeasuredQuantity quantity, double upper_bound) {
  return {.sensor = Sensor::gyro,
          .quantity = quantity,
          .axis = "x",
          .detected = false,
          .upper_bound = upper_bound};
}

/// An N-only fit result as `fit --format json` writes it: N kept, B and K given as upper bounds.
std::string n_only_fit(double b_upper, const char* k_upper = "2.0e-7") {
  char b_text[32];
  std::snprintf(b_text, sizeof b_text, "%.17g", b_upper);  // round-trips exactly
  return std::string(R"json({"channels":[{"name":"gx","quantity":"angular_rate",
    "model_terms":["N"],
    "parameters":{"N":{"value":2.0e-5,"ci_low":1.9e-5,"ci_high":2.1e-5,"unit":"rad/s/sqrt(Hz)"},
                  "B":{"upper_bound":)json") +
         b_text + R"json(,"unit":"rad/s","tau_min_s":600.0},
                  "K":{"upper_bound":)json" +
         k_upper + R"json(,"unit":"rad/s^2/sqrt(Hz)"},
                  "Q":{"upper_bound":1e-7,"unit":"rad"}},
    "method":"joint"}]})json";
}

}  // namespace

TEST_CASE("an undetected bias instability passes when its upper bound is within the limit") {
  const DataSheet sheet = parse_data_sheet(kSheet, "test.yaml");
  // 0.664 B_upper = 0.8 of the printed floor.
  const double b_upper = 0.8 * kBiasLimit / kFlickerFloorFactor;
  const auto items =
      check_compliance({undetected(MeasuredQuantity::bias_instability, b_upper)}, sheet);
  REQUIRE(items.size() == 1);
  CHECK(items[0].verdict == Verdict::pass);
  CHECK(items[0].spec_field == "bias_instability");
  CHECK(items[0].margin_upper == test::rel(0.8, kRoundingTolerance));
  CHECK(std::isnan(items[0].margin));  // no estimate to compare
  CHECK(items[0].rule.find("not detected") != std::string::npos);
  CHECK(overall_verdict(items) == "all pass");
}

TEST_CASE("an undetected term whose bound exceeds the limit is inconclusive, never a failure") {
  const DataSheet sheet = parse_data_sheet(kSheet, "test.yaml");
  const auto items = check_compliance(
      {undetected(MeasuredQuantity::bias_instability, 2.5 * kBiasLimit / kFlickerFloorFactor),
       undetected(MeasuredQuantity::rate_random_walk, 4.0 * kWalkLimit)},
      sheet);
  REQUIRE(items.size() == 2);
  CHECK(items[0].verdict == Verdict::inconclusive);
  CHECK(items[0].margin_upper == test::rel(2.5, kRoundingTolerance));
  CHECK(items[1].verdict == Verdict::inconclusive);
  CHECK(items[1].spec_field == "rate_random_walk");
  CHECK(items[1].margin_upper == test::rel(4.0, kRoundingTolerance));
  CHECK(to_string(items[0].verdict) == "inconclusive");
  CHECK_FALSE(any_failed(items));  // `check` exits 0
  CHECK(overall_verdict(items) == "inconclusive");

  SUBCASE("a bound that could not be computed (NaN) is inconclusive too") {
    const auto nan_items = check_compliance(
        {undetected(MeasuredQuantity::bias_instability, std::numeric_limits<double>::quiet_NaN())},
        sheet);
    CHECK(nan_items[0].verdict == Verdict::inconclusive);
  }
}

TEST_CASE("the overall verdict ranks fail, marginal, inconclusive, then all pass") {
  const DataSheet sheet = parse_data_sheet(kSheet, "test.yaml");
  const double arw = 0.2 * std::numbers::pi / 180.0 / 60.0;  // printed limit [rad/s/sqrt(Hz)]
  const MeasuredParameter inconclusive =
      undetected(MeasuredQuantity::bias_instability, 2.0 * kBiasLimit / kFlickerFloorFactor);
  const MeasuredParameter n_pass{
      Sensor::gyro, MeasuredQuantity::white_noise, "y", 0.5 * arw, 0.4 * arw, 0.6 * arw};
  const MeasuredParameter n_marginal{
      Sensor::gyro, MeasuredQuantity::white_noise, "z", 0.9 * arw, 0.8 * arw, 1.1 * arw};
  const MeasuredParameter n_fail{
      Sensor::gyro, MeasuredQuantity::white_noise, "z", 1.2 * arw, 1.1 * arw, 1.3 * arw};
  CHECK(overall_verdict(check_compliance({n_pass, inconclusive}, sheet)) == "inconclusive");
  CHECK(overall_verdict(check_compliance({n_marginal, inconclusive}, sheet)) == "marginal");
  const auto failed = check_compliance({n_fail, inconclusive}, sheet);
  CHECK(overall_verdict(failed) == "fail");
  CHECK(any_failed(failed));  // the fail decides the exit status, not the bound
}

TEST_CASE("terms a fit result gives only as an upper bound are read as not detected") {
  const auto p = measured_parameters_from_json(n_only_fit(3.0e-6), "fit.json");
  // N measured; B and K as bounds; Q (no data-sheet quantity) is not read.
  REQUIRE(p.size() == 3);
  CHECK(p[0].quantity == MeasuredQuantity::white_noise);
  CHECK(p[0].detected);
  CHECK(p[1].quantity == MeasuredQuantity::bias_instability);
  CHECK_FALSE(p[1].detected);
  CHECK(p[1].upper_bound == test::rel(3.0e-6, kRoundingTolerance));
  CHECK(p[2].quantity == MeasuredQuantity::rate_random_walk);
  CHECK_FALSE(p[2].detected);

  SUBCASE("a null bound (NaN written by the fit) is read as unknown") {
    const auto q = measured_parameters_from_json(n_only_fit(3.0e-6, "null"), "fit.json");
    REQUIRE(q.size() == 3);
    CHECK(std::isnan(q[2].upper_bound));
  }
  SUBCASE("a bound that is not a number is an error naming the term") {
    CHECK_THROWS_WITH_AS(measured_parameters_from_json(n_only_fit(3.0e-6, "\"big\""), "fit.json"),
                         doctest::Contains("fit.json: channels[0] (gx).parameters.K.upper_bound: "
                                           "expected a finite number >= 0, got \"big\""),
                         Error);
  }
}

TEST_CASE("an N-only fit still gets a bias-instability row in the compliance JSON and report") {
  const DataSheet sheet = parse_data_sheet(kSheet, "test.yaml");
  // 0.664 B_upper = 1.5 x the printed floor: the log cannot decide.
  const double b_upper = 1.5 * kBiasLimit / kFlickerFloorFactor;
  const auto items =
      check_compliance(measured_parameters_from_json(n_only_fit(b_upper), "fit.json"), sheet);
  const nlohmann::json doc = nlohmann::json::parse(compliance_json(items, sheet, {}));
  CHECK(doc["verdict"] == "inconclusive");
  CHECK(doc["failed"] == false);
  const nlohmann::json* b = nullptr;
  for (const auto& item : doc["items"]) {
    if (item["quantity"] == "bias_instability") b = &item;
  }
  REQUIRE(b != nullptr);
  CHECK((*b)["verdict"] == "inconclusive");
  CHECK((*b)["detected"] == false);
  CHECK((*b)["upper_bound"].get<double>() == test::rel(b_upper, kRoundingTolerance));
  CHECK((*b)["margin_upper"].get<double>() == test::rel(1.5, kRoundingTolerance));
  CHECK_FALSE(b->contains("value"));  // no estimate, as in the fit result
  CHECK_FALSE(b->contains("margin"));

  // The report shows the row with its verdict and says the term was not detected.
  const nlohmann::json results = {{"tool", "sigmatau"},
                                  {"version", "test"},
                                  {"input", {{"path", "n_only.csv"}}},
                                  {"channels", nlohmann::json::array()},
                                  {"compliance", doc}};
  ReportOptions options;
  options.plots = false;
  const ReportFiles report = build_report(results.dump(), options);
  const std::string& md = report.files.at("summary.md");
  CHECK(md.find("| gyro bias instability x | inconclusive | not detected") != std::string::npos);
  CHECK(md.find("**inconclusive**") != std::string::npos);
  const std::string& html = report.files.at("report.html");
  CHECK(html.find("<tr class=\"inconclusive\"><td>gyro bias instability x</td>") !=
        std::string::npos);
  CHECK(html.find("class=\"verdict inconclusive\"") != std::string::npos);
}

TEST_CASE("a term neither printed on the sheet nor detected gives no row") {
  // The test sheet prints no accelerometer: an undetected accelerometer B says nothing.
  const DataSheet sheet = parse_data_sheet(kSheet, "test.yaml");
  MeasuredParameter accel = undetected(MeasuredQuantity::bias_instability, 1e-4);
  accel.sensor = Sensor::accel;
  CHECK(check_compliance({accel}, sheet).empty());
  // Detected, the same term is listed as not specified (a measurement the sheet cannot judge).
  accel.detected = true;
  accel.value = accel.ci_low = accel.ci_high = 1e-4;
  const auto items = check_compliance({accel}, sheet);
  REQUIRE(items.size() == 1);
  CHECK(items[0].verdict == Verdict::not_specified);
}

TEST_CASE("the compliance chart's x range always shows the limit line at 1") {
  // Every item failing (ratios 3 to 12): autoscaling started the log axis at 1, so the limit
  // line sat on the frame. The range holds 1 with a 1.5x margin on each side.
  CompliancePlot all_fail;
  all_fail.rows = {{"a", 3, 2.5, 4, "fail"}, {"b", 10, 8, 12, "fail"}};
  auto [low, high] = compliance_x_range(all_fail);
  CHECK(low == doctest::Approx(1 / 1.5));
  CHECK(high == doctest::Approx(12 * 1.5));
  // Every item passing well inside: the line at 1 is the right end, with its margin.
  CompliancePlot all_pass;
  all_pass.rows = {{"a", 0.2, 0.1, 0.3, "pass"}, {"b", 0.5, 0, 0.5, "inconclusive"}};
  std::tie(low, high) = compliance_x_range(all_pass);
  CHECK(low == doctest::Approx(0.1 / 1.5));  // a zero lower end is left out (log axis)
  CHECK(high == doctest::Approx(1.5));
}
