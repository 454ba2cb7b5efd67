#pragma once
/// \file spec.hpp
/// IMU data sheets (specs/<vendor>_<part>.yaml): every value as printed (min / typ / max, the
/// number, its unit text), its SI value, the test condition and its source (document, revision,
/// page or table, primary or secondary). The schema is documented in specs/README.md.
///
/// A data sheet is a record of what a manufacturer printed, not a model: turning it into noise
/// terms needs conventions (which PSD a "noise density" is, what an "in-run bias stability"
/// means) and those live in convert.hpp. A compliance check compares a measurement with
/// SpecValue::limit() of the matching field.

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sigmatau/noise_model.hpp"
#include "sigmatau/units.hpp"

namespace sigmatau {

/// The schema version this parser reads (the `schema:` key of every file). Any other version is
/// rejected, so an old parser never silently misreads a newer file.
inline constexpr int kSpecSchemaVersion = 1;

/// Where a value was read.
struct SpecSource {
  std::string id;        ///< key in the file's `sources:` map
  std::string document;  ///< document title and number, e.g. "MPU-6000/MPU-6050 Product Specification PS-MPU-6000A-00"
  std::string revision;  ///< revision as printed ("3.4"); required for a primary source
  bool primary = false;  ///< true: the manufacturer's data sheet itself; false: a secondary quote
  std::string url;       ///< where it was read (optional)
  std::string note;      ///< free text (optional)
};

/// One number as printed, e.g. "±20 deg/s".
struct PrintedValue {
  std::string text;         ///< the text exactly as in the file ("±20 deg/s")
  double number = 0;        ///< the number as printed (20)
  std::string unit;         ///< the unit text as printed ("deg/s")
  bool plus_minus = false;  ///< printed with a leading ± (a symmetric bound)
  double value_si = 0;      ///< number converted to SI (units.hpp), e.g. 0.349 rad/s
  std::int64_t line = 0;    ///< 1-based line of the value in the file
  std::int64_t column = 0;  ///< 1-based column of the value in the file
};

/// What a sheet prints for one axis where it prints the axes apart (the BMI088's accelerometer
/// noise density: 160 µg/√Hz on X and Y, 190 µg/√Hz on Z). The entry's source, page and table
/// hold for it.
struct AxisValue {
  std::string axis;  ///< "x", "y" or "z"
  std::optional<PrintedValue> min;
  std::optional<PrintedValue> typ;
  std::optional<PrintedValue> max;
  std::string condition;  ///< as printed for that axis, may be empty
};

/// One data-sheet entry: min / typ / max where printed (at least one of them, or options), the
/// condition it holds under and its source.
struct SpecValue {
  std::optional<PrintedValue> min;
  std::optional<PrintedValue> typ;
  std::optional<PrintedValue> max;
  /// Selectable settings printed as a list (full-scale ranges, output data rates).
  std::vector<PrintedValue> options;
  std::string condition;  ///< test condition as printed ("at 10 Hz, 25 °C"), may be empty
  std::string note;       ///< remark by whoever wrote the file, may be empty
  SpecSource source;      ///< resolved from the file's `sources:` map
  std::string page;       ///< page in the source ("12"), may be empty for a secondary source
  std::string table;      ///< table or section in the source, may be empty
  std::int64_t line = 0;  ///< 1-based line of the field's key in the file
  /// Axes printed apart (`axes:` in the file); min / typ / max above hold for the other axes.
  std::vector<AxisValue> axes;

  /// This entry as it holds for one axis ("x", "y", "z"): that axis's min / typ / max and
  /// condition in place of the entry's where the sheet prints the axis apart, else the entry
  /// itself. Other names ("xy" of a cross-axis term) give the entry.
  SpecValue for_axis(std::string_view axis) const;

  /// The bound a measurement is compared with: max when printed, else typ (then
  /// limit_is_typical() is true), else nullptr.
  const PrintedValue* limit() const;
  /// True when limit() is the typical value because no max is printed.
  bool limit_is_typical() const { return !max && typ; }
  /// The value a filter model should use: typ when printed, else max, else min, else nullptr.
  const PrintedValue* nominal() const;
};

/// The fields a sensor section may hold. The key in the file is SpecFieldInfo::key (for
/// random_walk the key differs per sensor: angle_random_walk / velocity_random_walk).
enum class SpecField {
  noise_density,                        ///< rate noise density as printed (spectrum ASD)
  random_walk,                          ///< ARW / VRW (Allan N), e.g. 0.15 deg/sqrt(h)
  bias_instability,                     ///< in-run bias stability (an ADEV floor)
  rate_random_walk,                     ///< K
  rms_noise,                            ///< total RMS noise in a stated band
  initial_bias,                         ///< zero-rate / zero-g offset
  bias_over_temperature,                ///< total bias excursion over a temperature range
  bias_temperature_coefficient,         ///< bias change per kelvin
  sensitivity_error,                    ///< sensitivity / scale-factor tolerance (ratio)
  sensitivity_temperature_coefficient,  ///< sensitivity change per kelvin (ratio/K)
  cross_axis_sensitivity,               ///< cross-axis sensitivity (ratio)
  misalignment,                         ///< axis misalignment (angle)
  nonlinearity,                         ///< nonlinearity (ratio)
  g_sensitivity,                        ///< gyro linear-acceleration sensitivity
  full_scale,                           ///< measurement range(s)
  output_data_rate,                     ///< output data rate(s)
  bandwidth,                            ///< bandwidth / low-pass corner
};

/// Static description of a field for one sensor.
struct SpecFieldInfo {
  SpecField field;
  std::string_view key;          ///< YAML key
  std::string_view description;  ///< one line for `specs show`
  Dimension dimension;           ///< dimension every printed value must have
  bool positive = false;         ///< values must be > 0 (noise terms, rates); else >= 0
};

/// The fields a gyro or accel section accepts, in display order.
std::span<const SpecFieldInfo> spec_fields(Sensor sensor);
/// The description of `field` for `sensor`; nullptr when the sensor has no such field
/// (g_sensitivity is gyro only).
const SpecFieldInfo* spec_field_info(Sensor sensor, SpecField field);

/// The printed values of one triad.
struct SensorSheet {
  std::map<SpecField, SpecValue> values;
  /// The entry for `field`, or nullptr when the sheet does not print it ("not specified").
  const SpecValue* find(SpecField field) const;
};

/// One IMU data sheet.
struct DataSheet {
  int schema = kSpecSchemaVersion;
  std::string name;          ///< file stem, e.g. "tdk_mpu6050"
  std::string manufacturer;  ///< e.g. "TDK InvenSense"
  std::string part;          ///< e.g. "MPU-6050"
  std::string grade;         ///< consumer | industrial | tactical | navigation
  std::string description;   ///< may be empty
  std::string notes;         ///< may be empty
  std::filesystem::path file;
  std::map<std::string, SpecSource> sources;
  std::optional<SensorSheet> gyro;
  std::optional<SensorSheet> accel;

  /// The gyro or accel section, or nullptr when absent.
  const SensorSheet* sensor(Sensor which) const;
  /// "data sheet bosch_bmi088 (Bosch Sensortec BMI088)", as messages name a sheet.
  std::string label() const;
};

/// Parses a data sheet from YAML text. `file` names it in error messages. Throws ParseError
/// (file, line, column, message) on: unreadable YAML, a missing or unknown `schema` version,
/// an unknown or repeated key, a missing required key (manufacturer, part, grade, a value's
/// source), an unknown source id, a primary source without revision or a value from it without
/// page or table, a malformed number, an unknown unit, a wrong dimension, a value out of range,
/// min > typ, typ > max or min > max. Messages read "FIELD: found ..., expected ...".
DataSheet parse_data_sheet(std::string_view yaml_text, const std::string& file);

/// Reads and parses a data-sheet file (see parse_data_sheet). The name is the file stem.
DataSheet load_data_sheet(const std::filesystem::path& file);

/// The data-sheet files (*.yaml) in `directory`, sorted by name.
std::vector<std::filesystem::path> list_data_sheets(const std::filesystem::path& directory);

/// Resolves a `--spec` argument: an existing file path, else NAME or NAME.yaml in `directory`.
/// Throws Error listing where it looked.
std::filesystem::path find_data_sheet(std::string_view name_or_path,
                                      const std::filesystem::path& directory);

}  // namespace sigmatau
