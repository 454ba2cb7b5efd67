// SI and display (data-sheet) units of the noise terms (display_units.hpp).
#include "sigmatau/display_units.hpp"

namespace sigmatau {

std::string_view display_unit(NoiseTerm term, Sensor sensor) {
  const bool gyro = sensor == Sensor::gyro;
  switch (term) {
    case NoiseTerm::quantization: return gyro ? "arcsec" : "m/s";
    case NoiseTerm::white: return gyro ? "deg/sqrt(h)" : "ug/sqrt(Hz)";
    case NoiseTerm::rate_random_walk: return gyro ? "deg/h/sqrt(h)" : "m/s^3/sqrt(Hz)";
    case NoiseTerm::rate_ramp: return gyro ? "deg/h^2" : "m/s^3";
    case NoiseTerm::bias_instability:
    case NoiseTerm::gauss_markov:
    case NoiseTerm::sinusoid: break;
  }
  return gyro ? "deg/h" : "ug";
}

std::string_view si_unit(NoiseTerm term, Sensor sensor) {
  const bool gyro = sensor == Sensor::gyro;
  switch (term) {
    case NoiseTerm::quantization: return gyro ? "rad" : "m/s";
    case NoiseTerm::white: return gyro ? "rad/s/sqrt(Hz)" : "m/s^2/sqrt(Hz)";
    case NoiseTerm::rate_random_walk: return gyro ? "rad/s^2/sqrt(Hz)" : "m/s^3/sqrt(Hz)";
    case NoiseTerm::rate_ramp: return gyro ? "rad/s^2" : "m/s^3";
    case NoiseTerm::bias_instability:
    case NoiseTerm::gauss_markov:
    case NoiseTerm::sinusoid: break;
  }
  return gyro ? "rad/s" : "m/s^2";
}

}  // namespace sigmatau
