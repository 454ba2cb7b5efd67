#pragma once
/// \file display_units.hpp
/// The one home of the unit of each noise term per sensor: its SI unit (si_unit), which JSON
/// results, sidecars and the conversion's arithmetic print beside SI values, and its display
/// (data-sheet) unit (display_unit), used by the `fit` table and the report (report.html,
/// summary.md) so that the same fit shows the same unit everywhere. The library itself works in
/// SI (noise_model.hpp); every unit here parses with parse_unit (units.hpp).

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
///   Gauss-Markov sigma and sinusoid amplitude: the rate unit of B (deg/h | ug); a sum of
///   Gauss-Markov processes gives every entry's sigma in it.
/// An accelerometer's K and R keep their SI spelling: data sheets rarely print them, and
/// filter files (Kalibr's accelerometer_random_walk) use m/s^3/sqrt(Hz).
std::string_view display_unit(NoiseTerm term, Sensor sensor);

/// SI unit of `term` for `sensor`, the unit of NoiseTerms' values (noise_model.hpp):
///   term                 gyro                accelerometer
///   Q quantization       rad                 m/s
///   N white              rad/s/sqrt(Hz)      m/s^2/sqrt(Hz)
///   B bias instability   rad/s               m/s^2
///   K random walk        rad/s^2/sqrt(Hz)    m/s^3/sqrt(Hz)
///   R ramp               rad/s^2             m/s^3
///   Gauss-Markov sigma and sinusoid amplitude: the rate unit of B (rad/s | m/s^2).
/// Each parses with parse_unit to factor 1 and the term's dimension (dim::angle_random_walk,
/// ...).
std::string_view si_unit(NoiseTerm term, Sensor sensor);

}  // namespace sigmatau
