#pragma once
/// \file units.hpp
/// Units as data sheets print them, converted once at the boundary to SI (rad, m, s, K).
/// Angle is kept as its own dimension so that deg/s and m/s^2 cannot be confused, and exponents
/// are kept in halves so sqrt(Hz) and sqrt(h) are exact. Raw sensor counts (LSB) are a dimension
/// of their own, so a sensitivity such as 131 LSB/(deg/s) is counts/(angle/time) and cannot be
/// mistaken for a ratio such as ppm.
///
/// Grammar (whitespace around operators is ignored):
///   unit    := ['/'] factor { op factor }        a leading '/' means 1/...
///   op      := '*' | '·' | '⋅' | '/' | whitespace  left-associative, all one precedence:
///                                                  deg/s/sqrt(Hz) = deg s^-1 Hz^-1/2
///   factor  := ('sqrt' | '√' | 'rt' ['-']) factor | primary [power]
///   primary := symbol | '(' unit ')' | '1'
///   power   := '^' number | '^(' number ['/' number] ')' | superscripts (², ³, ⁻¹, ½)
///            | digits written right after a symbol ("m/s2" = m/s^2)
/// A product written as whitespace after a '/' ("deg/s h") is rejected as ambiguous: write
/// "deg/(s*h)" or "deg/s*h". "sqrtHz", "rtHz" and "rt-Hz" are sqrt(Hz).
///
/// Symbols (see known_units() for the full table, `sigmatau units --list` prints it):
///   angle        rad, deg, degree(s), °, º (a look-alike some data sheets print), arcsec, arcmin;
///                prefixes m, u, µ, μ on rad and deg (mrad, µrad, mdeg)
///   time         s, sec, min (minute), h, hr, hour(s); prefixes m, u, µ, μ, n on s and sec
///   frequency    Hz (prefixes m, k, M), SPS (samples per second, prefix k)
///   angular rate dps (= deg/s, prefixes m, u, µ, μ), dph (= deg/h), rpm
///   acceleration g = standard gravity gn = 9.80665 m/s^2 exactly (CGPM 1901, the conventional
///                value, not local gravity); mg, ug, µg, μg are milli- and micro-gee.
///                Mass units do not exist here: "mg" is never milligram, "kg" is rejected.
///   length       m (prefixes n, u, µ, μ, m, c, k), ft (0.3048 m)
///   ratio        %, ‰, ppm, ppb
///   temperature  K (prefix m), °C, degC, ℃, ºC. A lone °C ("25 °C") is an absolute
///                temperature (Unit::offset = 273.15 K); inside any compound (%/°C, ppm/K,
///                mg/°C, °C/min) it is a temperature difference, with no offset.
///   counts       LSB, lsb, count(s)
/// Micro can be written u, µ (U+00B5, micro sign) or μ (U+03BC, Greek mu). Exact symbols win
/// over prefixed ones: "m" is metre, "min" minute, "mg" milli-gee, "h" hour, "ms" millisecond.

#include <numbers>
#include <string>
#include <string_view>
#include <vector>

#include "sigmatau/error.hpp"

namespace sigmatau {

/// Standard gravity gn [m/s^2], the conventional value adopted by the 3rd CGPM (1901) and used
/// by IMU data sheets for "g", "mg", "µg". Not the local gravity at any site.
inline constexpr double kStandardGravity = 9.80665;

/// One degree [rad]: pi / 180, exact by definition; the factor of "deg" in parse_unit.
inline constexpr double kRadiansPerDegree = std::numbers::pi / 180;
/// Degrees in one radian (180 / pi), to write an angle held in rad in degrees.
inline constexpr double kDegreesPerRadian = 180 / std::numbers::pi;

/// Physical dimension as exponents of angle, length, time, temperature and counts (each in
/// halves, so rad/s/sqrt(Hz) = rad/sqrt(s) is angle2 = 2, time2 = -1).
struct Dimension {
  int angle2 = 0;        ///< 2 x exponent of angle (rad)
  int length2 = 0;       ///< 2 x exponent of length (m)
  int time2 = 0;         ///< 2 x exponent of time (s)
  int temperature2 = 0;  ///< 2 x exponent of temperature (K)
  int counts2 = 0;       ///< 2 x exponent of raw sensor counts (LSB)
  friend bool operator==(const Dimension&, const Dimension&) = default;
};

/// Dimension in words, e.g. "angle/time", "length/time^2", "angle/sqrt(time)",
/// "counts*time/angle", "dimensionless".
std::string to_string(const Dimension& dimension);

/// The SI unit of a dimension, written so parse_unit() reads it back with factor 1:
/// "rad/s", "m/s^2", "rad/sqrt(s)", "m/s^1.5", "LSB*s/rad", "1/s", "1" (dimensionless).
std::string si_unit_string(const Dimension& dimension);

/// A parsed unit: value_in_si = value_in_unit * factor + offset. `offset` is non-zero only for a
/// unit that is a lone absolute temperature (°C: 273.15 K); code converting a difference or a
/// scale (e.g. the samples of a log, whose offset cancels in every deviation) uses factor alone.
struct Unit {
  double factor = 1;
  Dimension dimension;
  double offset = 0;  ///< [SI unit of `dimension`]
};

/// A unit text that cannot be parsed. what() reads
/// `unknown unit "foo" at column 5 of "1.0 foo"`; column() is that 1-based column (in characters,
/// not bytes) within the text that was passed in, so a spec reader can add it to the column where
/// the text starts in its file. column() is 0 for errors that have no position (dimension
/// mismatches).
class UnitError : public Error {
 public:
  UnitError(const std::string& message, std::size_t column) : Error(message), column_(column) {}
  std::size_t column() const { return column_; }

 private:
  std::size_t column_;
};

/// Parses a unit expression ("deg/s", "°/√h", "mdps/rt-Hz", "ug/sqrt(Hz)", "m/s^2", "%/°C",
/// "LSB/(°/s)"; grammar at the top of this file).
/// Throws UnitError naming the text, the unknown or unexpected part and its column.
Unit parse_unit(std::string_view text);

/// parse_unit() plus a dimension check. Throws UnitError
/// `WHAT: expected angle/time (e.g. rad/s), found length/time^2 (m/s^2)` on a mismatch, and
/// prefixes parse errors with `WHAT: `. `what` names the option or field, e.g. "--unit".
Unit parse_unit_as(std::string_view text, const Dimension& expected, std::string_view what);

/// A number with its unit, in SI.
struct Quantity {
  double value_si = 0;  ///< [SI unit of `dimension`]
  Dimension dimension;
};

/// Parses "0.15 deg/sqrt(h)": a decimal number (optional sign, '−' accepted; no inf or nan),
/// optional whitespace, then a unit (empty means dimensionless). Throws UnitError on a malformed
/// number, a number out of double range ("1e999 deg"), a malformed unit, or an SI value that
/// overflows.
Quantity parse_quantity(std::string_view text);

/// Converts `value` from unit `from` to unit `to` (offsets included: 25 °C -> 298.15 K).
/// Throws UnitError when a unit is malformed or their dimensions differ; the message names both
/// units and both dimensions.
double convert(double value, std::string_view from, std::string_view to);

/// Parses `text` and checks its dimension: for a named field (e.g. "gyro.noise_density"), throws
/// UnitError `FIELD: expected angle/time (e.g. rad/s), found length/time^2 (m/s^2) in "3 m/s^2"`
/// on a mismatch, and `FIELD: ...` for a malformed text. Returns the value in SI.
double parse_quantity_as(std::string_view text, const Dimension& expected, std::string_view field);

/// One entry of the symbol table.
struct UnitSymbol {
  std::string_view name;  ///< as written, e.g. "dps"
  double factor;          ///< value_in_si = value * factor
  Dimension dimension;
  std::string_view prefixes;  ///< SI prefixes it takes, space-separated ("m u µ μ"), or ""
  std::string_view meaning;   ///< e.g. "degree per second"
};

/// The symbols parse_unit() knows, in table order.
const std::vector<UnitSymbol>& known_units();

/// Common dimensions.
namespace dim {
inline constexpr Dimension dimensionless{};
inline constexpr Dimension angle{2, 0, 0, 0, 0};
inline constexpr Dimension length{0, 2, 0, 0, 0};
inline constexpr Dimension time{0, 0, 2, 0, 0};
inline constexpr Dimension frequency{0, 0, -2, 0, 0};
inline constexpr Dimension angular_rate{2, 0, -2, 0, 0};           ///< rad/s
inline constexpr Dimension acceleration{0, 2, -4, 0, 0};           ///< m/s^2
inline constexpr Dimension velocity{0, 2, -2, 0, 0};               ///< m/s
inline constexpr Dimension angle_random_walk{2, 0, -1, 0, 0};      ///< rad/s/sqrt(Hz) = rad/sqrt(s)
inline constexpr Dimension velocity_random_walk{0, 2, -3, 0, 0};   ///< m/s^2/sqrt(Hz)
inline constexpr Dimension gyro_rate_random_walk{2, 0, -3, 0, 0};  ///< rad/s^2/sqrt(Hz) = rad/s^1.5
inline constexpr Dimension accel_rate_random_walk{0, 2, -5, 0, 0};  ///< m/s^3/sqrt(Hz)
inline constexpr Dimension angular_rate_ramp{2, 0, -4, 0, 0};       ///< rad/s^2
inline constexpr Dimension acceleration_ramp{0, 2, -6, 0, 0};       ///< m/s^3
inline constexpr Dimension temperature{0, 0, 0, 2, 0};              ///< K
inline constexpr Dimension counts{0, 0, 0, 0, 2};                   ///< LSB
inline constexpr Dimension gyro_sensitivity{-2, 0, 2, 0, 2};        ///< LSB/(rad/s)
inline constexpr Dimension accel_sensitivity{0, -2, 4, 0, 2};       ///< LSB/(m/s^2)
}  // namespace dim

}  // namespace sigmatau
