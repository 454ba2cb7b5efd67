#pragma once
/// \file display_units.hpp
/// The one home of the display (data-sheet) unit of each noise term per sensor, used by the
/// `fit` table and the report (report.html, summary.md) so that the same fit shows the same
/// unit everywhere. The library itself works in SI (noise_model.hpp); these units are for
/// people only and every one of them parses with parse_unit (units.hpp).

#include <string_view>

#include "sigmatau/noise_model.hpp"

namespace sigmatau {

/// Display unit of `term` for `sensor`:
///   term                 gyro             accelerometer
///   Q quantization       arcsec           m/s
///   N white              deg/sqrt(h)      ug/sqrt(Hz)
///   B bias instability   deg/h            ug
///   K random walk        deg/h/sqrt(h)    m/s^3/sqrt(Hz)
///   R ramp               deg/h^2          m/s^3
///   Gauss-Markov sigma and sinusoid amplitude: the rate unit of B (deg/h | ug).
/// An accelerometer's K and R keep their SI spelling: data sheets rarely print them, and
/// filter files (Kalibr's accelerometer_random_walk) use m/s^3/sqrt(Hz).
std::string_view display_unit(NoiseTerm term, Sensor sensor);

}  // namespace sigmatau
