// Triads for the filter conversion from a noise-term fit result.
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
  CHECK(gyro.bias_origin.find("B on axis y: not detected, its upper bound used") != std::string::npos);
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
  CHECK(kalibr.find("# gyro bias: B / K from the noise-term fit; B on axis y: not detected, its "
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
  CHECK(gyro.bias_origin.find("neither B nor K detected on any axis: their upper bounds used") !=
        std::string::npos);
  ConvertOptions o;
  o.rate_hz = 100;
  const std::string kalibr =
      export_filter_config(convert_noise(triads, o, "fit.json"), ExportFormat::kalibr);
  CHECK(kalibr.find("\ngyroscope_random_walk: 3.0") != std::string::npos);  // the largest axis
  CHECK(kalibr.find("gyroscope_random_walk: not given") == std::string::npos);
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
