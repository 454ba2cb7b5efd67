// `simulate --spec`: the noise terms a data sheet gives the simulator and the ones it leaves out
// (review C finding 8). Uses the shipped sheets in specs/, and a made-up fixture that prints no
// noise term at all (tests/data/specs/no_noise_terms.yaml).
#include "sigmatau/simulate_spec.hpp"

#include <doctest/doctest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "sigmatau/error.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

const std::filesystem::path kSpecsDir = std::filesystem::path(SIGMATAU_SOURCE_DIR) / "specs";

DataSheet sheet(const char* name) { return load_data_sheet(kSpecsDir / (std::string(name) + ".yaml")); }

/// The fixture with gyro ranges only and an accelerometer RMS noise (2.5 mg), no noise term.
DataSheet no_noise_terms() {
  return load_data_sheet(test::test_data_dir() / "specs" / "no_noise_terms.yaml");
}

/// The Error message of simulation_noise_from_data_sheet, or "" when it does not throw.
std::string refusal(const DataSheet& s, Sensor sensor) {
  try {
    (void)simulation_noise_from_data_sheet(s, sensor, DensityConvention::two_sided);
  } catch (const Error& e) {
    return e.what();
  }
  return {};
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("a sensor the sheet gives no noise term is refused, naming the sheet and the option") {
  SUBCASE("accelerometer: no noise field at all") {
    const DataSheet gyro_only =
        load_data_sheet(test::test_data_dir() / "specs" / "gyro_noise_only.yaml");
    const std::string m = refusal(gyro_only, Sensor::accel);
    CHECK(contains(m, "data sheet gyro_noise_only"));
    CHECK(contains(m, "prints no accel noise term"));
    CHECK(contains(m, "--accel-model"));
    CHECK(refusal(gyro_only, Sensor::gyro).empty());  // its gyro density is read
  }
  SUBCASE("gyro: ranges only") {
    const std::string m = refusal(no_noise_terms(), Sensor::gyro);
    CHECK(contains(m, "data sheet no_noise_terms"));
    CHECK(contains(m, "prints no gyro noise term"));
    CHECK(contains(m, "--model"));
  }
  SUBCASE("accelerometer: an RMS noise, which is no density, is named") {
    const std::string m = refusal(no_noise_terms(), Sensor::accel);
    CHECK(contains(m, "prints no accel noise term"));
    CHECK(contains(m, "RMS noise 2.5 mg is a total over the output band, not a density"));
  }
}

TEST_CASE("a sensor without white noise is simulated with what the sheet prints, and warned about") {
  for (const char* name : {"adi_adis16470", "adi_adis16505"}) {
    CAPTURE(name);
    const DataSheet s = sheet(name);
    const SheetNoise n = simulation_noise_from_data_sheet(s, Sensor::accel,
                                                          DensityConvention::two_sided);
    CHECK_FALSE(n.has_white);
    CHECK_FALSE(n.axes[0].white.has_value());
    CHECK(n.axes[2].bias_instability.has_value());
    REQUIRE(n.left_out.size() == 2);
    CHECK(contains(n.left_out[0], "white noise (no velocity random walk or noise density)"));
    CHECK(n.left_out[1] == "rate random walk");
    REQUIRE(n.read.size() == 1);
    CHECK(contains(n.read[0], "in-run bias stability"));
    const std::string w = sheet_noise_warning(s, Sensor::accel, n);
    CHECK(contains(w, "warning: data sheet " + std::string(name)));
    CHECK(contains(w, "prints no white noise for the accel"));
    CHECK(contains(w, "left out: white noise"));
    CHECK(contains(w, "--accel-model"));
  }
}

TEST_CASE("a sheet with white noise gives it, with no warning, and lists what it lacks") {
  const DataSheet s = sheet("tdk_icm42688p");
  const SheetNoise n = simulation_noise_from_data_sheet(s, Sensor::gyro, DensityConvention::two_sided);
  CHECK(n.has_white);
  CHECK(sheet_noise_warning(s, Sensor::gyro, n).empty());
  REQUIRE(n.read.size() == 1);
  CHECK(contains(n.read[0], "noise density 2.8"));
  CHECK(n.left_out == std::vector<std::string>{"bias instability", "rate random walk"});
  // STIM300's accelerometer: the velocity random walk is N itself.
  const SheetNoise a = simulation_noise_from_data_sheet(sheet("safran_stim300"), Sensor::accel,
                                                        DensityConvention::two_sided);
  CHECK(a.has_white);
  CHECK(a.left_out == std::vector<std::string>{"rate random walk"});
}

TEST_CASE("the LSM6DSO's noise densities are simulated, its RMS noise is not needed") {
  const DataSheet s = sheet("st_lsm6dso");
  for (const auto& row : {std::pair{Sensor::gyro, "noise density 3.8 mdps/√Hz"},
                          std::pair{Sensor::accel, "noise density 70 µg/√Hz"}}) {
    // Plain locals: CAPTURE's lambda cannot capture a structured binding before clang 16.
    const Sensor sensor = row.first;
    const char* const density = row.second;
    CAPTURE(to_string(sensor));
    const SheetNoise n = simulation_noise_from_data_sheet(s, sensor, DensityConvention::two_sided);
    CHECK(n.has_white);
    CHECK(sheet_noise_warning(s, sensor, n).empty());
    REQUIRE(n.read.size() == 1);
    CHECK(contains(n.read[0], density));
    CHECK(n.left_out == std::vector<std::string>{"bias instability", "rate random walk"});
  }
}

TEST_CASE("a density printed per axis is simulated per axis (BMI088 accelerometer: Z at 190/160)") {
  const SheetNoise n = simulation_noise_from_data_sheet(sheet("bosch_bmi088"), Sensor::accel,
                                                        DensityConvention::two_sided);
  REQUIRE(n.axes[0].white.has_value());
  REQUIRE(n.axes[2].white.has_value());
  CHECK(*n.axes[1].white == *n.axes[0].white);
  CHECK(*n.axes[2].white / *n.axes[0].white == test::rel(190.0 / 160.0, 1e-12));
  REQUIRE(n.read.size() == 1);
  CHECK(contains(n.read[0], "160 µg/√Hz (typ), 190 µg/√Hz (typ) on z"));
}
