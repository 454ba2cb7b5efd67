// Compliance verdicts against a data sheet: the three verdicts, the conventions that put a
// measurement and a printed value on the same footing, and reading result files.
#include <cmath>
#include <numbers>

#include "sigmatau/compliance.hpp"
#include "sigmatau/error.hpp"
#include "made_up_sheet.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

// A made-up sheet: every number below is chosen so that the verdicts are easy to check by hand.
const std::string kSheet = test::made_up_sheet("T-1", R"(gyro:
  noise_density:
    typ: 0.01 °/s/√Hz
    source: ds
    page: 1
  bias_instability:
    typ: 3 °/h
    source: ds
    page: 1
  initial_bias:
    max: ±0.5 °/s
    source: ds
    page: 1
accel:
  velocity_random_walk:
    typ: 0.06 m/s/√h
    source: ds
    page: 1
  sensitivity_error:
    typ: ±1 %
    max: ±3 %
    source: ds
    page: 1
)");

constexpr double kDeg = std::numbers::pi / 180.0;

MeasuredParameter gyro_n(double value, double low, double high) {
  return {Sensor::gyro, MeasuredQuantity::white_noise, "x", value, low, high};
}

}  // namespace

TEST_CASE("a noise density gets pass, marginal or fail from its upper bound and estimate") {
  const DataSheet sheet = parse_data_sheet(kSheet, "test.yaml");
  const double nd = 0.01 * kDeg;  // printed limit, read as N (two-sided convention)
  const auto items = check_compliance({gyro_n(0.8 * nd, 0.7 * nd, 0.9 * nd),    // bound within
                                       gyro_n(0.95 * nd, 0.9 * nd, 1.05 * nd),  // bound beyond
                                       gyro_n(1.2 * nd, 1.1 * nd, 1.3 * nd)},   // estimate beyond
                                      sheet);
  REQUIRE(items.size() == 3);
  CHECK(items[0].verdict == Verdict::pass);
  CHECK(items[1].verdict == Verdict::marginal);
  CHECK(items[2].verdict == Verdict::fail);
  CHECK(items[0].limit_is_typical);  // only typ printed: said so
  CHECK(items[0].margin == test::rel(0.8, 1e-12));
  CHECK(items[2].margin_upper == test::rel(1.3, 1e-12));
  CHECK(any_failed(items));
}

TEST_CASE("the one-sided convention compares N with ND / sqrt(2)") {
  const DataSheet sheet = parse_data_sheet(kSheet, "test.yaml");
  const double nd = 0.01 * kDeg;
  ComplianceOptions one_sided;
  one_sided.convention = DensityConvention::one_sided;
  const auto items = check_compliance({gyro_n(0.8 * nd, 0.75 * nd, 0.85 * nd)}, sheet, one_sided);
  // 0.8 ND > ND / sqrt(2) = 0.707 ND: the same measurement fails under this reading.
  CHECK(items[0].verdict == Verdict::fail);
  CHECK(items[0].limit_si == test::rel(nd / std::sqrt(2.0), 1e-12));
}

TEST_CASE("bias instability is compared as its ADEV floor 0.664 B") {
  const DataSheet sheet = parse_data_sheet(kSheet, "test.yaml");
  const double printed = 3.0 * kDeg / 3600.0;
  const double b = printed / kFlickerFloorFactor;  // exactly at the printed floor
  const auto items = check_compliance(
      {{Sensor::gyro, MeasuredQuantity::bias_instability, "x", 0.9 * b, 0.8 * b, 0.99 * b}}, sheet);
  CHECK(items[0].verdict == Verdict::pass);
  CHECK(items[0].compared == test::rel(0.9 * printed, 1e-12));
}

TEST_CASE("offsets and gain errors are compared by magnitude against max, not typ") {
  const DataSheet sheet = parse_data_sheet(kSheet, "test.yaml");
  const double limit = 0.5 * kDeg;
  const auto items = check_compliance(
      {{Sensor::gyro, MeasuredQuantity::bias, "y", -0.9 * limit, -1.1 * limit, -0.7 * limit},
       {Sensor::accel, MeasuredQuantity::scale_factor_error, "z", 0.02, 0.015, 0.025}},
      sheet);
  CHECK(items[0].verdict == Verdict::marginal);  // |b| within, |lower bound| beyond
  CHECK(items[0].compared_upper == test::rel(1.1 * limit, 1e-12));
  CHECK(items[1].verdict == Verdict::pass);  // 2 % against max 3 % (typ 1 % is not the limit)
  CHECK_FALSE(items[1].limit_is_typical);
}

TEST_CASE("a parameter the sheet does not print is not specified, and a VRW is used directly") {
  const DataSheet sheet = parse_data_sheet(kSheet, "test.yaml");
  const double vrw = 0.06 / 60.0;  // m/s/sqrt(h) -> m/s^2/sqrt(Hz)
  const auto items = check_compliance(
      {{Sensor::gyro, MeasuredQuantity::rate_random_walk, "x", 1e-5, 9e-6, 1.1e-5},
       {Sensor::accel, MeasuredQuantity::white_noise, "x", 0.5 * vrw, 0.4 * vrw, 0.6 * vrw}},
      sheet);
  CHECK(items[0].verdict == Verdict::not_specified);
  CHECK(items[1].verdict == Verdict::pass);
  CHECK(items[1].spec_field == "velocity_random_walk");
  CHECK_FALSE(any_failed(items));
}

TEST_CASE("measured parameters are read from fit and calibrate results") {
  const char* fit = R"json({"channels":[{"name":"gx","quantity":"angular_rate",
    "parameters":{"N":{"value":1e-4,"ci_low":9e-5,"ci_high":1.1e-4,"unit":"rad/s/sqrt(Hz)"},
                  "Q":{"upper_bound":1e-6,"unit":"rad"}}},
    {"name":"az","quantity":"specific_force","parameters":{"K":{"value":1e-5,"ci_low":8e-6,"ci_high":1.2e-5}}}]})json";
  const auto p = measured_parameters_from_json(fit, "fit.json");
  REQUIRE(p.size() == 2);  // Q is only an upper bound: not a measurement
  CHECK(p[0].sensor == Sensor::gyro);
  CHECK(p[0].axis == "x");
  CHECK(p[0].quantity == MeasuredQuantity::white_noise);
  CHECK(p[1].sensor == Sensor::accel);
  CHECK(p[1].quantity == MeasuredQuantity::rate_random_walk);

  const char* calibration = R"json({"accelerometer":{"bias":[0.1,0.2,0.3],
    "bias_ci":[[0.09,0.11],[0.19,0.21],[0.29,0.31]],"scale_factor_error":[0.01,0.02,0.03],
    "misalignment":[[0,0.001,null],[0.002,0,0.003],[null,null,0]],
    "matrix":[[1.01,0,0],[0.002,1.02,0],[0,0.003,1.03]]}})json";
  const auto c = measured_parameters_from_json(calibration, "cal.json");
  // 3 biases, 3 scale factors, and from the matrix the non-orthogonality of the 3 axis pairs
  // (the cross-axis terms one by one depend on the calibration frame: not read).
  REQUIRE(c.size() == 3 + 3 + 3);
  CHECK(c[0].ci_high == test::rel(0.11, 1e-15));
  CHECK(c[6].quantity == MeasuredQuantity::non_orthogonality);
  CHECK(c[6].axis == "xy");
  // Rows (1.01, 0, 0) and (0.002, 1.02, 0): sin(delta) = 0.002 / |(0.002, 1.02)| exactly.
  CHECK(c[6].value == test::rel(std::asin(0.002 / std::hypot(0.002, 1.02)), 1e-12));
  CHECK(c[8].axis == "yz");

  const char* with_temperature = R"json({"gyroscope":{"temperature_coefficients":[
    {"degree":1,"linear":1e-5,"linear_ci":[8e-6,1.2e-5]},{"degree":1,"linear":-2e-5,"linear_ci":[-3e-5,-1e-5]},
    {"degree":2,"linear":0.0,"linear_ci":[-1e-6,1e-6]}]}})json";
  const auto t = measured_parameters_from_json(with_temperature, "cal.json");
  REQUIRE(t.size() == 3);
  CHECK(t[1].quantity == MeasuredQuantity::bias_temperature_coefficient);
  CHECK(t[1].sensor == Sensor::gyro);
  CHECK(t[1].ci_low == test::rel(-3e-5, 1e-15));

  CHECK_THROWS_WITH_AS(measured_parameters_from_json("{\"x\":1}", "other.json"),
                       doctest::Contains("not a sigmatau fit"), Error);
  CHECK_THROWS_WITH_AS(measured_parameters_from_json("{", "broken.json"),
                       doctest::Contains("not valid JSON"), Error);
  CHECK_THROWS_WITH_AS(
      measured_parameters_from_json(R"json({"channels":[{"name":"temp","parameters":{}}]})json", "t.json"),
      doctest::Contains("temp"), Error);
}

TEST_CASE("an axis the sheet prints apart is compared with its own value (BMI088-style accel)") {
  // typ 160 on X and Y, typ 190 on Z, max 300 for none of them: the Z value has no max, so its
  // limit is its own typ, not the entry's max (axes: replaces min / typ / max as printed).
  const DataSheet sheet =
      load_data_sheet(test::test_data_dir() / "specs" / "axis_values.yaml");
  const double ug = 1e-6 * 9.80665;
  const auto accel_n = [&](const char* axis, double value) {
    return MeasuredParameter{Sensor::accel, MeasuredQuantity::white_noise, axis, value,
                             0.99 * value, 1.01 * value};
  };
  const auto items = check_compliance({accel_n("x", 170 * ug), accel_n("z", 170 * ug),
                                       accel_n("z", 200 * ug)},
                                      sheet);
  REQUIRE(items.size() == 3);
  CHECK(items[0].limit_si == test::rel(300 * ug, 1e-12));  // the entry's max on X
  CHECK_FALSE(items[0].limit_is_typical);
  CHECK(items[0].verdict == Verdict::pass);
  CHECK(items[1].limit_si == test::rel(190 * ug, 1e-12));  // Z's own typical value
  CHECK(items[1].limit_is_typical);
  CHECK(items[1].verdict == Verdict::pass);
  CHECK(items[2].verdict == Verdict::fail);
}
