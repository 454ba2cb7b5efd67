// What a verdict rests on (review F, findings 1, 4, 5): a fail whose interval still reaches the
// limit is marked "within uncertainty"; a verdict from a rejected fit (p below 1e-3) is marked
// "fit rejected"; the report has a warning banner at the top and shows the bias-instability floor
// 0.664 B beside sheet limits; the result reader takes sensor and axis from classify_channel.
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

#include "made_up_sheet.hpp"
#include "sigmatau/compliance.hpp"
#include "sigmatau/fit.hpp"
#include "sigmatau/noise_model.hpp"
#include "sigmatau/plot.hpp"
#include "sigmatau/report.hpp"
#include "sigmatau/spec.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

const std::string kSheet = test::made_up_sheet("T-3", R"(gyro:
  angle_random_walk:
    max: 0.2 °/√h
    source: ds
    page: 1
  bias_instability:
    max: 3 °/h
    source: ds
    page: 1
)");

constexpr double kDegPerHour = std::numbers::pi / 180.0 / 3600.0;  // deg/h -> rad/s
constexpr double kArwLimit = 0.2 * std::numbers::pi / 180.0 / 60.0;  // 0.2 deg/sqrt(h) in SI
// Ratios of exact decimal multiples of the limit: only rounding separates them from the value.
constexpr double kRoundingTolerance = 1e-12;

/// A white-noise estimate at `value` x the limit with interval [low, high] x the limit.
MeasuredParameter white(double value, double low, double high, double p_value) {
  return {.sensor = Sensor::gyro,
          .quantity = MeasuredQuantity::white_noise,
          .axis = "x",
          .value = value * kArwLimit,
          .ci_low = low * kArwLimit,
          .ci_high = high * kArwLimit,
          .fit_p_value = p_value};
}

ComplianceItem only_item(const MeasuredParameter& p) {
  const auto items = check_compliance({p}, parse_data_sheet(kSheet, "test.yaml"));
  REQUIRE(items.size() == 1);
  return items.front();
}

nlohmann::json json_item(const MeasuredParameter& p) {
  const DataSheet sheet = parse_data_sheet(kSheet, "test.yaml");
  const auto doc = nlohmann::json::parse(compliance_json(check_compliance({p}, sheet), sheet, {}));
  REQUIRE(doc["items"].size() == 1);
  return doc["items"][0];
}

/// analyze's results.json around a compliance section and a fit of channel gx.
nlohmann::json results_with(const nlohmann::json& compliance, double p_value,
                            const nlohmann::json& warnings) {
  const nlohmann::json b = {{"value", 4.5 * kDegPerHour},
                            {"ci_low", 4.0 * kDegPerHour},
                            {"ci_high", 5.0 * kDegPerHour}};
  return {{"tool", "sigmatau"},
          {"version", "test"},
          {"confidence", 0.95},
          {"input", {{"path", "log.csv"}}},
          {"channels", {{{"name", "gx"}, {"sensor", "gyro"}, {"allan", nlohmann::json::array()}}}},
          {"fit",
           {{"channels", {{{"name", "gx"}, {"p_value", p_value}, {"parameters", {{"B", b}}}}}}}},
          {"compliance", compliance},
          {"warnings", warnings}};
}

nlohmann::json compliance_of(const MeasuredParameter& p) {
  const DataSheet sheet = parse_data_sheet(kSheet, "test.yaml");
  return nlohmann::json::parse(compliance_json(check_compliance({p}, sheet), sheet, {}));
}

ReportFiles report_of(const nlohmann::json& results) {
  ReportOptions options;
  options.plots = false;
  return build_report(results.dump(), options);
}

}  // namespace

TEST_CASE("a fail whose lower bound is within the limit is a fail within uncertainty") {
  const ComplianceItem close = only_item(white(1.01, 0.98, 1.04, 0.5));
  CHECK(close.verdict == Verdict::fail);
  CHECK(fail_within_uncertainty(close));
  CHECK(close.margin_low == test::rel(0.98, kRoundingTolerance));
  const ComplianceItem clear = only_item(white(1.2, 1.1, 1.3, 0.5));
  CHECK(clear.verdict == Verdict::fail);
  CHECK_FALSE(fail_within_uncertainty(clear));
  // A pass or marginal is never marked, and the exit-status rule is unchanged.
  CHECK_FALSE(fail_within_uncertainty(only_item(white(0.99, 0.96, 1.02, 0.5))));
  CHECK(any_failed({close}));

  const nlohmann::json j = json_item(white(1.01, 0.98, 1.04, 0.5));
  CHECK(j["within_uncertainty"] == true);
  CHECK(j["margin_low"].get<double>() == test::rel(0.98, kRoundingTolerance));
  CHECK(j["compared_low"].get<double>() == test::rel(0.98 * kArwLimit, kRoundingTolerance));
  CHECK(json_item(white(1.2, 1.1, 1.3, 0.5))["within_uncertainty"] == false);
}

TEST_CASE("the lower bound of a bias instability is compared as its floor 0.664 B_low") {
  const MeasuredParameter b{.sensor = Sensor::gyro,
                            .quantity = MeasuredQuantity::bias_instability,
                            .axis = "x",
                            .value = 4.6 * kDegPerHour,
                            .ci_low = 4.4 * kDegPerHour,
                            .ci_high = 5.0 * kDegPerHour};
  const ComplianceItem item = only_item(b);
  CHECK(item.verdict == Verdict::fail);  // 0.664 x 4.6 = 3.06 > 3
  CHECK(item.compared_low == test::rel(kFlickerFloorFactor * 4.4 * kDegPerHour, kRoundingTolerance));
  CHECK(fail_within_uncertainty(item));  // 0.664 x 4.4 = 2.92 <= 3
}

TEST_CASE("a verdict from a rejected fit is marked, with its p value") {
  CHECK(fit_rejected(white(1, 1, 1, 0.0)));
  CHECK_FALSE(fit_rejected(white(1, 1, 1, kMisfitPValue)));  // at the threshold: kept
  CHECK_FALSE(fit_rejected(white(1, 1, 1, std::numeric_limits<double>::quiet_NaN())));
  CHECK(verdict_text("fail", false, 0.0) == "fail (fit rejected, p = 0)");
  CHECK(verdict_text("fail", true, 2e-5) == "fail (within uncertainty; fit rejected, p = 2e-05)");
  CHECK(verdict_text("pass", false, 0.4) == "pass");

  const nlohmann::json rejected = json_item(white(2, 1.9, 2.1, 0.0));
  CHECK(rejected["fit_rejected"] == true);
  CHECK(rejected["fit_p_value"] == 0.0);
  CHECK(json_item(white(2, 1.9, 2.1, 0.3))["fit_rejected"] == false);
  // No p value known (a calibration, a slopes fit): no claim either way.
  CHECK_FALSE(json_item(white(2, 1.9, 2.1, std::numeric_limits<double>::quiet_NaN()))
                  .contains("fit_rejected"));
}

TEST_CASE("a fit result's p value and channel names reach the measured parameters") {
  const std::string fit = R"json({"channels":[
    {"name":"gyro_y","p_value":0.0,"method":"joint",
     "parameters":{"N":{"value":1e-4,"ci_low":0.9e-4,"ci_high":1.1e-4}}},
    {"name":"acc_z","p_value":0.42,"method":"joint",
     "parameters":{"N":{"value":1e-3,"ci_low":0.9e-3,"ci_high":1.1e-3}}},
    {"name":"imu_x","quantity":"angular_rate","method":"slopes","p_value":0.0,
     "parameters":{"N":{"value":1e-4,"ci_low":0.9e-4,"ci_high":1.1e-4}}}]})json";
  const auto measured = measured_parameters_from_json(fit, "fit.json");
  REQUIRE(measured.size() == 3);
  // Read by classify_channel, the one column-name rule (it used to be the first letter).
  CHECK(measured[0].sensor == Sensor::gyro);
  CHECK(measured[0].axis == "y");
  CHECK(fit_rejected(measured[0]));
  CHECK(measured[1].sensor == Sensor::accel);
  CHECK(measured[1].axis == "z");
  CHECK(measured[1].fit_p_value == 0.42);
  // The quantity decides before the name ("imu_x" says nothing); a slopes fit has no p value.
  CHECK(measured[2].sensor == Sensor::gyro);
  CHECK(measured[2].axis == "x");
  CHECK(std::isnan(measured[2].fit_p_value));

  // A name classify_channel knows but the first-letter rule did not.
  const auto omega = measured_parameters_from_json(
      R"json({"channels":[{"name":"omega_z","parameters":{"N":{"value":1e-4,"ci_low":0.9e-4,"ci_high":1.1e-4}}}]})json",
      "fit.json");
  REQUIRE(omega.size() == 1);
  CHECK(omega[0].sensor == Sensor::gyro);
  CHECK(omega[0].axis == "z");
  CHECK_THROWS_WITH_AS(measured_parameters_from_json(
                           R"json({"channels":[{"name":"temperature","parameters":{}}]})json",
                           "fit.json"),
                       doctest::Contains("temperature"), Error);
}

TEST_CASE("the report opens with a warning banner naming rejected fits and implausible units") {
  const nlohmann::json warnings = {
      "gx: no model of these noise terms describes the curve (p = 0)",
      "gx: a static gyro reading a mean rate of 1 rad/s (1 rad/s) is implausible (more than 0.1 "
      "rad/s); the data look like deg/s, not rad/s"};
  const ReportFiles files =
      report_of(results_with(compliance_of(white(2, 1.9, 2.1, 0.0)), 0.0, warnings));
  const std::string& html = files.files.at("report.html");
  const auto banner = html.find("id=\"warning-banner\"");
  REQUIRE(banner != std::string::npos);
  CHECK(banner < html.find("<h2 id=\"summary\">"));  // at the top, before any table
  CHECK(html.find("2 warnings; fit rejected for gx", banner) != std::string::npos);
  CHECK(html.find("implausible units for gx", banner) != std::string::npos);
  CHECK(html.find("<a href=\"#warnings\">", banner) != std::string::npos);
  CHECK(html.find("<h2 id=\"warnings\">") != std::string::npos);
  const std::string& md = files.files.at("summary.md");
  const auto md_banner = md.find("> **Warning:** 2 warnings; fit rejected for gx");
  REQUIRE(md_banner != std::string::npos);
  CHECK(md_banner < md.find("| channel |"));

  // The compliance row on that fit says so, and the note explains it.
  CHECK(md.find("| gyro white noise x | fail (fit rejected, p = 0) |") != std::string::npos);
  CHECK(md.find(kFitRejectedNote) != std::string::npos);
  CHECK(html.find("<td>fail (fit rejected, p = 0)</td>") != std::string::npos);

  // No warnings, no banner.
  const ReportFiles quiet = report_of(
      results_with(compliance_of(white(2, 1.9, 2.1, 0.5)), 0.5, nlohmann::json::array()));
  CHECK(quiet.files.at("report.html").find("warning-banner") == std::string::npos);
  CHECK(quiet.files.at("summary.md").find("**Warning:**") == std::string::npos);
  CHECK(quiet.files.at("summary.md").find("fit rejected") == std::string::npos);
}

TEST_CASE("the compliance tables give values in units with intervals, and mark a fail within uncertainty") {
  const ReportFiles files = report_of(
      results_with(compliance_of(white(1.01, 0.98, 1.04, 0.5)), 0.5, nlohmann::json::array()));
  const std::string& md = files.files.at("summary.md");
  // 1.01 x 0.2 deg/sqrt(h) = 0.202 [0.196, 0.208]; the ratio with its interval.
  CHECK(md.find("| gyro white noise x | fail (within uncertainty) | 0.202 [0.196, 0.208] °/√h | "
                "0.2 °/√h (max) | 1.01 [0.980, 1.04] |") != std::string::npos);
  CHECK(md.find(kWithinUncertaintyNote) != std::string::npos);  // the rule, where verdicts are explained
  const std::string& html = files.files.at("report.html");
  CHECK(html.find("<td>fail (within uncertainty)</td><td>0.202 [0.196, 0.208] °/√h</td>") !=
        std::string::npos);
}

TEST_CASE("with a data sheet, B is shown with its floor 0.664 B next to the limit") {
  const MeasuredParameter b{.sensor = Sensor::gyro,
                            .quantity = MeasuredQuantity::bias_instability,
                            .axis = "x",
                            .value = 4.5 * kDegPerHour,
                            .ci_low = 4.0 * kDegPerHour,
                            .ci_high = 5.0 * kDegPerHour};
  const ReportFiles files = report_of(results_with(compliance_of(b), 0.5, nlohmann::json::array()));
  const std::string& md = files.files.at("summary.md");
  // 0.664 x 4.5 = 2.989, 0.664 x [4, 5] = [2.657, 3.321] deg/h.
  CHECK(md.find("4.5 [4, 5] deg/h (floor 0.664 B = 2.989 [2.657, 3.321])") != std::string::npos);
  CHECK(md.find("| 0.664 B = 2.989 [2.657, 3.321] °/h | 3 °/h (max) |") != std::string::npos);
  // Without a sheet the summary shows the coefficient alone.
  nlohmann::json no_sheet = results_with(compliance_of(b), 0.5, nlohmann::json::array());
  no_sheet["compliance"] = nullptr;
  CHECK(report_of(no_sheet).files.at("summary.md").find("floor 0.664 B =") == std::string::npos);
}

TEST_CASE("the compliance chart has a colour key, the interval's level, typ / max, and an arrow for a bound") {
  if (!gnuplot_available()) {
    MESSAGE("gnuplot not found: compliance chart check skipped");
    return;
  }
  const DataSheet sheet = parse_data_sheet(kSheet, "test.yaml");
  const MeasuredParameter bound{.sensor = Sensor::gyro,
                                .quantity = MeasuredQuantity::bias_instability,
                                .axis = "x",
                                .detected = false,
                                .upper_bound = 9.0 * kDegPerHour};
  const auto items = check_compliance({white(0.5, 0.45, 0.55, 0.5), bound}, sheet);
  const nlohmann::json compliance = nlohmann::json::parse(compliance_json(items, sheet, {}));
  ReportOptions options;
  options.plot_format = PlotFormat::svg;
  const ReportFiles files =
      build_report(results_with(compliance, 0.5, nlohmann::json::array()).dump(), options);
  REQUIRE(files.files.count("compliance.svg") == 1);
  const std::string& svg = files.files.at("compliance.svg");
  for (const char* key : {">pass<", ">marginal<", ">fail<", ">inconclusive<", ">not detected (upper bound)<"}) {
    CHECK_MESSAGE(svg.find(key) != std::string::npos, key);
  }
  CHECK(svg.find("bar: 95 % confidence interval") != std::string::npos);  // results' level
  CHECK(svg.find("gyro white noise x (max)") != std::string::npos);
  CHECK(svg.find("gyro bias instability x (max), not detected") != std::string::npos);

  // With every term detected the key has no arrow entry.
  const auto detected = check_compliance({white(0.5, 0.45, 0.55, 0.5)}, sheet);
  const ReportFiles plain = build_report(
      results_with(nlohmann::json::parse(compliance_json(detected, sheet, {})), 0.5,
                   nlohmann::json::array())
          .dump(),
      options);
  CHECK(plain.files.at("compliance.svg").find("not detected (upper bound)") == std::string::npos);
}

TEST_CASE("the ADEV plot keys every fitted term once, whichever channel keeps it, each in its own colour") {
  if (!gnuplot_available()) {
    MESSAGE("gnuplot not found: ADEV legend check skipped");
    return;
  }
  const std::vector<double> taus = {0.01, 0.1, 1.0, 10.0, 100.0};
  nlohmann::json points = nlohmann::json::array();
  std::vector<double> white_line, walk_line;
  for (const double tau : taus) {
    const double dev = 1e-4 / std::sqrt(tau);
    points.push_back({{"tau", tau}, {"dev", dev}, {"ci_low", 0.9 * dev}, {"ci_high", 1.1 * dev}});
    white_line.push_back(dev);
    walk_line.push_back(1e-6 * std::sqrt(tau));
  }
  const nlohmann::json allan = {{{"statistic", "oadev"}, {"points", points}}};
  const nlohmann::json model = {{"tau", taus}, {"adev", white_line}};
  // gx keeps N only, gy keeps N and K: the K line used to have no key entry.
  const nlohmann::json results = {
      {"tool", "sigmatau"},
      {"version", "test"},
      {"input", {{"path", "log.csv"}}},
      {"channels",
       {{{"name", "gx"}, {"sensor", "gyro"}, {"allan", allan}},
        {{"name", "gy"}, {"sensor", "gyro"}, {"allan", allan}}}},
      {"fit",
       {{"channels",
         {{{"name", "gx"},
           {"parameters", nlohmann::json::object()},
           {"model_adev", model},
           {"terms_adev", {{"N", white_line}}}},
          {{"name", "gy"},
           {"parameters", nlohmann::json::object()},
           {"model_adev", model},
           {"terms_adev", {{"N", white_line}, {"K", walk_line}}}}}}}}};
  ReportOptions options;
  options.plot_format = PlotFormat::svg;
  const ReportFiles files = build_report(results.dump(), options);
  REQUIRE(files.files.count("adev_gyro.svg") == 1);
  const std::string& svg = files.files.at("adev_gyro.svg");
  CHECK(svg.find(">K term<") != std::string::npos);
  // Keyed once: as often as a channel's own key entry (the SVG repeats each key text).
  const auto count = [&svg](const std::string& text) {
    std::size_t n = 0;
    for (auto at = svg.find(text); at != std::string::npos; at = svg.find(text, at + 1)) ++n;
    return n;
  };
  CHECK(count(">N term<") == count(">gx<"));
  CHECK(count(">K term<") == count(">gx<"));
  // Distinct colours per term (SVG writes them as rgb(r, g, b)): N cyan, K brown.
  CHECK(svg.find("rgb( 23, 190, 207)") != std::string::npos);
  CHECK(svg.find("rgb(140,  86,  75)") != std::string::npos);
}

TEST_CASE("report: a Gauss-Markov sum draws one keyed curve per entry, each its own colour") {
  const std::vector<double> taus{0.01, 0.1, 1, 10, 100};
  nlohmann::json points = nlohmann::json::array();
  std::vector<double> total, gm1, gm2;
  NoiseTerms t;
  t.gauss_markov = {GaussMarkov{1e-4, 0.5}, GaussMarkov{5e-5, 20.0}};
  for (const double tau : taus) {
    const double dev = std::sqrt(continuous_avar(t, tau));
    points.push_back({{"tau", tau}, {"dev", dev}, {"ci_low", 0.9 * dev}, {"ci_high", 1.1 * dev}});
    total.push_back(dev);
    gm1.push_back(std::sqrt(continuous_avar(only_gauss_markov(t, 0), tau)));
    gm2.push_back(std::sqrt(continuous_avar(only_gauss_markov(t, 1), tau)));
  }
  const nlohmann::json results = {
      {"tool", "sigmatau"},
      {"version", "test"},
      {"input", {{"path", "log.csv"}}},
      {"channels",
       {{{"name", "gx"},
         {"sensor", "gyro"},
         {"allan", {{{"statistic", "oadev"}, {"points", points}}}}}}},
      {"fit",
       {{"channels",
         {{{"name", "gx"},
           {"parameters", nlohmann::json::object()},
           {"model_adev", {{"tau", taus}, {"adev", total}}},
           {"terms_adev", {{"GM1", gm1}, {"GM2", gm2}}}}}}}}};
  ReportOptions options;
  options.plot_format = PlotFormat::svg;
  const ReportFiles files = build_report(results.dump(), options);
  REQUIRE(files.files.count("adev_gyro.svg") == 1);
  const std::string& svg = files.files.at("adev_gyro.svg");
  CHECK(svg.find(">GM1 term<") != std::string::npos);
  CHECK(svg.find(">GM2 term<") != std::string::npos);
  CHECK(svg.find("rgb(255, 127,  14)") != std::string::npos);  // GM1 orange
  CHECK(svg.find("rgb(196, 156,   0)") != std::string::npos);  // GM2 dark yellow
}
