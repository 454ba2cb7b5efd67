// The calibration's unit checks and notes (calibrate_checks.hpp): the median magnitude of a log,
// the refusal of a column read in a wrong unit (naming the unit given) only beyond the stated
// bounds, and the notes and table labels when a bias temperature model is dropped (review C).
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <numbers>
#include <string>
#include <vector>

#include "sigmatau/calibrate.hpp"
#include "sigmatau/calibrate_checks.hpp"
#include "sigmatau/calibrate_log.hpp"
#include "sigmatau/error.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

constexpr double kG = 9.80665;

using test::error_of;

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// A result with a gyroscope whose rotation fit left `rms` [rad] with chi^2/dof `chi2_dof`.
CalibrationResult gyro_result(double rms, double chi2_dof) {
  CalibrationResult r;
  TriadCalibration g;
  g.matrix_estimated = true;
  g.residual_rms = rms;
  g.dof = 13;
  g.chi2 = chi2_dof * g.dof;
  r.gyro = g;
  return r;
}

/// A result with temperatures of the static intervals `temps` [K]; the accelerometer's bias
/// temperature model present when `accel_model`, the gyroscope's never.
CalibrationResult temperature_result(const std::vector<double>& temps, bool accel_model) {
  CalibrationResult r;
  r.has_temperature = true;
  r.temperature_min_k = r.temperature_max_k = temps.front();
  for (double t : temps) {
    StaticInterval s;
    s.temperature_k = t;
    r.detection.intervals.push_back(s);
    r.temperature_min_k = std::min(r.temperature_min_k, t);
    r.temperature_max_k = std::max(r.temperature_max_k, t);
  }
  r.accel.matrix_estimated = true;
  r.accel.dof = 20;  // a fit with degrees of freedom left (0 adds its own note)
  if (accel_model) r.accel.temperature = std::array<BiasTemperatureAxis, 3>{};
  TriadCalibration g;
  g.matrix_estimated = true;
  g.dof = 30;
  r.gyro = g;
  return r;
}

}  // namespace

TEST_CASE("median_accel_magnitude: gravity from a mostly static log, rates and increments") {
  // 60 % of the rows rest (|a| = g in changing directions), 40 % are accelerated to 3 g: the
  // median is g to the histogram's bin (log10 step 1e-3, i.e. 0.23 %).
  const double bin = std::pow(10.0, 1e-3) - 1;
  for (bool increments : {false, true}) {
    const double rate = 200, per_sample = increments ? 1 / rate : 1.0;
    CalibrationLog log(false, false, std::int64_t{1} << 20);
    std::vector<double> rows;
    for (int i = 0; i < 1000; ++i) {
      const double m = (i % 5 < 3 ? 1.0 : 3.0) * kG * per_sample;
      const double th = 0.01 * i;
      rows.insert(rows.end(), {m * std::cos(th), m * std::sin(th) * 0.6, m * std::sin(th) * 0.8});
    }
    log.append(rows);
    const double median = median_accel_magnitude(log, rate, increments);
    CHECK(std::abs(median / kG - 1) <= bin);
  }
  CalibrationLog empty(false, false, 1024);
  CHECK(median_accel_magnitude(empty, 100, false) == 0);
}

TEST_CASE("check_accel_unit: a factor of 2 passes, a unit mix-up names the unit given") {
  CHECK(error_of([] { check_accel_unit(1.9 * kG, kG, "m/s^2", 1, false, "a.csv"); }).empty());
  CHECK(error_of([] { check_accel_unit(kG / 1.9, kG, "m/s^2", 1, false, "a.csv"); }).empty());
  // Columns in mg read as g: 1000 x the gravity.
  const std::string mg = error_of([] { check_accel_unit(1000 * kG, kG, "g", kG, false, "a.csv"); });
  CHECK(contains(mg, "a.csv: "));
  CHECK(contains(mg, "read in g (--accel-unit g)"));
  CHECK(contains(mg, "they look like mg (--accel-unit mg)"));
  CHECK(!contains(mg, "in m/s^2"));
  // Columns in m/s^2 read as g: 9.8 x.
  const std::string si = error_of([] { check_accel_unit(kG * kG, kG, "g", kG, false, ""); });
  CHECK(contains(si, "they look like m/s^2"));
  // Increments: no unit suggested, the unit given still named.
  const std::string inc = error_of([] { check_accel_unit(50 * kG, kG, "mm/s", 1e-3, true, ""); });
  CHECK(contains(inc, "read in mm/s (--accel-unit mm/s): is that their unit?"));
}

TEST_CASE("check_gyro_unit: refuses only a large misfit far beyond the noise") {
  const std::string wrong =
      error_of([] { check_gyro_unit(gyro_result(0.4, 1e4), "rad/s", "g.csv"); });
  CHECK(contains(wrong, "g.csv: "));
  CHECK(contains(wrong, "Are the gyro columns in rad/s (--gyro-unit rad/s"));
  // Below the angle bound however large chi^2 (a low-noise gyroscope's unmodelled errors) ...
  CHECK(error_of([] {
          check_gyro_unit(gyro_result(0.5 * kMaxGyroRotationMisfit, 1e5), "rad/s", "");
        }).empty());
  // ... and within the noise however large the angle (a very noisy gyroscope).
  CHECK(error_of([] {
          check_gyro_unit(gyro_result(0.4, 0.5 * kMinGyroMisfitChi2PerDof), "rad/s", "");
        }).empty());
  // No matrix (its note says why), no gyroscope: nothing to check.
  CalibrationResult none = gyro_result(0.4, 1e4);
  none.gyro->matrix_estimated = false;
  CHECK(error_of([&] { check_gyro_unit(none, "rad/s", ""); }).empty());
  CHECK(error_of([] { check_gyro_unit(CalibrationResult{}, "rad/s", ""); }).empty());
}

TEST_CASE("check_gyro_rotation_angles: a gyroscope that turned less than gravity did is refused") {
  // Four rests with gravity along +x, -y, -x, +y (the sensor turned +90 deg about z each time,
  // so gravity turned -90 deg in its frame), 100 rows of rotation about z between them
  // integrating to `fraction` of the turn.
  const double rate = 100;
  const auto run = [&](double fraction) {
    CalibrationLog log(true, false, std::int64_t{1} << 20);
    CalibrationResult r;
    r.accel.matrix_estimated = true;
    r.gyro = TriadCalibration{};
    const Eigen::Vector3d down[4] = {{kG, 0, 0}, {0, -kG, 0}, {-kG, 0, 0}, {0, kG, 0}};
    std::vector<double> rows;
    std::int64_t row = 0;
    for (int k = 0; k < 4; ++k) {
      StaticInterval s;
      s.first = row;
      for (int i = 0; i < 300; ++i, ++row)
        rows.insert(rows.end(), {down[k].x(), down[k].y(), down[k].z(), 0, 0, 0});
      s.last = row - 1;
      s.accel_mean = down[k];
      r.detection.intervals.push_back(s);
      if (k == 3) break;
      const double w = fraction * (std::numbers::pi / 2) * rate / 100;  // [rad/s] for 100 rows
      for (int i = 0; i < 100; ++i, ++row) rows.insert(rows.end(), {0, 0, 0, 0, 0, w});
    }
    log.append(rows);
    return error_of([&] { check_gyro_rotation_angles(log, rate, false, r, "deg/s", "r.csv"); });
  };
  CHECK(run(1.0).empty());
  CHECK(run(0.9).empty());  // a -10 % gain error misses by 9 deg, under kMaxRawGyroMisfit
  const std::string small = run(1 / 57.3);  // rad/s read as deg/s
  CHECK(contains(small, "r.csv: "));
  CHECK(contains(small, "read in deg/s (--gyro-unit deg/s)"));
  CHECK(contains(small, "in 3 of 3 rotations"));
  // Three times too far (270 deg for 90): gravity lands 180 deg from where it went.
  const std::string far = run(3.0);
  CHECK(contains(far,
                 "read in deg/s (--gyro-unit deg/s), integrated across the rotations, misses "
                 "where gravity went by more than 30 deg in 3 of 3 rotations (median 180 deg)"));
  CHECK(run(1.1).empty());  // a 10 % gain error misses by 9 deg
}

TEST_CASE("check_temperature_unit: degC read as K and K read as degC are refused") {
  CHECK(error_of([] {
          check_temperature_unit(temperature_result({233.15, 398.15}, true), "K", "");
        }).empty());  // -40 to 125 degC, an industrial rating
  const std::string cold = error_of([] {
    check_temperature_unit(temperature_result({293.15 - 273.15, 40}, true), "K", "t.csv");
  });
  CHECK(contains(cold, "t.csv: "));
  CHECK(contains(cold, "read in K (--temp-unit K)"));
  CHECK(contains(cold, "is the column in degC (--temp-unit degC)?"));
  const std::string hot = error_of([] {
    check_temperature_unit(temperature_result({566, 586}, true), "degC", "");
  });
  CHECK(contains(hot, "above any IMU's range"));
  CalibrationResult none;  // no temperature column: nothing to check
  CHECK(error_of([&] { check_temperature_unit(none, "K", ""); }).empty());
}

TEST_CASE("median_temperature_k and the check before the calibration: glitches cannot move it") {
  // 1000 rows at 20-40 (degC read as K) with 10 glitches at 0: the median is the rows' lower
  // median to a bin (0.1 K), near 30 K whatever the glitches.
  CalibrationLog log(false, true, std::int64_t{1} << 20);
  std::vector<double> rows, temps;
  for (int i = 0; i < 1000; ++i) {
    temps.push_back(i % 100 == 0 ? 0.0 : 20 + 0.02 * i);
    rows.insert(rows.end(), {0, 0, kG, temps.back()});
  }
  log.append(rows);
  std::sort(temps.begin(), temps.end());
  const double median = median_temperature_k(log);
  CHECK(std::abs(median - temps[499]) <= 0.1);
  const std::string cold = error_of([&] { check_temperature_unit(median, "K", "t.csv"); });
  CHECK(contains(cold, "t.csv: "));
  CHECK(contains(cold, "read in K (--temp-unit K), has a median of"));
  CHECK(contains(cold, "is the column in degC (--temp-unit degC)?"));
  CHECK(error_of([] { check_temperature_unit(303.0, "K", ""); }).empty());
  CHECK(contains(error_of([] { check_temperature_unit(576.0, "degC", ""); }),
                 "above any IMU's range"));
  CalibrationLog none(false, false, 1024);
  CHECK(median_temperature_k(none) == 0);
}

TEST_CASE(
    "calibration_notes and the table: a dropped temperature model is said, with where b holds") {
  // Span 0.4 K: neither sensor gets a temperature model.
  const CalibrationResult flat = temperature_result({298.0, 298.4}, false);
  const auto notes = calibration_notes(flat);
  REQUIRE(notes.size() == 2);
  CHECK(contains(notes[0],
                 "accelerometer: no bias temperature model (the static intervals span only 0.4 K"));
  CHECK(contains(notes[0], "mean temperature 25.05 degC, not at T0 = 25.00 degC"));
  CHECK(contains(notes[1], "gyroscope: no bias temperature model"));
  const std::string flat_table = calibration_table(flat);
  CHECK(contains(flat_table,
                 "# temperature 24.85 to 25.25 degC over the static intervals (mean 25.05 degC)"));
  CHECK(contains(flat_table,
                 "bias b at the log's mean temperature 25.05 degC (no temperature model)"));
  CHECK(contains(flat_table, "compensation: x = A^-1 (y - b)\n"));
  CHECK(contains(flat_table, "notes:\n  accelerometer: no bias temperature model"));
  CHECK(!contains(flat_table, "T0 = 25.00 degC,"));
  // A span of 20 K, the accelerometer's model present: only the gyroscope's is noted (its
  // reason unknown here), with the drift warning.
  CalibrationResult ramp = temperature_result({293.15, 313.15}, true);
  const auto ramp_notes = calibration_notes(ramp);
  REQUIRE(ramp_notes.size() == 1);
  CHECK(contains(ramp_notes[0], "gyroscope: no bias temperature model"));
  CHECK(contains(ramp_notes[0], "its drift over the 20 K the log spans"));
  const std::string ramp_table = calibration_table(ramp);
  CHECK(contains(ramp_table, "bias b at T0 = 25.00 degC (temperature model below)"));
  CHECK(contains(ramp_table,
                 "(c1 = c2 = 0 for the gyroscope, whose b holds at the mean temperature)"));
  // The JSON says at which temperature each bias holds: T0 with a model, else the mean (the
  // tolerance is the rounding of the sums, well below a mK).
  const auto doc = nlohmann::json::parse(calibration_json(ramp));
  CHECK(std::abs(doc["accelerometer"]["bias_temperature_k"].get<double>() - 298.15) <= 1e-9);
  CHECK(std::abs(doc["gyroscope"]["bias_temperature_k"].get<double>() - 303.15) <= 1e-9);
  // A matrix not estimated is a note too.
  ramp.gyro->matrix_estimated = false;
  ramp.gyro->note = "too few rotations";
  CHECK(contains(calibration_notes(ramp)[0],
                 "gyroscope: matrix not estimated, only the bias: too few rotations"));
  // Without a temperature column: no notes, the bias labelled as such.
  CalibrationResult plain;
  plain.accel.matrix_estimated = true;
  plain.accel.dof = 20;
  CHECK(calibration_notes(plain).empty());
  // No degrees of freedom left: said.
  plain.accel.dof = 0;
  REQUIRE(calibration_notes(plain).size() == 1);
  CHECK(contains(calibration_notes(plain)[0], "accelerometer: the fit has 0 degrees of freedom"));
  plain.accel.dof = 20;
  CHECK(contains(calibration_table(plain), "bias b (no temperature column)"));
}
