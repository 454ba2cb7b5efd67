// A saved `sigmatau adev --format json` result read back for fit (saved_adev.hpp).
#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "sigmatau/error.hpp"
#include "sigmatau/saved_adev.hpp"
#include "test_support.hpp"

using namespace sigmatau;

TEST_CASE("a saved adev result is read back in SI, with the rate as written") {
  const SavedAdev saved = read_adev_json(
      R"({"input":{"rate_hz":100,"samples":1000,"kind":"rate"},"results":[{"channel":"gx","statistic":"oadev","unit":"deg/s","points":[{"tau":0.01,"m":1,"n":999,"dev":1.0,"edf":600,"alpha":0}]},{"channel":"gx","statistic":"mdev","points":[]}]})",
      "x.json");
  CHECK(saved.rate_hz == 100);
  REQUIRE(saved.curves.size() == 1);  // the mdev result is skipped
  CHECK(saved.curves[0].channel == "gx");
  CHECK(saved.curves[0].sensor == Sensor::gyro);
  CHECK(saved.curves[0].source.tau0_s == doctest::Approx(0.01).epsilon(1e-15));
  // Rate samples: the phase has one point more than the samples.
  CHECK(saved.curves[0].source.n_phase_points == 1001);
  // deg/s -> rad/s is pi/180 exactly as units.hpp defines it.
  SIGMATAU_CHECK_REL(saved.curves[0].curve.points[0].value.dev, 3.14159265358979323846 / 180, 1e-15);
  CHECK(saved.curves[0].curve.points[0].confidence.edf == 600);
}

TEST_CASE("a saved adev result of the wrong shape is a clear error naming the file and field") {
  CHECK_THROWS_WITH_AS(read_adev_json(R"({"channels": []})", "x.json"),
                       doctest::Contains("x.json: not a saved"), Error);
  CHECK_THROWS_WITH_AS(read_adev_json("{\"input\":", "x.json"), doctest::Contains("not valid JSON"), Error);
  CHECK_THROWS_WITH_AS(
      read_adev_json(R"({"input":{"rate_hz":0,"samples":1000},"results":[]})", "x.json"),
      doctest::Contains("input.rate_hz: expected a finite number > 0, got 0"), Error);
  CHECK_THROWS_WITH_AS(
      read_adev_json(R"({"input":{"rate_hz":100,"samples":1000},"results":[{"statistic":"mdev"}]})", "x.json"),
      doctest::Contains("no oadev"), Error);
  CHECK_THROWS_WITH_AS(
      read_adev_json(R"({"input":{"rate_hz":100,"samples":1000},"results":[{"statistic":"oadev","channel":"gx","points":[{"tau":0.01}]}]})",
                     "x.json"),
      doctest::Contains("results[0].points[0].m"), Error);
}

TEST_CASE("every number of a saved adev result is checked: type, finiteness, sign, range") {
  // One point, with one field replaced by a bad value each time: before, a dev of "abc" was read
  // as NaN (the point silently dropped from the fit) and -1 as a deviation of -1 unit.
  const auto with = [](const std::string& input, const std::string& result,
                       const std::string& point) {
    return R"({"input":{"rate_hz":100,"samples":1000)" + input +
           R"(},"results":[{"channel":"gx","statistic":"oadev","unit":"deg/s")" + result +
           R"(,"points":[{"tau":0.01,"m":1,"n":999,"edf":600,"alpha":0,"ci_low":0.9,"ci_high":1.1,)" +
           point + "}]}]}";
  };
  CHECK(read_adev_json(with("", "", R"("dev":1.0)"), "x.json").curves.size() == 1);
  const struct {
    std::string input, result, point, message;
  } kBad[] = {
      {"", "", R"("dev":"abc")",
       "x.json: results[0].points[0].dev: expected a finite number >= 0, got \"abc\""},
      {"", "", R"("dev":-1)", "results[0].points[0].dev: expected a finite number >= 0, got -1"},
      {"", "", R"("dev":1e999)",
       "x.json: not valid JSON ([json.exception.out_of_range.406] number overflow"},  // was exit 3
      {"", "", R"("dev":true)",
       "results[0].points[0].dev: expected a finite number >= 0, got true"},
      {"", "", R"("dev":1,"tau":-0.01)",
       "results[0].points[0].tau: expected a finite number > 0, got -0.01"},
      {"", "", R"("dev":1,"m":1.5)",
       "results[0].points[0].m: expected an integer in [1, 1000], got 1.5"},
      {"", "", R"("dev":1,"m":0)",
       "results[0].points[0].m: expected an integer in [1, 1000], got 0"},
      {"", "", R"("dev":1,"n":-3)",
       "results[0].points[0].n: expected an integer in [0, 1000], got -3"},
      {"", "", R"("dev":1,"edf":-3)",
       "results[0].points[0].edf: expected a finite number > 0, got -3"},
      {"", "", R"("dev":1,"alpha":"x")",
       "results[0].points[0].alpha: expected an integer in [-2, 2], got \"x\""},
      {"", "", R"("dev":1,"ci_high":"wide")",
       "results[0].points[0].ci_high: expected a finite number >= 0"},
      {"", R"(,"confidence":2)", R"("dev":1)",
       "results[0].confidence: expected a number in (0, 1), got 2"},
      {R"(,"kind":"voltage")", "", R"("dev":1)",
       "input.kind: data kind must be rate, increment or phase"},
      {R"(,"kind":7)", "", R"("dev":1)", "input.kind: expected a text, got 7"},
  };
  for (const auto& bad : kBad) {
    CAPTURE(bad.point);
    CHECK_THROWS_WITH_AS(read_adev_json(with(bad.input, bad.result, bad.point), "x.json"),
                         doctest::Contains(bad.message.c_str()), Error);
  }
  CHECK_THROWS_WITH_AS(
      read_adev_json(R"({"input":{"rate_hz":100,"samples":-5},"results":[]})", "x.json"),
      doctest::Contains("input.samples: expected an integer in [2, "), Error);
  // null is what adev writes where it could not compute a value: still read, as no value.
  const SavedAdev undefined = read_adev_json(with("", "", R"("dev":null,"edf":null)"), "x.json");
  CHECK(std::isnan(undefined.curves[0].curve.points[0].value.dev));
}

TEST_CASE("a file is taken for JSON by its first character that is not blank") {
  CHECK(looks_like_json("  \n\t{\"input\": 1}"));
  CHECK_FALSE(looks_like_json("t,gx,gy\n0,1,2\n"));
  CHECK_FALSE(looks_like_json("   "));
  CHECK_FALSE(looks_like_json(""));
}
