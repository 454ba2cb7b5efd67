// Unit parser: every data-sheet notation, the worked conversions of THEORY.md §3.2 and §9, round
// trips, dimension checks and malformed input.
//
// Expected values are computed here from the definitions (degree = pi/180 rad, h = 3600 s,
// gn = 9.80665 m/s^2), never by the code under test, or taken as printed by the published sources
// THEORY.md cites, with a tolerance derived from how many digits were printed.
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "sigmatau/units.hpp"
#include "test_support.hpp"

using namespace sigmatau;
using sigmatau::test::rel;

namespace {

constexpr double kDeg = std::numbers::pi / 180;  // definition of the degree [rad]
constexpr double kGn = 9.80665;                  // standard gravity, 3rd CGPM (1901) [m/s^2]

// A unit factor is a product of at most about ten correctly rounded doubles (each step adds at
// most 0.5 ulp = 1.1e-16 relative), so 1e-14 bounds the rounding with a wide margin while still
// catching any wrong constant (the nearest plausible mistake, g = 9.81, is off by 3.4e-4).
constexpr double kRoundoff = 1e-14;

double si(std::string_view quantity) { return parse_quantity(quantity).value_si; }

struct Caught {
  bool thrown = false;
  std::string message;
  std::size_t column = 0;
};

template <class F>
Caught catch_unit_error(F&& f) {
  try {
    f();
  } catch (const UnitError& e) {
    return {true, e.what(), e.column()};
  }
  return {};
}

struct Notation {
  const char* text;
  double factor;
  Dimension dimension;
};

void check_notations(const std::vector<Notation>& table) {
  for (const auto& n : table) {
    INFO("unit text: \"" << n.text << "\"");
    const Unit u = parse_unit(n.text);
    CHECK(u.factor == rel(n.factor, kRoundoff));
    CHECK(u.dimension == n.dimension);
    CHECK(to_string(u.dimension) == to_string(n.dimension));  // prints both on failure
  }
}

constexpr Dimension kInverseTemperature{0, 0, 0, -2, 0};
constexpr Dimension kSqrtTime{0, 0, 1, 0, 0};
constexpr Dimension kInverseSqrtTime{0, 0, -1, 0, 0};

}  // namespace

TEST_CASE("angle notations parse to radians") {
  check_notations({
      {"rad", 1, dim::angle},
      {"mrad", 1e-3, dim::angle},
      {"urad", 1e-6, dim::angle},
      {"µrad", 1e-6, dim::angle},
      {"μrad", 1e-6, dim::angle},
      {"deg", kDeg, dim::angle},
      {"°", kDeg, dim::angle},
      {"º", kDeg, dim::angle},
      {"degree", kDeg, dim::angle},
      {"degrees", kDeg, dim::angle},
      {"mdeg", 1e-3 * kDeg, dim::angle},
      {"arcmin", kDeg / 60, dim::angle},
      {"arcsec", kDeg / 3600, dim::angle},
  });
}

TEST_CASE("time and frequency notations parse to seconds and hertz") {
  check_notations({
      {"s", 1, dim::time},
      {"sec", 1, dim::time},
      {"ms", 1e-3, dim::time},
      {"msec", 1e-3, dim::time},
      {"us", 1e-6, dim::time},
      {"µs", 1e-6, dim::time},
      {"μs", 1e-6, dim::time},
      {"ns", 1e-9, dim::time},
      {"min", 60, dim::time},
      {"h", 3600, dim::time},
      {"hr", 3600, dim::time},
      {"hour", 3600, dim::time},
      {"hours", 3600, dim::time},
      {"Hz", 1, dim::frequency},
      {"kHz", 1e3, dim::frequency},
      {"mHz", 1e-3, dim::frequency},
      {"SPS", 1, dim::frequency},
      {"kSPS", 1e3, dim::frequency},
  });
}

TEST_CASE("square roots of Hz and of hours in every spelling") {
  check_notations({
      {"sqrt(Hz)", 1, kInverseSqrtTime},
      {"√Hz", 1, kInverseSqrtTime},
      {"√ Hz", 1, kInverseSqrtTime},
      {"rt-Hz", 1, kInverseSqrtTime},
      {"rtHz", 1, kInverseSqrtTime},
      {"sqrtHz", 1, kInverseSqrtTime},
      {"Hz^0.5", 1, kInverseSqrtTime},
      {"Hz^(1/2)", 1, kInverseSqrtTime},
      {"Hz^½", 1, kInverseSqrtTime},
      {"Hz½", 1, kInverseSqrtTime},
      {"/rtHz", 1, kSqrtTime},
      {"/√Hz", 1, kSqrtTime},
      {"1/sqrt(Hz)", 1, kSqrtTime},
      {"sqrt(h)", 60, kSqrtTime},
      {"√h", 60, kSqrtTime},
      {"rt-h", 60, kSqrtTime},
      {"√hr", 60, kSqrtTime},
      {"sqrt(kHz)", std::sqrt(1e3), kInverseSqrtTime},
  });
}

TEST_CASE("angular rates, accelerations and lengths parse to SI") {
  check_notations({
      {"dps", kDeg, dim::angular_rate},
      {"mdps", 1e-3 * kDeg, dim::angular_rate},
      {"deg/s", kDeg, dim::angular_rate},
      {"°/s", kDeg, dim::angular_rate},
      {"°/h", kDeg / 3600, dim::angular_rate},
      {"dph", kDeg / 3600, dim::angular_rate},
      {"rpm", 2 * std::numbers::pi / 60, dim::angular_rate},
      {"rad/s", 1, dim::angular_rate},
      {"g", kGn, dim::acceleration},
      {"mg", 1e-3 * kGn, dim::acceleration},
      {"ug", 1e-6 * kGn, dim::acceleration},
      {"µg", 1e-6 * kGn, dim::acceleration},  // U+00B5 micro sign
      {"μg", 1e-6 * kGn, dim::acceleration},  // U+03BC Greek mu
      {"m/s^2", 1, dim::acceleration},
      {"m/s²", 1, dim::acceleration},
      {"m/s2", 1, dim::acceleration},
      {"m·s⁻²", 1, dim::acceleration},
      {"m*s^-2", 1, dim::acceleration},
      {"m s^−2", 1, dim::acceleration},  // U+2212 minus sign, implicit product
      {"m/s/s", 1, dim::acceleration},
      {"m", 1, dim::length},
      {"mm", 1e-3, dim::length},
      {"cm", 1e-2, dim::length},
      {"km", 1e3, dim::length},
      {"µm", 1e-6, dim::length},
      {"ft", 0.3048, dim::length},
      {"m/s", 1, dim::velocity},
      {"ft/s^2", 0.3048, dim::acceleration},
  });
}

TEST_CASE("ratios, temperatures and counts parse with their own dimensions") {
  check_notations({
      {"%", 1e-2, dim::dimensionless},
      {"‰", 1e-3, dim::dimensionless},
      {"ppm", 1e-6, dim::dimensionless},
      {"ppb", 1e-9, dim::dimensionless},
      {"1", 1, dim::dimensionless},
      {"K", 1, dim::temperature},
      {"°C", 1, dim::temperature},
      {"degC", 1, dim::temperature},
      {"℃", 1, dim::temperature},
      {"mK", 1e-3, dim::temperature},
      {"LSB", 1, dim::counts},
      {"lsb", 1, dim::counts},
      {"counts", 1, dim::counts},
      {"%/°C", 1e-2, kInverseTemperature},
      {"%/degC", 1e-2, kInverseTemperature},
      {"ppm/K", 1e-6, kInverseTemperature},
      {"LSB/(°/s)", 1 / kDeg, dim::gyro_sensitivity},
      {"LSB/(deg/s)", 1 / kDeg, dim::gyro_sensitivity},
      {"LSB/dps", 1 / kDeg, dim::gyro_sensitivity},
      {"LSB/g", 1 / kGn, dim::accel_sensitivity},
  });
}

TEST_CASE("compound data-sheet units have the noise-term dimensions") {
  check_notations({
      {"deg/s/sqrt(Hz)", kDeg, dim::angle_random_walk},
      {"°/s/√Hz", kDeg, dim::angle_random_walk},
      {"°/s /√Hz", kDeg, dim::angle_random_walk},
      {"mdps/rt-Hz", 1e-3 * kDeg, dim::angle_random_walk},
      {"dps/rtHz", kDeg, dim::angle_random_walk},
      {"deg/sqrt(h)", kDeg / 60, dim::angle_random_walk},
      {"°/√hr", kDeg / 60, dim::angle_random_walk},
      {"rad/sqrt(s)", 1, dim::angle_random_walk},
      {"rad/s^0.5", 1, dim::angle_random_walk},
      {"°/h/√h", kDeg / 3600 / 60, dim::gyro_rate_random_walk},
      {"rad/s^1.5", 1, dim::gyro_rate_random_walk},
      {"rad/s*sqrt(Hz)", 1, dim::gyro_rate_random_walk},
      {"rad/s^2/sqrt(Hz)", 1, dim::gyro_rate_random_walk},
      {"ug/sqrt(Hz)", 1e-6 * kGn, dim::velocity_random_walk},
      {"µg/√Hz", 1e-6 * kGn, dim::velocity_random_walk},
      {"mg/rt-Hz", 1e-3 * kGn, dim::velocity_random_walk},
      {"m/s/sqrt(h)", 1.0 / 60, dim::velocity_random_walk},
      {"m/s^1.5", 1, dim::velocity_random_walk},
      {"m/s^(3/2)", 1, dim::velocity_random_walk},
      {"m/s^3/sqrt(Hz)", 1, dim::accel_rate_random_walk},
      {"deg/s^2", kDeg, dim::angular_rate_ramp},
      {"°/h/h", kDeg / 3600 / 3600, dim::angular_rate_ramp},
      {"m/s^3", 1, dim::acceleration_ramp},
      {"(m/s)^2", 1, Dimension{0, 4, -4, 0, 0}},
      {"(deg/s)^2/Hz", kDeg * kDeg, Dimension{4, 0, -2, 0, 0}},
      {"°/s/g", kDeg / kGn, Dimension{2, -2, 2, 0, 0}},
      {"mg/°C", 1e-3 * kGn, Dimension{0, 2, -4, -2, 0}},
      {"°C/min", 1.0 / 60, Dimension{0, 0, -2, 2, 0}},
      {"deg / s", kDeg, dim::angular_rate},
      {"  deg/s  ", kDeg, dim::angular_rate},
      {"deg\u00A0/\u00A0s", kDeg, dim::angular_rate},  // no-break spaces copied from a PDF
  });
}

TEST_CASE("quotients and products are left-associative") {
  // deg/s/sqrt(Hz) = deg s^-1 Hz^-1/2, not deg / (s / sqrt(Hz)).
  CHECK(parse_unit("deg/s/sqrt(Hz)").dimension == parse_unit("deg*s^-1*Hz^(-1/2)").dimension);
  CHECK(parse_unit("m/s/s").dimension == dim::acceleration);
  CHECK(parse_unit("deg/s*s").dimension == dim::angle);
  CHECK(parse_unit("deg/(s*s)").dimension == dim::angular_rate_ramp);
}

TEST_CASE("THEORY 3.2: ARW, VRW, accelerometer ND, bias and RRW conversions") {
  // 1 deg/s/sqrt(Hz) = 60 deg/sqrt(h), since sqrt(h) = 60 sqrt(s).
  CHECK(convert(1, "deg/s/sqrt(Hz)", "deg/sqrt(h)") == rel(60, kRoundoff));
  CHECK(convert(0.3, "deg/sqrt(h)", "deg/s/sqrt(Hz)") == rel(0.005, kRoundoff));
  // 0.15 deg/sqrt(h) = 0.15 pi/180/60 rad/sqrt(s); published 4.3633e-5, printed to 5 digits:
  // half a unit in the last place is 0.5e-9 / 4.3633e-5 = 1.15e-5.
  CHECK(si("0.15 deg/sqrt(h)") == rel(0.15 * kDeg / 60, kRoundoff));
  CHECK(si("0.15 deg/sqrt(h)") == rel(4.3633e-5, 1.15e-5));
  // VRW 0.06 m/s/sqrt(h) = 1e-3 m/s^1.5 exactly (0.06 / 60).
  CHECK(convert(0.06, "m/s/sqrt(h)", "m/s^1.5") == rel(1e-3, kRoundoff));
  // Accelerometer ND: 1 ug/sqrt(Hz) = 9.80665e-6 m/s^2/sqrt(Hz).
  CHECK(convert(1, "µg/√Hz", "m/s^2/sqrt(Hz)") == rel(1e-6 * kGn, kRoundoff));
  CHECK(convert(1, "ug/sqrt(Hz)", "m/s/sqrt(h)") == rel(1e-6 * kGn * 60, kRoundoff));
  // Bias instability: deg/h to deg/s is /3600.
  CHECK(convert(1, "deg/h", "deg/s") == rel(1.0 / 3600, kRoundoff));
  // Rate random walk K: deg/h/sqrt(h) -> deg/s^1.5 is /3600^1.5 = /216000; -> rad/s^1.5 adds
  // pi/180.
  CHECK(convert(1, "deg/s^1.5", "deg/h/sqrt(h)") == rel(216000, kRoundoff));
  CHECK(convert(1, "deg/h/sqrt(h)", "rad/s^1.5") == rel(kDeg / 216000, kRoundoff));
  CHECK(convert(1, "deg/h/sqrt(h)", "rad/s*sqrt(Hz)") == rel(kDeg / 216000, kRoundoff));
}

TEST_CASE("THEORY 9 T4: MathWorks fit results in data-sheet units") {
  // Published values printed to 4 or 5 digits; each tolerance is half a unit in the last place.
  CHECK(convert(0.0125631765533906, "rad/s/sqrt(Hz)", "deg/sqrt(h)") == rel(43.19, 0.005 / 43.19));
  CHECK(convert(9.38284069320333e-5, "rad/s*sqrt(Hz)", "deg/h/sqrt(h)") ==
        rel(1161.2, 0.05 / 1161.2));
  CHECK(convert(0.00203140909966965, "rad/s", "deg/h") == rel(419.0, 0.05 / 419.0));
}

TEST_CASE("THEORY 9 T5: STIM300 data-sheet values in SI (NavToolkit)") {
  // The source used g = 9.81, 3.4e-4 above gn = 9.80665; 4e-4 covers that (its 4 printed digits
  // are exact: 0.05e-3 * 9.81 = 4.905e-4).
  CHECK(si("0.05 mg") == rel(4.905e-4, 4e-4));
  CHECK(si("0.05 mg") == rel(0.05e-3 * kGn, kRoundoff));
  CHECK(si("0.06 m/s/√hr") == rel(1e-3, kRoundoff));
  // Printed to 5 digits: half a unit in the last place relative to the value.
  CHECK(si("0.5 °/hr") == rel(2.4241e-6, 0.5e-10 / 2.4241e-6));
  CHECK(si("0.15 °/√hr") == rel(4.3633e-5, 0.5e-9 / 4.3633e-5));
}

TEST_CASE("THEORY 9 T6: VN-100 values in SI (Kalibr yaml comments)") {
  // The source used g = 9.8; gn/9.8 - 1 = 6.8e-4, so 7e-4 (its digits 1.372 are exact for 9.8).
  CHECK(si("0.14 mg/√Hz") == rel(1.372e-3, 7e-4));
  CHECK(si("0.14 mg/√Hz") == rel(0.14e-3 * kGn, kRoundoff));
  // Printed to 6 digits, but 0.0035 pi/180 = 6.108652e-5 rounds to 6.10865e-5: the source's last
  // digit is one too high, so the tolerance is one unit (not half a unit) in the last place.
  CHECK(si("0.0035 °/s/√Hz") == rel(6.10866e-5, 1e-10 / 6.10866e-5));
  CHECK(si("0.0035 °/s/√Hz") == rel(0.0035 * kDeg, kRoundoff));
}

TEST_CASE("THEORY 9 T7: ENGO623 course constants in SI") {
  // Printed to 4 digits (half a unit in the last place) or exact.
  CHECK(si("0.01 °/√hr") == rel(2.909e-6, 0.5e-9 / 2.909e-6));
  CHECK(si("0.003 m/s/√hr") == rel(5e-5, kRoundoff));
  CHECK(si("0.1 °/hr") == rel(4.848e-7, 0.5e-10 / 4.848e-7));
}

TEST_CASE("THEORY 9 T8 and T10: accelerometer noise density to VRW") {
  // Published to 3-4 digits; tolerance is half a unit in the last printed place.
  const std::array<std::pair<double, double>, 4> nd_vrw = {
      {{400, 0.2354}, {230, 0.1353}, {70, 0.0412}, {140, 0.0824}}};
  for (const auto& row : nd_vrw) {
    const double nd_ug = row.first, vrw_published = row.second;
    INFO(nd_ug << " ug/sqrt(Hz)");
    const double vrw = convert(nd_ug, "ug/sqrt(Hz)", "m/s/sqrt(h)");
    const double half_ulp = 0.5e-4;  // all four are printed to 4 decimals
    CHECK(vrw == rel(vrw_published, half_ulp / vrw_published));
    CHECK(vrw == rel(nd_ug * 1e-6 * kGn * 60, kRoundoff));
  }
  // ADIS16448 (T8): 60 x 0.23 mg x g = 0.135 m/s/sqrt(h), printed to 3 digits.
  CHECK(convert(0.23, "mg/√Hz", "m/s/√h") == rel(0.135, 0.5e-3 / 0.135));
}

TEST_CASE("temperature: a lone degC is absolute, inside a compound it is a difference") {
  CHECK(si("25 °C") == rel(298.15, kRoundoff));
  CHECK(si("-40 degC") == rel(233.15, kRoundoff));
  CHECK(si("−40 ℃") == rel(233.15, kRoundoff));  // U+2212 minus sign
  CHECK(convert(25, "degC", "K") == rel(298.15, kRoundoff));
  CHECK(convert(298.15, "K", "°C") == rel(25, 1e-12));  // 298.15 - 273.15 cancels 12 digits
  CHECK(parse_unit("°C").offset == 273.15);
  CHECK(parse_unit("%/°C").offset == 0);
  CHECK(parse_unit("°C/min").offset == 0);
  CHECK(si("0.026 %/°C") == rel(2.6e-4, kRoundoff));  // MPU-6050 / ICM-20948 sensitivity TC
  CHECK(si("0.8 mg/°C") == rel(0.8e-3 * kGn, kRoundoff));
  CHECK(convert(1, "ppm/K", "%/degC") == rel(1e-4, kRoundoff));
}

TEST_CASE("counts: a sensitivity in LSB converts between angle units") {
  CHECK(convert(131, "LSB/(°/s)", "LSB/(rad/s)") == rel(131 / kDeg, kRoundoff));
  CHECK(si("16384 LSB/g") == rel(16384 / kGn, kRoundoff));
  const Caught c = catch_unit_error([] { convert(1, "LSB", "ppm"); });
  CHECK(c.thrown);
  CHECK(c.message.find("counts") != std::string::npos);
}

TEST_CASE("round trips through SI return the value") {
  const std::array<const char*, 16> units = {
      "deg/s",       "mdps", "°/h",   "deg/sqrt(h)", "°/s/√Hz", "°/h/√h", "mg",     "µg/√Hz",
      "m/s/sqrt(h)", "%/°C", "ppm/K", "LSB/(°/s)",   "arcsec",  "kHz",    "ft/s^2", "(deg/s)^2/Hz"};
  for (const char* u : units) {
    const Unit unit = parse_unit(u);
    const std::string si_text = si_unit_string(unit.dimension);
    INFO(u << " <-> " << si_text);
    for (double x : {1.2345, -3e-7, 4.5e5}) {
      CHECK(convert(convert(x, u, si_text), si_text, u) == rel(x, kRoundoff));
      CHECK(convert(x, u, u) == rel(x, kRoundoff));
    }
  }
}

TEST_CASE("the SI unit strings parse back with factor 1") {
  const std::array<Dimension, 17> dims = {dim::dimensionless,
                                          dim::angle,
                                          dim::length,
                                          dim::time,
                                          dim::frequency,
                                          dim::angular_rate,
                                          dim::acceleration,
                                          dim::velocity,
                                          dim::angle_random_walk,
                                          dim::velocity_random_walk,
                                          dim::gyro_rate_random_walk,
                                          dim::accel_rate_random_walk,
                                          dim::angular_rate_ramp,
                                          dim::acceleration_ramp,
                                          dim::temperature,
                                          dim::gyro_sensitivity,
                                          dim::accel_sensitivity};
  for (const Dimension& d : dims) {
    const std::string text = si_unit_string(d);
    INFO(text);
    const Unit u = parse_unit(text);
    CHECK(u.dimension == d);
    CHECK(u.factor == 1);
  }
  CHECK(si_unit_string(dim::angle_random_walk) == "rad/sqrt(s)");
  CHECK(si_unit_string(dim::gyro_rate_random_walk) == "rad/s^1.5");
  CHECK(si_unit_string(dim::acceleration) == "m/s^2");
  CHECK(si_unit_string(dim::dimensionless) == "1");
}

TEST_CASE("dimensions are described in words") {
  CHECK(to_string(dim::angular_rate) == "angle/time");
  CHECK(to_string(dim::acceleration) == "length/time^2");
  CHECK(to_string(dim::angle_random_walk) == "angle/sqrt(time)");
  CHECK(to_string(dim::gyro_rate_random_walk) == "angle/time^1.5");
  CHECK(to_string(dim::frequency) == "1/time");
  CHECK(to_string(dim::dimensionless) == "dimensionless");
  CHECK(to_string(dim::gyro_sensitivity) == "counts*time/angle");
  CHECK(to_string(kInverseTemperature) == "1/temperature");
}

TEST_CASE("a dimension mismatch names both units and both dimensions") {
  SUBCASE("convert") {
    const Caught c = catch_unit_error([] { convert(1, "deg/s", "m/s^2"); });
    REQUIRE(c.thrown);
    CHECK(c.message == "cannot convert deg/s (angle/time) to m/s^2 (length/time^2)");
  }
  SUBCASE("parse_quantity_as") {
    const Caught c =
        catch_unit_error([] { parse_quantity_as("3 m/s^2", dim::angular_rate, "gyro.bias"); });
    REQUIRE(c.thrown);
    CHECK(
        c.message ==
        "gyro.bias: expected angle/time (e.g. rad/s), found length/time^2 (m/s^2) in \"3 m/s^2\"");
  }
  SUBCASE("parse_quantity_as without a unit") {
    const Caught c = catch_unit_error(
        [] { parse_quantity_as("0.005", dim::angle_random_walk, "gyro.noise_density"); });
    REQUIRE(c.thrown);
    CHECK(c.message.find("found dimensionless (no unit)") != std::string::npos);
  }
  SUBCASE("parse_unit_as") {
    const Caught c = catch_unit_error([] { parse_unit_as("mg", dim::angular_rate, "--unit"); });
    REQUIRE(c.thrown);
    CHECK(c.message == "--unit: expected angle/time (e.g. rad/s), found length/time^2 (mg)");
  }
  SUBCASE("a matching dimension passes") {
    CHECK(parse_quantity_as("0.15 deg/sqrt(h)", dim::angle_random_walk, "gyro.arw") ==
          rel(0.15 * kDeg / 60, kRoundoff));
    CHECK(parse_unit_as("mdps", dim::angular_rate, "--unit").factor == rel(1e-3 * kDeg, kRoundoff));
  }
}

TEST_CASE("malformed input names the text, the problem and its column") {
  struct Bad {
    const char* text;
    bool quantity;  // parse_quantity instead of parse_unit
    const char* message_part;
    std::size_t column;
  };
  const std::array<Bad, 30> cases = {{
      {"", false, "empty unit", 1},
      {"   ", false, "empty unit", 4},
      {"", true, "empty quantity", 1},
      {"1.0 foo", true, "unknown unit \"foo\" at column 5 of \"1.0 foo\"", 5},
      {"deg//s", false, "expected a unit, found '/' at column 5", 5},
      {"deg/", false, "found the end of the text", 5},
      {"(deg/s", false, "unbalanced '('", 1},
      {"deg/(s", false, "unbalanced '('", 5},
      {"deg/s)", false, "unbalanced ')'", 6},
      {"()", false, "expected a unit, found ')'", 2},
      {"1e999 deg", true, "number \"1e999\" is out of double range", 1},
      {"1e308 km", true, "overflows", 1},
      {"nan deg", true, "expected a number", 1},
      {"inf", true, "expected a number", 1},
      {"deg", true, "expected a number, found 'd'", 1},
      {"Hz^0.25", false, "multiple of 1/2", 3},
      {"sqrt(sqrt(Hz))", false, "multiple of 1/2", 1},
      {"deg^", false, "expected an exponent, found the end of the text", 5},
      {"deg^x", false, "expected an exponent, found 'x'", 5},
      {"s^99", false, "out of range", 2},
      {"m/s^(1/0)", false, "zero denominator", 8},
      {"deg/s h", false, "ambiguous product", 7},
      {"2/s", false, "must be 1", 1},
      {"kg", false, "mass units are not supported", 1},
      {"HZ", false, "did you mean \"Hz\"", 1},
      {"°/s rms", false, "rms is not a unit", 5},
      {"°/foo", false, "unknown unit \"foo\"", 3},  // columns count characters, not bytes
      {"deg\xff", false, "not UTF-8", 4},
      {"deg$s", false, "unexpected '$'", 4},
      {"deg**2", false, "expected a unit, found '*'", 5},
  }};
  for (const Bad& b : cases) {
    INFO("text: \"" << b.text << "\"");
    const Caught c = catch_unit_error([&] {
      if (b.quantity) {
        parse_quantity(b.text);
      } else {
        parse_unit(b.text);
      }
    });
    REQUIRE(c.thrown);
    INFO("message: " << c.message);
    CHECK(c.message.find(b.message_part) != std::string::npos);
    CHECK(c.column == b.column);
    CHECK(c.message.find("\"" + std::string(b.text) + "\"") != std::string::npos);
  }
}

TEST_CASE("unit errors are sigmatau::Error, so the CLI maps them to exit code 2") {
  CHECK_THROWS_AS(parse_unit("furlong"), Error);
  CHECK_THROWS_AS(convert(1, "deg", "s"), Error);
  CHECK_THROWS_WITH_AS(parse_quantity_as("1 foo", dim::time, "tau"),
                       doctest::Contains("tau: unknown unit \"foo\""), UnitError);
}

TEST_CASE("exact symbols win over prefixed readings") {
  CHECK(parse_unit("m").dimension == dim::length);         // metre, not milli-anything
  CHECK(parse_unit("min").factor == 60);                   // minute, not milli-inch
  CHECK(parse_unit("mg").dimension == dim::acceleration);  // milli-g, not milligram
  CHECK(parse_unit("h").factor == 3600);                   // hour
  CHECK(parse_unit("ms").dimension == dim::time);          // millisecond, not metre-second
}

TEST_CASE("every symbol in the table parses to its table entry") {
  for (const UnitSymbol& s : known_units()) {
    INFO(s.name);
    const Unit u = parse_unit(s.name);
    CHECK(u.factor == s.factor);
    CHECK(u.dimension == s.dimension);
  }
}
