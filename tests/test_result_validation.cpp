// Results handed back to sigmatau are validated (issue 28): a fit result read for the filter
// files (convert --fit, read_fit_for_filter) and for the compliance check (check,
// measured_parameters_from_json), and a calibrate result read by check. Before, a negative N
// was converted and checked, a value of the wrong type was taken as absent (the term silently
// dropped), a bias of the wrong type ended in "unexpected result layout" without its field, and
// a reversed interval went into a verdict. Each bad value is an Error naming file and field. (The
// saved adev JSON: test_saved_adev; data sheets: test_spec.)
#include <doctest/doctest.h>

#include <regex>
#include <string>

#include "sigmatau/compliance.hpp"
#include "sigmatau/convert.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/filter_export.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

/// A fit result of one gyro channel, gx, with `n` as its N term and `extra` added to the channel.
std::string fit_with(const std::string& n, const std::string& extra = "") {
  return R"j({"confidence":0.683,"channels":[{"name":"gx","quantity":"angular_rate","method":"joint",)j" +
         extra + R"j("parameters":{"N":)j" + n +
         R"j(,"B":{"upper_bound":4e-6,"unit":"rad/s"},"K":{"upper_bound":2e-7}}}]})j";
}

constexpr const char* kGoodN =
    R"j({"value":1e-4,"ci_low":9e-5,"ci_high":1.1e-4,"unit":"rad/s/sqrt(Hz)"})j";

using test::error_of;

}  // namespace

TEST_CASE("a fit result is read only when every number of its terms is right, by both readers") {
  // The good one is read by both.
  CHECK(triads_from_fit_json(fit_with(kGoodN), "fit.json").size() == 1);
  CHECK(measured_parameters_from_json(fit_with(kGoodN), "fit.json").size() == 3);
  const struct {
    std::string n, extra, message;
  } kBad[] = {
      {R"j({"value":-1e-4,"ci_low":9e-5,"ci_high":1.1e-4})j", "",
       "fit.json: channels[0] (gx).parameters.N.value: expected a finite number >= 0, got -0.0001"},
      {R"j({"value":"abc","ci_low":9e-5,"ci_high":1.1e-4})j", "",
       "channels[0] (gx).parameters.N.value: expected a finite number >= 0, got \"abc\""},
      {R"j({"value":null,"ci_low":9e-5,"ci_high":1.1e-4})j", "",
       "channels[0] (gx).parameters.N.value: expected a finite number >= 0, got null"},
      {R"j({"value":1e-4,"ci_low":1.1e-4,"ci_high":9e-5})j", "",
       "channels[0] (gx).parameters.N: expected ci_low <= ci_high, got 0.00011 > 9e-05"},
      {R"j({"value":1e-4,"ci_low":-1,"ci_high":1.1e-4})j", "",
       "channels[0] (gx).parameters.N.ci_low: expected a finite number >= 0, got -1"},
      {R"j({"upper_bound":-2e-4})j", "",
       "channels[0] (gx).parameters.N.upper_bound: expected a finite number >= 0, got -0.0002"},
      {"7", "", "channels[0] (gx).parameters.N: expected an object, got 7"},
      {kGoodN, R"j("p_value":2,)j", "channels[0] (gx).p_value: expected a number in [0, 1], got 2"},
      {kGoodN, R"j("p_value":"low",)j", "channels[0] (gx).p_value: expected a number in [0, 1]"},
      {kGoodN, R"j("name":5,)j", "channels[0].name: expected a text, got 5"},
  };
  for (const auto& bad : kBad) {
    CAPTURE(bad.n);
    CAPTURE(bad.extra);
    const std::string text = fit_with(bad.n, bad.extra);
    CHECK(error_of([&] { triads_from_fit_json(text, "fit.json"); }).find(bad.message) !=
          std::string::npos);
    CHECK(error_of([&] { measured_parameters_from_json(text, "fit.json"); }).find(bad.message) !=
          std::string::npos);
  }
  // A B term's tau_min_s (the filter's Gauss-Markov time) must be > 0.
  const std::string tau_min =
      R"j({"confidence":0.683,"channels":[{"name":"gx","quantity":"angular_rate",
    "parameters":{"N":{"value":1e-4,"ci_low":9e-5,"ci_high":1.1e-4},
                  "B":{"value":3e-6,"ci_low":2e-6,"ci_high":4e-6,"tau_min_s":-600}}}]})j";
  CHECK(error_of([&] {
          triads_from_fit_json(tau_min, "fit.json");
        }).find("parameters.B.tau_min_s: expected a finite number > 0, got -600") !=
        std::string::npos);
}

TEST_CASE("a fit result's level and log rate are checked") {
  const std::string level = R"j({"confidence":5,"channels":[{"name":"gx","quantity":"angular_rate",
    "parameters":{"N":{"value":1e-4,"ci_low":9e-5,"ci_high":1.1e-4}}}]})j";
  CHECK(error_of([&] {
          triads_from_fit_json(level, "fit.json");
        }).find("fit.json: confidence: expected a number in (0, 1), got 5") != std::string::npos);
  CHECK(error_of([&] {
          measured_parameters_from_json(level, "fit.json");
        }).find("fit.json: confidence: expected a number in (0, 1), got 5") != std::string::npos);
  const std::string rate = R"j({"input":{"rate_hz":-100},"channels":[{"name":"gx",
    "quantity":"angular_rate","parameters":{"N":{"value":1e-4,"ci_low":9e-5,"ci_high":1.1e-4}}}]})j";
  CHECK(error_of([&] {
          triads_from_fit_json(rate, "fit.json");
        }).find("fit.json: input.rate_hz: expected a finite number > 0, got -100") !=
        std::string::npos);
  // A number beyond a double: "not valid JSON", an Error (exit 2), where it was exit 3.
  CHECK(error_of([&] {
          triads_from_fit_json(fit_with(R"j({"value":1e999})j"), "fit.json");
        }).find("fit.json: not valid JSON") != std::string::npos);
  CHECK(error_of([&] {
          measured_parameters_from_json(fit_with(R"j({"value":1e999})j"), "fit.json");
        }).find("fit.json: not valid JSON") != std::string::npos);
}

TEST_CASE("a calibrate result's biases, scale factors, intervals and matrix are checked") {
  const auto with = [](const std::string& gyro) {
    return R"j({"confidence":0.95,"gyroscope":{)j" + gyro + "}}";
  };
  CHECK(measured_parameters_from_json(
            with(R"j("bias":[0.1,-0.2,0],"bias_ci":[[0,0.2],[-0.3,-0.1],[-0.1,0.1]])j"), "cal.json")
            .size() == 3);
  const struct {
    std::string gyro, message;
  } kBad[] = {
      {R"j("bias":[0.1,"x",0])j",
       "cal.json: gyroscope.bias[1]: expected a finite number, got \"x\""},
      {R"j("bias":[0.1,null,0])j",
       "cal.json: gyroscope.bias[1]: expected a finite number, got null"},
      {R"j("bias":[0.1,0.2])j",
       "gyroscope.bias: expected an array of at least 3 numbers, got [0.1,0.2]"},
      {R"j("bias":[0,0,0],"bias_ci":[[0,1],[0.3,-0.3],[0,1]])j",
       "gyroscope.bias_ci[1]: expected [low, high] with low <= high, got [0.3,-0.3]"},
      {R"j("scale_factor_error":[1e-3,true,0])j",
       "gyroscope.scale_factor_error[1]: expected a finite number"},
      {R"j("matrix":[[1,0,0],[0,"one",0],[0,0,1]])j",
       "gyroscope.matrix[1][1]: expected a finite number"},
      {R"j("matrix":[[1,0,0],[0,1,0],[0,0,1]],"parameters":["G_xx"],"covariance":[[-1]])j",
       "gyroscope.covariance[0][0]: expected a variance >= 0, got -1"},
      {R"j("temperature_coefficients":[{"linear":"hot"}])j",
       "gyroscope.temperature_coefficients[0].linear: expected a finite number, got \"hot\""},
      {R"j("confidence":1.5,"matrix":[[1,0,0],[0,1,0],[0,0,1]])j",
       "gyroscope.confidence: expected a number in (0, 1), got 1.5"},
  };
  for (const auto& bad : kBad) {
    CAPTURE(bad.gyro);
    CHECK(error_of([&] {
            measured_parameters_from_json(with(bad.gyro), "cal.json");
          }).find(bad.message) != std::string::npos);
  }
}

TEST_CASE("a value whose filter numbers overflow is refused, never written as inf or null") {
  ConvertOptions options;
  options.rate_hz = 200;
  // The issue's fit value of 1e308: N^2 f_s overflows. Before, PX4's EKF2_GYR_NOISE read inf
  // and the JSON's variances null.
  const std::string huge_n = fit_with(R"j({"value":1e308,"ci_low":1e308,"ci_high":1e308})j");
  CHECK(
      error_of([&] { convert_fit(read_fit_for_filter(huge_n, "fit.json"), options, "fit.json"); })
          .find("gyro white noise: N = 1e+308 rad/s/sqrt(Hz) gives a variance per sample that "
                "is not finite at 200 Hz (inflation 1, from fit.json)") != std::string::npos);
  // A bias term likewise, given directly.
  NoiseTerms terms;
  terms.white = 1e-3;
  terms.rate_random_walk = 1e300;
  const TriadNoise bias = uniform_triad(Sensor::accel, terms);
  CHECK(error_of([&] {
          convert_noise({bias}, options, "the test");
        }).find("accel bias (rate_random_walk): its variance per step is not finite at 200 Hz") !=
        std::string::npos);
  // Large but finite all the way: every format is written, with no inf, nan or null in it.
  const auto noise =
      convert_fit(read_fit_for_filter(
                      fit_with(R"j({"value":1e150,"ci_low":1e150,"ci_high":1e150})j"), "fit.json"),
                  options, "fit.json");
  for (const ExportFormat format :
       {ExportFormat::kalibr, ExportFormat::openvins, ExportFormat::vins_fusion,
        ExportFormat::gtsam, ExportFormat::px4, ExportFormat::json}) {
    CAPTURE(to_string(format));
    const std::string text = export_filter_config(noise, format);
    // As a word of its own ("inflation", "information" are fine).
    static const std::regex kNotANumber("(^|[^A-Za-z_])(inf|infinity|nan|null)([^A-Za-z_]|$)",
                                        std::regex::icase);
    std::smatch found;
    CHECK_MESSAGE(!std::regex_search(text, found, kNotANumber), found.str());
  }
}
