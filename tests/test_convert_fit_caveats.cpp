// What a filter file says about the fit it rests on (review F findings 1, 3, 10, 11, 12): a fit
// rejected by its goodness of fit, implausible units, the level of an upper bound, the measured
// tau of the ADEV minimum for a Gauss-Markov bias, terms left out, the method used, a filter
// rate above the log's; and the channel-name rule shared with every verb.
#include <nlohmann/json.hpp>

#include <string>

#include "sigmatau/convert.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/filter_export.hpp"
#include "sigmatau/fit.hpp"
#include "test_support.hpp"

using namespace sigmatau;
using nlohmann::json;

namespace {

/// Round-off only: the conversion is a few multiplications of the numbers given.
constexpr double kRoundOff = 1e-12;

/// A fit JSON with gyro channels gx, gy, gz; `extra(axis)` adds fields to each channel.
json gyro_fit(double confidence = 0.95) {
  json doc = {{"confidence", confidence}, {"channels", json::array()}};
  for (const char* name : {"gx", "gy", "gz"}) {
    doc["channels"].push_back(
        {{"name", name},
         {"quantity", "angular_rate"},
         {"method", "joint"},
         {"p_value", 0.4},
         {"misfit_tau_s", 0.01},
         {"parameters",
          {{"N", {{"value", 1e-4}, {"unit", "rad/s/sqrt(Hz)"}}},
           {"B", {{"value", 3e-6}, {"tau_min_s", 300.0}, {"unit", "rad/s"}}},
           {"K", {{"upper_bound", 2e-7}, {"unit", "rad/s^2/sqrt(Hz)"}}}}}});
  }
  return doc;
}

ConvertOptions at(double rate_hz) {
  ConvertOptions o;
  o.rate_hz = rate_hz;
  return o;
}

bool has(const std::string& text, const std::string& part) {
  INFO("looking for: " << part << "\nin:\n" << text);
  return text.find(part) != std::string::npos;
}

const ExportFormat kTextFormats[] = {ExportFormat::kalibr, ExportFormat::openvins,
                                     ExportFormat::vins_fusion, ExportFormat::gtsam,
                                     ExportFormat::px4};

}  // namespace

TEST_CASE("a fit rejected by its goodness of fit is named, with p and advice, in every file") {
  json doc = gyro_fit();
  doc["channels"][0]["p_value"] = 0.0;
  doc["channels"][0]["misfit_at_shortest_taus"] = true;
  doc["channels"][2]["p_value"] = 2e-4;
  doc["channels"][2]["misfit_tau_s"] = 81.92;
  doc["channels"][2]["misfit_at_shortest_taus"] = false;
  const FitForFilter fit = read_fit_for_filter(doc.dump(), "f.json");
  REQUIRE(fit.warnings.size() == 2);  // one line per advice; gy (p = 0.4) is not named
  std::string all;
  for (const auto& w : fit.warnings) all += w + "\n";
  CHECK(has(all, "gx (p = 0, worst at tau = 0.01 s)"));
  CHECK(has(all, "gz (p = 0.0002, worst at tau = 81.92 s)"));
  CHECK_FALSE(has(all, "gy ("));
  CHECK(has(all, "if the sensor filters its output, fit from longer taus (fit / analyze --tau-min)"));
  CHECK(has(all, "fit a tau range without it (fit / analyze --tau-min / --tau-max)"));
  const DiscreteNoise noise = convert_fit(fit, at(100), "f.json");
  for (const ExportFormat format : kTextFormats) {
    CAPTURE(to_string(format));
    const std::string text = export_filter_config(noise, format);
    CHECK(has(text, "# WARNING: the noise-term fit is rejected by its goodness of fit (p < 0.001) on gx"));
    CHECK(has(text, "# WARNING: the noise-term fit is rejected by its goodness of fit (p < 0.001) on gz"));
  }
  const json exported = json::parse(export_filter_config(noise, ExportFormat::json));
  REQUIRE(exported.contains("warnings"));
  CHECK(exported["warnings"].size() == 2);
}

TEST_CASE("a fit at p just above the threshold, or without a p value, gets no warning") {
  json doc = gyro_fit();
  for (auto& c : doc["channels"]) c["p_value"] = kMisfitPValue;  // not below: accepted
  CHECK(read_fit_for_filter(doc.dump(), "f.json").warnings.empty());
  for (auto& c : doc["channels"]) c.erase("p_value");  // the slopes method has none
  CHECK(read_fit_for_filter(doc.dump(), "f.json").warnings.empty());
  const DiscreteNoise noise =
      convert_fit(read_fit_for_filter(doc.dump(), "f.json"), at(100), "f.json");
  // A gyro fit alone: the Kalibr file's only warning is that it lacks the accelerometer's keys.
  const std::string kalibr = export_filter_config(noise, ExportFormat::kalibr);
  CHECK_FALSE(has(kalibr, "rejected"));
  CHECK(has(kalibr, "# WARNING: incomplete: accelerometer_noise_density"));
  CHECK_FALSE(json::parse(export_filter_config(noise, ExportFormat::json)).contains("warnings"));
}

TEST_CASE("the advice covers both causes when the result does not say where the misfit is") {
  json doc = gyro_fit();
  doc["channels"][1]["p_value"] = 1e-9;  // `fit --format json` records no misfit_at_shortest_taus
  const FitForFilter fit = read_fit_for_filter(doc.dump(), "f.json");
  REQUIRE(fit.warnings.size() == 1);
  CHECK(has(fit.warnings[0], "gy (p = 1e-09"));
  CHECK(has(fit.warnings[0], "fit from longer taus (fit / analyze --tau-min), else fit a tau range"));
}

TEST_CASE("analyze's unit-plausibility warnings reach the files") {
  json doc = {{"fit", gyro_fit()}, {"input", {{"rate_hz", 100.0}}}};
  doc["unit_warnings"] = json::array(
      {{{"channels", "gx+gy+gz"}, {"likely_unit", "deg/s"},
        {"message", "gx+gy+gz: a static gyro reading ... the data look like deg/s, not rad/s"}}});
  const FitForFilter fit = read_fit_for_filter(doc.dump(), "results.json");
  REQUIRE(fit.warnings.size() == 1);
  const std::string px4 = export_filter_config(convert_fit(fit, at(100), "r"), ExportFormat::px4);
  CHECK(has(px4, "# WARNING: gx+gy+gz: a static gyro reading ... the data look like deg/s, not "
                 "rad/s; if the declared unit is wrong, every value written from this log is wrong "
                 "by the same factor: give the log's unit (--gyro-unit / --accel-unit)"));
}

TEST_CASE("an upper bound standing in for an undetected term names its level") {
  SUBCASE("fit JSON: top-level confidence 0.95") {
    const DiscreteNoise noise = convert_fit(read_fit_for_filter(gyro_fit(0.95).dump(), "f"), at(100), "f");
    // B kept on every axis, K on none: the random walk comes from B (rule of thumb), no bound.
    CHECK_FALSE(noise.gyro->bias_from_upper_bound);
    json doc = gyro_fit(0.95);
    doc["channels"][1]["parameters"]["K"] = {{"value", 5e-7}};  // K kept on y only
    const std::string kalibr = export_filter_config(
        convert_fit(read_fit_for_filter(doc.dump(), "f"), at(100), "f"), ExportFormat::kalibr);
    CHECK(has(kalibr, "# gyro bias: from the noise-term fit; K on axes x, z: not detected, its 95 % "
                      "upper bound used"));
  }
  SUBCASE("analyze results.json: the fit section's confidence 0.683") {
    json fit = gyro_fit();
    fit.erase("confidence");
    fit["confidence"] = 0.683;
    fit["channels"][1]["parameters"]["K"] = {{"value", 5e-7}};
    const json doc = {{"confidence", 0.683}, {"fit", fit}};
    const std::string kalibr = export_filter_config(
        convert_fit(read_fit_for_filter(doc.dump(), "r"), at(100), "r"), ExportFormat::kalibr);
    CHECK(has(kalibr, "not detected, its 68.3 % upper bound used"));
  }
}

TEST_CASE("a bound of B is not named when the random walk written is K's") {
  // K kept on x and z, B kept on x and y: rw from K, so B's bound on z plays no part (review F
  // finding 11: "B on axis z: not detected" appeared in files whose random walk is K's bound).
  json doc = gyro_fit();
  doc["channels"][0]["parameters"]["K"] = {{"value", 4e-7}};
  doc["channels"][2]["parameters"]["K"] = {{"value", 6e-7}};
  doc["channels"][2]["parameters"]["B"] = {{"upper_bound", 7e-6}};
  const FitForFilter fit = read_fit_for_filter(doc.dump(), "f");
  const DiscreteNoise rw = convert_fit(fit, at(100), "f");
  REQUIRE(rw.gyro->bias);
  CHECK(rw.gyro->bias->source == BiasSource::rate_random_walk);
  const std::string kalibr = export_filter_config(rw, ExportFormat::kalibr);
  CHECK(has(kalibr, "K on axis y: not detected, its 95 % upper bound used"));
  CHECK_FALSE(has(kalibr, "B on axis"));
  // For a Gauss-Markov the bias comes from B: then B's bound is the one named.
  ConvertOptions gm = at(100);
  gm.bias_model = BiasModel::gauss_markov;
  const std::string gm_text = export_filter_config(convert_fit(fit, gm, "f"), ExportFormat::kalibr);
  CHECK(has(gm_text, "B on axis z: not detected, its 95 % upper bound used"));
  CHECK_FALSE(has(gm_text, "K on axis"));
}

TEST_CASE("with neither B nor K detected, the file says which bound the written bias is") {
  json doc = gyro_fit(0.683);
  for (auto& c : doc["channels"]) c["parameters"]["B"] = {{"upper_bound", 4e-6}};
  const FitForFilter fit = read_fit_for_filter(doc.dump(), "f");
  const DiscreteNoise noise = convert_fit(fit, at(100), "f");
  CHECK(noise.gyro->bias->source == BiasSource::rate_random_walk);
  CHECK(has(export_filter_config(noise, ExportFormat::kalibr),
            "neither B nor K detected on any axis: K's 68.3 % upper bound used on every axis (B's "
            "bound plays no part in a random walk from K)"));
}

TEST_CASE("Gauss-Markov: tau_min is each axis's measured ADEV minimum unless one is given") {
  json doc = gyro_fit();
  doc["channels"][0]["parameters"]["B"]["tau_min_s"] = 327.68;
  doc["channels"][1]["parameters"]["B"]["tau_min_s"] = 655.36;
  doc["channels"][2]["parameters"]["B"].erase("tau_min_s");  // not measured on z
  const FitForFilter fit = read_fit_for_filter(doc.dump(), "f");
  ConvertOptions o = at(100);
  o.bias_model = BiasModel::gauss_markov;
  SUBCASE("measured: per axis, z takes the shortest measured") {
    const DiscreteNoise noise = convert_fit(fit, o, "f");
    const BiasDiscrete& b = *noise.gyro->bias;
    SIGMATAU_CHECK_REL(b.tau_c_s(0), 327.68 / kGaussMarkovPeakTau, kRoundOff);
    SIGMATAU_CHECK_REL(b.tau_c_s(1), 655.36 / kGaussMarkovPeakTau, kRoundOff);
    SIGMATAU_CHECK_REL(b.tau_c_s(2), 327.68 / kGaussMarkovPeakTau, kRoundOff);
    const std::string kalibr = export_filter_config(noise, ExportFormat::kalibr);
    CHECK(has(kalibr, "matched at the ADEV minimum at tau = 327.68 s (x), 655.36 s (y), 327.68 s "
                      "(z): the tau of the ADEV minimum the fit measured (none on z: the shortest "
                      "measured used there)"));
    CHECK_FALSE(has(kalibr, "(--tau-min)"));  // analyze has no such option for the GM
    const json j = json::parse(export_filter_config(noise, ExportFormat::json));
    CHECK(j["gyro"]["bias"]["tau_min_s"].size() == 3);
  }
  SUBCASE("given: every axis") {
    o.tau_min_s = 100;
    const DiscreteNoise noise = convert_fit(fit, o, "f");
    SIGMATAU_CHECK_REL(noise.gyro->bias->tau_c_s(1), 100 / kGaussMarkovPeakTau, kRoundOff);
    CHECK(has(export_filter_config(noise, ExportFormat::kalibr),
              "at tau = 100 s: given (convert --tau-min)"));
  }
  SUBCASE("nothing measured: T_ref, and said so") {
    for (auto& c : doc["channels"]) c["parameters"]["B"].erase("tau_min_s");
    const DiscreteNoise noise = convert_fit(read_fit_for_filter(doc.dump(), "f"), o, "f");
    SIGMATAU_CHECK_REL(noise.gyro->bias->tau_c_s(0), kDefaultReferenceTime / kGaussMarkovPeakTau, kRoundOff);
    CHECK(has(export_filter_config(noise, ExportFormat::kalibr),
              "at tau = 100 s: T_ref (convert --tref): no tau of the ADEV minimum measured or given"));
  }
}

TEST_CASE("a rate ramp or quantization kept by the fit is named as left out, with its value") {
  json doc = gyro_fit();
  doc["channels"][0]["parameters"]["R"] = {{"value", 9.77e-6}, {"unit", "rad/s^2"}};
  doc["channels"][2]["parameters"]["Q"] = {{"value", 1.5e-6}, {"unit", "rad"}};
  doc["channels"][1]["parameters"]["R"] = {{"upper_bound", 1e-6}};  // a bound is not kept
  const std::string text = export_filter_config(
      convert_fit(read_fit_for_filter(doc.dump(), "f"), at(100), "f"), ExportFormat::vins_fusion);
  CHECK(has(text, "# note: rate ramp R kept by the fit, left out of this file (a filter has no "
                  "ramp term): gx 9.77e-06 rad/s^2\n"));
  CHECK(has(text, "# note: quantization Q kept by the fit, left out of this file (a filter has no "
                  "quantization term): gz 1.5e-06 rad\n"));
}

TEST_CASE("the header names the fit method whose terms are used") {
  json doc = gyro_fit();
  SUBCASE("joint") {
    CHECK(read_fit_for_filter(doc.dump(), "f").notes.front() ==
          "terms from the joint noise-term fit, bounds and intervals at 95 %");
  }
  SUBCASE("both: the joint terms, and why") {
    doc["channels"][0]["slopes"] = {{"method", "slopes"}, {"parameters", json::object()}};
    const std::string note = read_fit_for_filter(doc.dump(), "f").notes.front();
    CHECK(has(note, "terms from the joint noise-term fit, bounds and intervals at 95 %; the slopes "
                    "results beside it (fit --method both) are not used: the joint fit weighs"));
  }
  SUBCASE("slopes") {
    for (auto& c : doc["channels"]) c["method"] = "slopes";
    const std::string gtsam = export_filter_config(
        convert_fit(read_fit_for_filter(doc.dump(), "f"), at(100), "f"), ExportFormat::gtsam);
    CHECK(has(gtsam, "# note: terms from the slopes fit (fit --method slopes), bounds and "
                     "intervals at 95 %: it has no goodness-of-fit test"));
  }
}

TEST_CASE("channels whose curve read-outs stand in for the joint fit are named in every file") {
  // fit / analyze write "reported_from": "curve_readings" where the joint fit is rejected or
  // contradicted by its curve (fit.hpp, NoiseFit::readings): those channels' terms are read
  // from the curve, which the files say, and not as a "slopes fit" nor as a rejected fit.
  json doc = gyro_fit();
  for (auto& c : doc["channels"]) {
    c["method"] = "slopes";
    c["reported_from"] = "curve_readings";
    c["readings_reason"] = "rejected (p = 0) and contradicted by the curve";
    c.erase("p_value");
  }
  const FitForFilter fit = read_fit_for_filter(doc.dump(), "f");
  CHECK(fit.warnings.empty());
  REQUIRE(fit.notes.size() == 1);
  CHECK(has(fit.notes.front(), "terms of gx (joint fit rejected (p = 0) and contradicted by the "
                               "curve), gy (joint fit"));
  CHECK(has(fit.notes.front(), "read from the ADEV curve itself (IEEE 952: bias stability from "
                               "the curve's minimum"));
  const std::string kalibr = export_filter_config(convert_fit(fit, at(100), "f"), ExportFormat::kalibr);
  CHECK(has(kalibr, "# note: terms of gx"));
}

TEST_CASE("a filter rate above the log's rate says the white level is extrapolated") {
  CHECK(rate_above_log_note(200, 100) ==
        "the filter rate 200 Hz is above the log's sample rate 100 Hz: the white-noise level was "
        "measured only up to 50 Hz (the log's Nyquist frequency) and is extrapolated, as flat, to "
        "100 Hz; a filter's rate should be the IMU's own (Kalibr's update_rate)");
  CHECK(rate_above_log_note(100, 100).empty());
  CHECK(rate_above_log_note(50, 100).empty());
  // A log's rate from its time stamps is a fraction of a percent off its nominal rate.
  CHECK(rate_above_log_note(100, 99.8).empty());
  CHECK(rate_above_log_note(100, 0).empty());  // unknown

  json doc = {{"fit", gyro_fit()}, {"input", {{"rate_hz", 100.0}}}};
  const FitForFilter fit = read_fit_for_filter(doc.dump(), "results.json");
  REQUIRE(fit.log_rate_hz.has_value());
  const DiscreteNoise above = convert_fit(fit, at(200), "r");
  CHECK(has(export_filter_config(above, ExportFormat::kalibr), "# note: the filter rate 200 Hz is above"));
  CHECK(json::parse(export_filter_config(above, ExportFormat::json))["notes"].back() == above.rate_note);
  CHECK(convert_fit(fit, at(100), "r").rate_note.empty());
  // A fit JSON without the log's rate: nothing to compare, nothing said.
  CHECK(convert_fit(read_fit_for_filter(gyro_fit().dump(), "f"), at(1000), "f").rate_note.empty());
}

TEST_CASE("a fit channel's sensor comes from its quantity, else from the column-name rule") {
  SUBCASE("angular_velocity_x is a gyro axis (it used to be read as an accelerometer: 'a')") {
    const json doc = {{"channels",
                       {{{"name", "angular_velocity_x"}, {"parameters", {{"N", {{"value", 1e-4}}}}}},
                        {{"name", "linear_acceleration_y"}, {"parameters", {{"N", {{"value", 2e-3}}}}}}}}};
    const auto triads = triads_from_fit_json(doc.dump(), "f");
    REQUIRE(triads.size() == 2);
    CHECK(triads[0].sensor == Sensor::gyro);
    CHECK(*triads[0].axes[0].white == 1e-4);
    CHECK(triads[1].sensor == Sensor::accel);
    CHECK(*triads[1].axes[1].white == 2e-3);
  }
  SUBCASE("the quantity wins over the name") {
    const json doc = {{"channels",
                       {{{"name", "ax"}, {"quantity", "angular_rate"},
                         {"parameters", {{"N", {{"value", 1e-4}}}}}}}}};
    const auto triads = triads_from_fit_json(doc.dump(), "f");
    REQUIRE(triads.size() == 1);
    CHECK(triads[0].sensor == Sensor::gyro);
  }
  SUBCASE("a name the rule does not know, without a quantity, is refused naming it") {
    const json doc = {{"channels", {{{"name", "angle_x"}, {"parameters", json::object()}}}}};
    CHECK_THROWS_WITH_AS(triads_from_fit_json(doc.dump(), "f.json"),
                         doctest::Contains("channel \"angle_x\": cannot tell its sensor"), Error);
  }
}
