// si_unit (display_units.hpp), the one spelling of each noise term's SI unit that fit's JSON, the
// simulation sidecar, the conversion's arithmetic and the Kalibr-style filter files print: every
// string must parse (units.hpp) to factor 1 and the term's own dimension, or a reader of those
// files converting it back would get the value wrong.
#include <doctest/doctest.h>

#include <string>

#include "sigmatau/display_units.hpp"
#include "sigmatau/units.hpp"

using namespace sigmatau;

namespace {

struct Expected {
  NoiseTerm term;
  Dimension gyro;
  Dimension accel;
};

}  // namespace

TEST_CASE("each noise term's SI unit parses to factor 1 and the term's dimension") {
  // Gauss-Markov sigma and sinusoid amplitude are in the sensor's output (rate) unit, as B.
  const Expected expected[] = {
      {NoiseTerm::quantization, dim::angle, dim::velocity},
      {NoiseTerm::white, dim::angle_random_walk, dim::velocity_random_walk},
      {NoiseTerm::bias_instability, dim::angular_rate, dim::acceleration},
      {NoiseTerm::rate_random_walk, dim::gyro_rate_random_walk, dim::accel_rate_random_walk},
      {NoiseTerm::rate_ramp, dim::angular_rate_ramp, dim::acceleration_ramp},
      {NoiseTerm::gauss_markov, dim::angular_rate, dim::acceleration},
      {NoiseTerm::sinusoid, dim::angular_rate, dim::acceleration},
  };
  CHECK(std::size(expected) == kAllNoiseTerms.size());
  for (const Expected& e : expected) {
    for (const Sensor sensor : {Sensor::gyro, Sensor::accel}) {
      const std::string unit(si_unit(e.term, sensor));
      CAPTURE(to_string(e.term));
      CAPTURE(to_string(sensor));
      CAPTURE(unit);
      const Unit parsed = parse_unit(unit);
      // SI units: the factor is 1 exactly (parse_unit multiplies exact factors of 1).
      CHECK(parsed.factor == 1.0);
      CHECK(parsed.offset == 0.0);
      CHECK(parsed.dimension == (sensor == Sensor::gyro ? e.gyro : e.accel));
    }
  }
}

TEST_CASE("the SI units are spelled as the files written so far spell them") {
  // These strings are in users' saved fit results, sidecars and filter files: a new spelling of
  // the same unit would still parse, but would change every file byte for byte.
  CHECK(si_unit(NoiseTerm::white, Sensor::gyro) == "rad/s/sqrt(Hz)");
  CHECK(si_unit(NoiseTerm::white, Sensor::accel) == "m/s^2/sqrt(Hz)");
  CHECK(si_unit(NoiseTerm::rate_random_walk, Sensor::gyro) == "rad/s^2/sqrt(Hz)");
  CHECK(si_unit(NoiseTerm::rate_random_walk, Sensor::accel) == "m/s^3/sqrt(Hz)");
  CHECK(si_unit(NoiseTerm::bias_instability, Sensor::gyro) == "rad/s");
  CHECK(si_unit(NoiseTerm::bias_instability, Sensor::accel) == "m/s^2");
  CHECK(si_unit(NoiseTerm::quantization, Sensor::gyro) == "rad");
  CHECK(si_unit(NoiseTerm::rate_ramp, Sensor::accel) == "m/s^3");
}
