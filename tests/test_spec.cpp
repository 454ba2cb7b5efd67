// Data-sheet parser: every shipped sheet parses with sane values, known values convert to the
// published SI numbers, and each bad fixture fails with the exact located error.
#include <cmath>
#include <numbers>
#include <string>

#include "sigmatau/error.hpp"
#include "sigmatau/spec.hpp"
#include "test_support.hpp"

using namespace sigmatau;
using sigmatau::test::test_data_dir;

namespace {

const std::filesystem::path kSpecsDir = std::filesystem::path(SIGMATAU_SOURCE_DIR) / "specs";
constexpr double kDeg = std::numbers::pi / 180;

/// Floating-point round-off of a unit conversion (a few multiplications of exact constants).
constexpr double kRoundOff = 1e-12;

const PrintedValue& typ(const DataSheet& s, Sensor sensor, SpecField field) {
  const SpecValue* v = s.sensor(sensor)->find(field);
  REQUIRE(v != nullptr);
  REQUIRE(v->typ.has_value());
  return *v->typ;
}

/// Parses a fixture and returns the ParseError it throws (fails the test if none).
ParseError parse_error(const std::string& fixture) {
  const auto path = test_data_dir() / "specs" / fixture;
  try {
    load_data_sheet(path);
  } catch (const ParseError& e) {
    CHECK(e.file() == path.string());
    return e;
  }
  FAIL("no error for " << fixture);
  return ParseError("", 0, 0, "");
}

}  // namespace

TEST_CASE("every shipped data sheet parses, with sourced, finite, non-negative values") {
  const auto files = list_data_sheets(kSpecsDir);
  CHECK(files.size() >= 12);  // the issue asks for at least 12 real IMUs
  for (const auto& file : files) {
    INFO(file.string());
    const DataSheet sheet = load_data_sheet(file);
    CHECK(sheet.name == file.stem().string());
    CHECK(!sheet.manufacturer.empty());
    CHECK(!sheet.part.empty());
    for (const Sensor sensor : {Sensor::gyro, Sensor::accel}) {
      const SensorSheet* s = sheet.sensor(sensor);
      if (!s) continue;
      for (const auto& [field, value] : s->values) {
        const SpecFieldInfo* info = spec_field_info(sensor, field);
        REQUIRE(info != nullptr);
        INFO(info->key);
        CHECK(!value.source.document.empty());
        if (value.source.primary) {
          CHECK(!value.source.revision.empty());
          CHECK((!value.page.empty() || !value.table.empty()));
        }
        std::vector<PrintedValue> all = value.options;
        for (const auto* p : {&value.min, &value.typ, &value.max}) {
          if (*p) all.push_back(**p);
        }
        CHECK(!all.empty());
        for (const auto& p : all) {
          INFO(p.text);
          CHECK(std::isfinite(p.value_si));
          CHECK(p.value_si >= 0);
          CHECK(!p.unit.empty());
          CHECK(p.line > 0);
        }
      }
    }
  }
}

TEST_CASE("the MPU-6050 sheet holds the primary figures of PS-MPU-6000A-00 rev 3.4 pp. 12-13") {
  const DataSheet s = load_data_sheet(kSpecsDir / "tdk_mpu6050.yaml");
  // Hand conversions: 0.005 deg/s/sqrt(Hz) x pi/180; 400 ug/sqrt(Hz) x 9.80665e-6; ±20 deg/s.
  SIGMATAU_CHECK_REL(typ(s, Sensor::gyro, SpecField::noise_density).value_si, 0.005 * kDeg,
                     kRoundOff);
  SIGMATAU_CHECK_REL(typ(s, Sensor::accel, SpecField::noise_density).value_si, 400 * 9.80665e-6,
                     kRoundOff);
  const PrintedValue& zro = typ(s, Sensor::gyro, SpecField::initial_bias);
  CHECK(zro.plus_minus);
  CHECK(zro.number == 20);
  CHECK(zro.unit == "º/s");
  SIGMATAU_CHECK_REL(zro.value_si, 20 * kDeg, kRoundOff);
  const SpecValue* nd = s.gyro->find(SpecField::noise_density);
  CHECK(nd->source.primary);
  CHECK(nd->source.revision.starts_with("3.4"));
  CHECK(nd->page == "12");
  CHECK(nd->limit_is_typical());  // only typ is printed: a check compares against typ
  const SpecValue* fs = s.accel->find(SpecField::full_scale);
  REQUIRE(fs->options.size() == 4);
  SIGMATAU_CHECK_REL(fs->options[3].value_si, 16 * 9.80665, kRoundOff);
  CHECK(s.gyro->find(SpecField::bias_instability) == nullptr);  // not specified
}

TEST_CASE("STIM300 values convert to the published SI numbers (THEORY.md T5)") {
  const DataSheet s = load_data_sheet(kSpecsDir / "safran_stim300.yaml");
  // T5 (NavToolkit stim300_model): 1e-3 m/s^1.5, 2.4241e-6 rad/s, 4.3633e-5 rad/s^0.5 are
  // printed to 5 digits (rtol 1e-4 covers their rounding).
  SIGMATAU_CHECK_REL(typ(s, Sensor::accel, SpecField::random_walk).value_si, 1e-3, kRoundOff);
  SIGMATAU_CHECK_REL(typ(s, Sensor::gyro, SpecField::bias_instability).value_si, 2.4241e-6, 1e-4);
  SIGMATAU_CHECK_REL(typ(s, Sensor::gyro, SpecField::random_walk).value_si, 4.3633e-5, 1e-4);
  // T5 gives 4.905e-4 m/s^2 for 0.05 mg using g = 9.81; sigmatau uses standard gravity
  // 9.80665, a relative difference of 3.6e-4, hence rtol 5e-4.
  SIGMATAU_CHECK_REL(typ(s, Sensor::accel, SpecField::bias_instability).value_si, 4.905e-4, 5e-4);
}

TEST_CASE("VN-100 noise densities convert to the published SI numbers (THEORY.md T6)") {
  const DataSheet s = load_data_sheet(kSpecsDir / "vectornav_vn100.yaml");
  // T6: 6.10866e-5 rad/s/sqrt(Hz) printed to 6 digits (rtol 1e-5).
  SIGMATAU_CHECK_REL(typ(s, Sensor::gyro, SpecField::noise_density).value_si, 6.10866e-5, 1e-5);
  // T6: 1.372e-3 m/s^2/sqrt(Hz) uses g = 9.8; standard gravity 9.80665 differs by 6.8e-4.
  SIGMATAU_CHECK_REL(typ(s, Sensor::accel, SpecField::noise_density).value_si, 1.372e-3, 1e-3);
}

TEST_CASE("the VN-100's accelerometer bias stability is a maximum, as its data sheet prints it") {
  // Quoted "< 0.04 mg" from the v7.0 data sheet (specs/vectornav_vn100.yaml, source cr7): an
  // upper bound, so a check compares with it as a guaranteed maximum, not a typical value.
  const DataSheet s = load_data_sheet(kSpecsDir / "vectornav_vn100.yaml");
  const SpecValue* b = s.accel->find(SpecField::bias_instability);
  REQUIRE(b != nullptr);
  CHECK_FALSE(b->typ.has_value());
  REQUIRE(b->max.has_value());
  CHECK_FALSE(b->limit_is_typical());
  SIGMATAU_CHECK_REL(b->max->value_si, 0.04e-3 * 9.80665, kRoundOff);
}

TEST_CASE("the BMI088 accelerometer noise density is read per axis from BST-BMI088-DS001-14") {
  // Table 4, page 9: 160 µg/√Hz on X and Y, 190 µg/√Hz on Z (±3 g, 25 °C, normal mode).
  const DataSheet s = load_data_sheet(kSpecsDir / "bosch_bmi088.yaml");
  const SpecValue* nd = s.accel->find(SpecField::noise_density);
  REQUIRE(nd != nullptr);
  CHECK(nd->source.primary);
  CHECK(nd->page == "9");
  const double ug = 1e-6 * 9.80665;
  REQUIRE(nd->for_axis("x").typ.has_value());
  SIGMATAU_CHECK_REL(nd->for_axis("x").typ->value_si, 160 * ug, kRoundOff);
  SIGMATAU_CHECK_REL(nd->for_axis("y").typ->value_si, 160 * ug, kRoundOff);
  SIGMATAU_CHECK_REL(nd->for_axis("z").typ->value_si, 190 * ug, kRoundOff);
  CHECK(nd->for_axis("z").condition.starts_with("Z axis"));
  CHECK(nd->for_axis("xy").typ->value_si == nd->typ->value_si);  // no axis of that name
}

TEST_CASE("the ADIS16465 accelerometer velocity random walk is read from Rev. B, Table 1") {
  // Page 3: 0.012 m/s/√h (1 σ); page 4: noise density 23 µg/√Hz rms (10-40 Hz, no filtering).
  const DataSheet s = load_data_sheet(kSpecsDir / "adi_adis16465.yaml");
  const SpecValue* vrw = s.accel->find(SpecField::random_walk);
  REQUIRE(vrw != nullptr);
  CHECK(vrw->source.primary);
  CHECK(vrw->page == "3");
  SIGMATAU_CHECK_REL(vrw->typ->value_si, 0.012 / 60.0, kRoundOff);
  SIGMATAU_CHECK_REL(typ(s, Sensor::accel, SpecField::noise_density).value_si, 23e-6 * 9.80665,
                     kRoundOff);
}

TEST_CASE("a value with typ and max reports max as its limit") {
  const DataSheet s = load_data_sheet(test_data_dir() / "specs" / "good_minimal.yaml");
  const SpecValue* b = s.gyro->find(SpecField::bias_instability);
  REQUIRE(b != nullptr);
  CHECK(b->limit() == &*b->max);
  CHECK(!b->limit_is_typical());
  CHECK(b->nominal() == &*b->typ);
  SIGMATAU_CHECK_REL(b->max->value_si, 6 * kDeg / 3600, kRoundOff);
}

TEST_CASE("bad data sheets fail with the file, line, column, field, found and expected") {
  SUBCASE("unknown schema version") {
    const ParseError e = parse_error("bad_schema_version.yaml");
    CHECK(e.line() == 2);
    CHECK(e.column() == 9);
    CHECK(e.message() == "schema: found version \"2\", expected 1 (the only version this "
                         "sigmatau reads)");
  }
  SUBCASE("unknown field") {
    const ParseError e = parse_error("unknown_field.yaml");
    CHECK(e.line() == 11);
    CHECK(e.column() == 3);
    CHECK(e.message().starts_with(
        "gyro: found unknown key \"noise_densty\", expected one of noise_density, "
        "angle_random_walk, bias_instability"));
  }
  SUBCASE("repeated field") {
    const ParseError e = parse_error("duplicate_field.yaml");
    CHECK(e.line() == 12);
    CHECK(e.message() == "gyro: found key \"noise_density\" twice, expected it once");
  }
  SUBCASE("unknown unit: the column points at the unit") {
    const ParseError e = parse_error("unknown_unit.yaml");
    CHECK(e.line() == 12);
    CHECK(e.column() == 16);  // "typ: " starts at 5, the value at 10, "furlong" at 10 + 6
    CHECK(e.message() == "gyro.noise_density.typ: unknown unit \"furlong\" at column 7 of "
                         "\"0.005 furlong/s/sqrt(Hz)\"");
  }
  SUBCASE("wrong dimension") {
    const ParseError e = parse_error("wrong_dimension.yaml");
    CHECK(e.line() == 12);
    CHECK(e.column() == 10);
    CHECK(e.message() == "gyro.bias_instability.typ: expected angle/time (e.g. rad/s), found "
                         "angle/sqrt(time) (deg/sqrt(h)) in \"3 deg/sqrt(h)\"");
  }
  SUBCASE("typ above max") {
    const ParseError e = parse_error("typ_above_max.yaml");
    CHECK(e.line() == 13);  // the max value's line
    CHECK(e.message() ==
          "gyro.bias_instability: found typ 5 deg/h > max 3 deg/h, expected typ <= max");
  }
  SUBCASE("malformed value") {
    const ParseError e = parse_error("malformed_value.yaml");
    CHECK(e.line() == 12);
    CHECK(e.message() == "accel.noise_density.typ: found \"abc ug/sqrt(Hz)\", expected a number "
                         "with its unit as printed (e.g. \"1 m/s^1.5\")");
  }
  SUBCASE("missing unit") {
    const ParseError e = parse_error("missing_unit.yaml");
    CHECK(e.line() == 12);
    CHECK(e.message() == "accel.nonlinearity.typ: found \"0.5\" without a unit, expected a "
                         "number with its unit as printed (e.g. \"0.5 %\")");
  }
  SUBCASE("unknown source id") {
    const ParseError e = parse_error("unknown_source.yaml");
    CHECK(e.line() == 13);
    CHECK(e.message() ==
          "gyro.noise_density.source: found \"datasheet\", expected one of the sources (ds)");
  }
  SUBCASE("primary source without page or table") {
    const ParseError e = parse_error("primary_without_page.yaml");
    CHECK(e.line() == 11);
    CHECK(e.message() == "gyro.noise_density: found a primary source without page or table, "
                         "expected page: N or table: NAME");
  }
  SUBCASE("a value no sensor comes near (issue 28: 1e308 became inf and null in filter files)") {
    const std::string sheet =
        "schema: 1\nmanufacturer: Test\npart: T-1\ngrade: consumer\n"
        "sources:\n  ds:\n    document: Test\n    kind: secondary\n"
        "gyro:\n  noise_density:\n    typ: 1e308 deg/s/sqrt(Hz)\n"
        "    source: ds\n";
    try {
      parse_data_sheet(sheet, "big.yaml");
      FAIL("1e308 deg/s/sqrt(Hz) was accepted");
    } catch (const ParseError& e) {
      CHECK(e.line() == 11);
      CHECK(e.column() == 10);
      CHECK(e.message() ==
            "gyro.noise_density.typ: found 1e308 deg/s/sqrt(Hz), expected a value "
            "below 1e+100 rad/sqrt(s) (no sensor comes near it: a typo or a unit "
            "slip?)");
    }
  }
  SUBCASE("negative magnitude") {
    const ParseError e = parse_error("negative_value.yaml");
    CHECK(e.line() == 12);
    CHECK(e.message() == "gyro.initial_bias.typ: found -20 deg/s, expected a magnitude >= 0 "
                         "(write a symmetric bound as ±X)");
  }
}

TEST_CASE("an axis under axes: other than x, y, z is a located error") {
  const ParseError e = parse_error("bad_axis.yaml");
  CHECK(e.line() == 15);
  CHECK(e.column() == 7);
  CHECK(e.message().starts_with("accel.noise_density.axes: found unknown key \"w\", expected one of x, y, z"));
}

TEST_CASE("invalid YAML and missing keys are located errors too") {
  CHECK_THROWS_AS(parse_data_sheet("schema: [1", "inline.yaml"), ParseError);
  try {
    parse_data_sheet("schema: 1\nmanufacturer: X\npart: Y\ngrade: cheap\n", "inline.yaml");
    FAIL("no error");
  } catch (const ParseError& e) {
    CHECK(e.line() == 4);
    CHECK(e.message() ==
          "grade: found \"cheap\", expected consumer, industrial, tactical or navigation");
  }
}

TEST_CASE("find_data_sheet resolves a name, a name.yaml and a path") {
  CHECK(find_data_sheet("tdk_mpu6050", kSpecsDir) == kSpecsDir / "tdk_mpu6050.yaml");
  CHECK(find_data_sheet("tdk_mpu6050.yaml", kSpecsDir) == kSpecsDir / "tdk_mpu6050.yaml");
  CHECK_THROWS_AS(find_data_sheet("no_such_imu", kSpecsDir), Error);
}
