#pragma once
/// \file units.hpp
/// Units as data sheets print them, converted once at the boundary to SI (rad, m, s, K).
/// Angle is kept as its own dimension so that deg/s and m/s^2 cannot be confused, and exponents
/// are kept in halves so sqrt(Hz) and sqrt(h) are exact.
///
/// (API sketch by the integrator; the units module owner completes it. Keep these names.)

#include <string>
#include <string_view>

namespace sigmatau {

/// Physical dimension as exponents of angle, length, time, temperature (each in halves, so
/// rad/s/sqrt(Hz) is angle 2, time -1 ... i.e. angle^1 time^-1/2).
struct Dimension {
  int angle2 = 0;        ///< 2 x exponent of angle (rad)
  int length2 = 0;       ///< 2 x exponent of length (m)
  int time2 = 0;         ///< 2 x exponent of time (s)
  int temperature2 = 0;  ///< 2 x exponent of temperature (K)
  friend bool operator==(const Dimension&, const Dimension&) = default;
};

/// Human-readable dimension, e.g. "angle/time" or "length/time^2/sqrt(1/time)".
std::string to_string(const Dimension& dimension);

/// A parsed unit: value_in_si = value_in_unit * factor (affine units such as degC are only
/// accepted where a temperature *difference* is meant, e.g. %/degC).
struct Unit {
  double factor = 1;
  Dimension dimension;
};

/// Parses a unit expression ("deg/s", "°/√h", "mdps/rt-Hz", "ug/sqrt(Hz)", "m/s^2", "%/°C",
/// "LSB/(°/s)", products, quotients, powers, parentheses). Throws Error naming the text and the
/// unknown part.
Unit parse_unit(std::string_view text);

/// A number with its unit, in SI.
struct Quantity {
  double value_si = 0;
  Dimension dimension;
};

/// Parses "0.15 deg/sqrt(h)" (number, optional space, unit). Throws Error on a malformed number
/// or unit.
Quantity parse_quantity(std::string_view text);

/// Converts `value` from unit `from` to unit `to`; throws Error when their dimensions differ
/// (the message names both units and both dimensions).
double convert(double value, std::string_view from, std::string_view to);

/// Parses `text` and checks its dimension: for a named field (e.g. "gyro.noise_density"), throws
/// Error "FIELD: found <unit> (<dimension>), expected <dimension>" on a mismatch. Returns SI.
double parse_quantity_as(std::string_view text, const Dimension& expected, std::string_view field);

/// Common dimensions.
namespace dim {
inline constexpr Dimension dimensionless{};
inline constexpr Dimension angle{2, 0, 0, 0};
inline constexpr Dimension time{0, 0, 2, 0};
inline constexpr Dimension frequency{0, 0, -2, 0};
inline constexpr Dimension angular_rate{2, 0, -2, 0};            ///< rad/s
inline constexpr Dimension acceleration{0, 2, -4, 0};            ///< m/s^2
inline constexpr Dimension velocity{0, 2, -2, 0};                ///< m/s
inline constexpr Dimension angle_random_walk{2, 0, -1, 0};       ///< rad/s/sqrt(Hz) = rad/sqrt(s)
inline constexpr Dimension velocity_random_walk{0, 2, -3, 0};    ///< m/s^2/sqrt(Hz)
inline constexpr Dimension gyro_rate_random_walk{2, 0, -3, 0};   ///< rad/s^2/sqrt(Hz) = rad/s^1.5
inline constexpr Dimension accel_rate_random_walk{0, 2, -5, 0};  ///< m/s^3/sqrt(Hz)
inline constexpr Dimension angular_rate_ramp{2, 0, -4, 0};       ///< rad/s^2
inline constexpr Dimension acceleration_ramp{0, 2, -6, 0};       ///< m/s^3
inline constexpr Dimension temperature{0, 0, 0, 2};
}  // namespace dim

}  // namespace sigmatau
