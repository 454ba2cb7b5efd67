// A saved `sigmatau adev --format json` result read back for fit (saved_adev.hpp).
#include "sigmatau/saved_adev.hpp"

#include <doctest/doctest.h>

#include "sigmatau/error.hpp"
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
  CHECK_THROWS_WITH_AS(read_adev_json(R"({"input":{"rate_hz":0,"samples":1000},"results":[]})", "x.json"),
                       doctest::Contains("input.rate_hz must be a number > 0"), Error);
  CHECK_THROWS_WITH_AS(
      read_adev_json(R"({"input":{"rate_hz":100,"samples":1000},"results":[{"statistic":"mdev"}]})", "x.json"),
      doctest::Contains("no oadev"), Error);
  CHECK_THROWS_WITH_AS(
      read_adev_json(R"({"input":{"rate_hz":100,"samples":1000},"results":[{"statistic":"oadev","channel":"gx","points":[{"tau":0.01}]}]})",
                     "x.json"),
      doctest::Contains("results[0].points[0].m"), Error);
}

TEST_CASE("a file is taken for JSON by its first character that is not blank") {
  CHECK(looks_like_json("  \n\t{\"input\": 1}"));
  CHECK_FALSE(looks_like_json("t,gx,gy\n0,1,2\n"));
  CHECK_FALSE(looks_like_json("   "));
  CHECK_FALSE(looks_like_json(""));
}
