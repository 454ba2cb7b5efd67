// The report's display units (report_common.cpp, display_units) and fit's table take each noise
// term's unit from one place, display_unit (review G #4): they used to disagree on a gyro's R
// (deg/h/h against deg/h^2) and an accelerometer's K (m/s^3/sqrt(Hz) against m/s/h^1.5).
#include <doctest/doctest.h>

#include <string>

#include "../lib/src/report_common.hpp"  // internal interface under test
#include "sigmatau/display_units.hpp"

using namespace sigmatau;

TEST_CASE("the report's per-term units are display_unit's, for both sensors") {
  for (const Sensor sensor : {Sensor::gyro, Sensor::accel}) {
    const auto u = report_detail::display_units(std::string(to_string(sensor)));
    CAPTURE(to_string(sensor));
    CHECK(u.white == display_unit(NoiseTerm::white, sensor));
    CHECK(u.bias == display_unit(NoiseTerm::bias_instability, sensor));
    CHECK(u.walk == display_unit(NoiseTerm::rate_random_walk, sensor));
    CHECK(u.ramp == display_unit(NoiseTerm::rate_ramp, sensor));
    CHECK(u.quantization == display_unit(NoiseTerm::quantization, sensor));
    CHECK(u.deviation == display_unit(NoiseTerm::bias_instability, sensor));
  }
  CHECK(report_detail::display_units("gyro").ramp == "deg/h^2");
  CHECK(report_detail::display_units("temperature").white.empty());
}
