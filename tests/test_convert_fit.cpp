// Triads for the filter conversion from a noise-term fit result.
#include <cstdio>
#include <string>

#include "sigmatau/convert.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/filter_export.hpp"
#include "test_support.hpp"

using namespace sigmatau;

TEST_CASE("a fit result becomes triads; a bias term kept on some axes gets its bound elsewhere") {
  const char* fit = R"json({"channels":[
    {"name":"gx","quantity":"angular_rate","parameters":{"N":{"value":1e-4,"ci_low":9e-5,"ci_high":1.1e-4},
      "B":{"value":3e-6,"ci_low":2e-6,"ci_high":4e-6},"K":{"upper_bound":2e-7}}},
    {"name":"gy","quantity":"angular_rate","parameters":{"N":{"value":2e-4,"ci_low":1.9e-4,"ci_high":2.1e-4},
      "B":{"upper_bound":5e-6},"K":{"upper_bound":3e-7}}},
    {"name":"az","quantity":"specific_force","parameters":{"N":{"value":1e-3,"ci_low":9e-4,"ci_high":1.1e-3},
      "K":{"value":4e-5,"ci_low":3e-5,"ci_high":5e-5}}}]})json";
  const auto triads = triads_from_fit_json(fit, "fit.json");
  REQUIRE(triads.size() == 2);
  const TriadNoise& gyro = triads[0];
  CHECK(gyro.sensor == Sensor::gyro);
  CHECK(*gyro.axes[0].white == 1e-4);
  CHECK(*gyro.axes[1].white == 2e-4);
  CHECK(*gyro.axes[0].bias_instability == 3e-6);
  CHECK(*gyro.axes[1].bias_instability == 5e-6);  // not kept on y: its upper bound
  CHECK_FALSE(gyro.axes[0].rate_random_walk.has_value());  // K kept nowhere: stays absent
  CHECK(gyro.bias_instability_is_bound[1]);
  CHECK_FALSE(gyro.bias_instability_is_bound[0]);
  CHECK(*gyro.axes[2].white == 2e-4);  // no gz channel: the largest measured axis stands in
  CHECK(*gyro.axes[2].bias_instability == 5e-6);
  CHECK(gyro.white_origin.find("axes z not in the fit") != std::string::npos);
  const TriadNoise& accel = triads[1];
  CHECK(accel.sensor == Sensor::accel);
  CHECK(*accel.axes[2].rate_random_walk == 4e-5);
  CHECK(*accel.axes[0].white == 1e-3);  // az alone: copied to x and y

  // The filter files say that a bound stands in: it is not a measured value.
  ConvertOptions o;
  o.rate_hz = 100;
  const std::string kalibr =
      export_filter_config(convert_noise(triads, o, "fit.json"), ExportFormat::kalibr);
  // z has no channel and takes y's B, a bound: the file says so for both.
  CHECK(kalibr.find("# gyro bias: from the noise-term fit; B on axes y, z: not detected, its "
                    "upper bound used") != std::string::npos);
  CHECK(kalibr.find("# accel bias:") == std::string::npos);  // accel K measured on its axis
}

TEST_CASE("a triad with neither B nor K kept gets both upper bounds, so a filter file is complete") {
  // A short log: white noise only. Kalibr needs a random walk, and the bound is what the log
  // says of it; before, the key was left out ("not given").
  const char* fit = R"json({"channels":[
    {"name":"gx","quantity":"angular_rate","parameters":{"N":{"value":1e-4,"ci_low":9e-5,"ci_high":1.1e-4},
      "B":{"upper_bound":4e-6},"K":{"upper_bound":2e-6}}},
    {"name":"gy","quantity":"angular_rate","parameters":{"N":{"value":1e-4,"ci_low":9e-5,"ci_high":1.1e-4},
      "B":{"upper_bound":5e-6},"K":{"upper_bound":3e-6}}},
    {"name":"gz","quantity":"angular_rate","parameters":{"N":{"value":1e-4,"ci_low":9e-5,"ci_high":1.1e-4},
      "B":{"upper_bound":6e-6},"K":{"upper_bound":1e-6}}}]})json";
  const auto triads = triads_from_fit_json(fit, "fit.json");
  REQUIRE(triads.size() == 1);
  const TriadNoise& gyro = triads[0];
  CHECK(gyro.bias_from_upper_bound);
  CHECK(*gyro.axes[1].rate_random_walk == 3e-6);
  CHECK(*gyro.axes[2].bias_instability == 6e-6);
  CHECK(gyro.no_bias_term_detected);
  ConvertOptions o;
  o.rate_hz = 100;
  const std::string kalibr =
      export_filter_config(convert_noise(triads, o, "fit.json"), ExportFormat::kalibr);
  CHECK(kalibr.find("neither B nor K detected on any axis: K's upper bound used on every axis") !=
        std::string::npos);
  CHECK(kalibr.find("\ngyroscope_random_walk: 3.0") != std::string::npos);  // the largest axis
  CHECK(kalibr.find("gyroscope_random_walk: not given") == std::string::npos);
}

TEST_CASE("a rule-of-thumb K above the fit's own bound on K says by how much") {
  // B kept on every axis, K on none: K comes from B by the rule of thumb, 0.664 B / sqrt(T_ref),
  // which can exceed the bound the same fit gives for K (the ADIS16405 accelerometers: 3.8x).
  const auto fit_with_k_bound = [](double k_bound) {
    char bound[32];
    std::snprintf(bound, sizeof bound, "%g", k_bound);
    std::string axes;
    for (const char* name : {"gx", "gy", "gz"}) {
      axes += std::string(axes.empty() ? "" : ",") + R"({"name":")" + name +
              R"(","quantity":"angular_rate","parameters":{"N":{"value":1e-4,"ci_low":9e-5,"ci_high":1.1e-4},)" +
              R"("B":{"value":3e-6,"ci_low":2e-6,"ci_high":4e-6},"K":{"upper_bound":)" +
              bound + "}}}";
    }
    return R"({"channels":[)" + axes + "]}";
  };
  ConvertOptions o;
  o.rate_hz = 100;  // T_ref 100 s: K = 0.664 x 3e-6 / 10 = 1.99e-7 (kFlickerFloorFactor 0.66428)
  const double k_rule = kFlickerFloorFactor * 3e-6 / 10;
  const auto triads = triads_from_fit_json(fit_with_k_bound(1e-8), "fit.json");
  REQUIRE(triads[0].rate_random_walk_bound.has_value());
  const DiscreteNoise above = convert_noise(triads, o, "fit.json");
  char expected[64];
  std::snprintf(expected, sizeof expected, "K is %.3g times that", k_rule / 1e-8);
  const std::string kalibr = export_filter_config(above, ExportFormat::kalibr);
  CHECK(kalibr.find("# gyro bias: the fit bounds K below 1e-08 rad/s^2/sqrt(Hz)") != std::string::npos);
  CHECK(kalibr.find(expected) != std::string::npos);
  // A bound above the rule's K: nothing to say.
  const DiscreteNoise below = convert_noise(triads_from_fit_json(fit_with_k_bound(1e-6), "fit.json"), o, "fit.json");
  CHECK(below.gyro->bias_note.empty());
}

TEST_CASE("an analyze results.json is read through its fit section") {
  const char* results = R"json({"tool":"sigmatau","channels":[{"name":"gx","allan":[]}],
    "fit":{"channels":[{"name":"gx","quantity":"angular_rate","parameters":{"N":{"value":1e-4}}}]}})json";
  const auto triads = triads_from_fit_json(results, "results.json");
  REQUIRE(triads.size() == 1);
  CHECK(*triads[0].axes[0].white == 1e-4);
}

TEST_CASE("results that are not a fit are refused with the file named") {
  CHECK_THROWS_WITH_AS(triads_from_fit_json("{\"x\":1}", "a.json"), doctest::Contains("a.json: not a sigmatau fit"), Error);
  CHECK_THROWS_WITH_AS(triads_from_fit_json("[1,", "b.json"), doctest::Contains("not valid JSON"), Error);
  CHECK_THROWS_WITH_AS(
      triads_from_fit_json(R"json({"channels":[{"name":"temp","parameters":{}}]})json", "c.json"),
      doctest::Contains("temp"), Error);
}

TEST_CASE("typed terms replace a source's for their sensor and add a sensor it lacks") {
  // A gyro fit whose B is a bound on y and K a bound everywhere, and no accelerometer.
  const char* fit = R"json({"channels":[
    {"name":"gx","quantity":"angular_rate","parameters":{"N":{"value":1e-4,"ci_low":9e-5,"ci_high":1.1e-4},
      "B":{"value":3e-6,"ci_low":2e-6,"ci_high":4e-6},"K":{"upper_bound":2e-7}}},
    {"name":"gy","quantity":"angular_rate","parameters":{"N":{"value":2e-4,"ci_low":1.9e-4,"ci_high":2.1e-4},
      "B":{"upper_bound":5e-6},"K":{"upper_bound":3e-7}}}]})json";
  auto triads = triads_from_fit_json(fit, "fit.json");
  REQUIRE(triads.size() == 1);
  NoiseTerms gyro_k;
  gyro_k.rate_random_walk = 4e-6;
  replace_with_typed_terms(triads, Sensor::gyro, gyro_k, "", "rate random walk K = 4e-6");
  NoiseTerms accel;
  accel.white = 1.5e-3;
  accel.rate_random_walk = 3e-4;
  replace_with_typed_terms(triads, Sensor::accel, accel, "noise density typed", "K typed");
  REQUIRE(triads.size() == 2);
  const TriadNoise& g = triads[0];
  for (const auto& a : g.axes) {
    CHECK(*a.rate_random_walk == 4e-6);
    CHECK_FALSE(a.bias_instability.has_value());  // the typed bias replaces the fit's B
  }
  CHECK(*g.axes[1].white == 2e-4);  // no white noise typed: the fit's stays
  CHECK_FALSE(g.bias_instability_is_bound[1]);
  CHECK_FALSE(g.rate_random_walk_bound.has_value());
  CHECK(g.bias_origin == "rate random walk K = 4e-6 (typed; replaces the source's bias)");
  const TriadNoise& a = triads[1];
  CHECK(a.sensor == Sensor::accel);
  CHECK(*a.axes[2].white == 1.5e-3);
  CHECK(a.white_origin == "noise density typed (typed)");
  // The file now has all four terms, and says no upper bound stands in for the gyro bias.
  ConvertOptions o;
  o.rate_hz = 100;
  const DiscreteNoise noise = convert_noise(triads, o, "fit.json and command-line terms");
  CHECK(missing_filter_keys(noise, ExportFormat::kalibr).empty());
  const std::string kalibr = export_filter_config(noise, ExportFormat::kalibr);
  CHECK(kalibr.find("not detected") == std::string::npos);
  CHECK(kalibr.find("gyroscope_random_walk: 4.0e-06") != std::string::npos);
}
