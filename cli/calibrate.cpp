// `sigmatau calibrate`: scale factors, misalignment, biases and their temperature dependence from
// a multi-position log (calibrate.hpp).
#include <cstdio>
#include <iostream>
#include <memory>
#include <numbers>

#include "channel_units.hpp"
#include "log_options.hpp"
#include "memory_budget.hpp"
#include "sigmatau/calibrate.hpp"
#include "sigmatau/calibrate_checks.hpp"
#include "sigmatau/calibrate_log.hpp"
#include "sigmatau/earth.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/output_file.hpp"
#include "sigmatau/units.hpp"
#include "verbs.hpp"

namespace sigmatau::cli {
namespace {

struct CalibrateArguments {
  LogArguments log;  // with --gyro-unit / --accel-unit (add_sensor_unit_options; unset: SI)
  std::string gyro_columns, accel_columns, temp_column;
  std::string temp_unit = "K";
  std::optional<double> gravity;
  std::optional<double> latitude_deg;
  std::string reference_temperature = "25 degC";
  int min_orientations = 9;
  double confidence = 0.95;
  std::string format = "table";
  std::string output;
  bool force = false;
  std::string memory = "256MiB";
};

std::size_t find_column(const std::vector<std::string>& channel_names, const std::string& path,
                        const std::string& name, const std::string& option) {
  for (std::size_t i = 0; i < channel_names.size(); ++i)
    if (channel_names[i] == name) return i;
  std::string known;
  for (const auto& n : channel_names) known += (known.empty() ? "" : ", ") + n;
  throw Error(path + ": no column '" + name + "' (" + option + "); the log has: " + known);
}

/// Which input column feeds each channel of the calibration rows, and the factors to SI.
struct ColumnPlan {
  std::vector<std::size_t> column;  // per row value: ax ay az [gx gy gz] [temp]
  bool gyro = false, temperature = false;
  double accel_factor = 1, gyro_factor = 1;
  std::string accel_unit, gyro_unit;  // as given (or SI), for the unit checks' messages
  Unit temp_unit, kelvin;  // temperature: (v * factor + offset - K offset) / K factor (convert())
};

ColumnPlan plan_columns(const CalibrateArguments& a, const std::vector<std::string>& channel_names,
                        bool increments) {
  const auto has = [&](const std::string& n) {
    for (const auto& c : channel_names)
      if (c == n) return true;
    return false;
  };
  const auto names = [&](const std::string& given, const char* prefix, const std::string& option) {
    std::vector<std::string> out;
    if (!given.empty()) {
      out = split_list(given, option);
      if (out.size() != 3) throw Error(option + ": expected three column names x,y,z");
    } else {
      for (const char* axis : {"x", "y", "z"}) out.push_back(std::string(prefix) + axis);
    }
    return out;
  };
  ColumnPlan plan;
  // The sensor of each column is the one --accel / --gyro (or its default names) gives it; the
  // columns' units follow the rules every log-reading verb shares (channel_units_of: both units
  // checked against --kind whether or not the log has that sensor, a ROS bag's fixed units).
  std::vector<std::string> columns = names(a.accel_columns, "a", "--accel");
  const auto gyro_names = names(a.gyro_columns, "g", "--gyro");
  plan.gyro = !a.gyro_columns.empty() || has(gyro_names[0]);
  if (plan.gyro) columns.insert(columns.end(), gyro_names.begin(), gyro_names.end());
  std::vector<ChannelSensor> sensors;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    const bool gyro = c >= 3;
    const bool named = !(gyro ? a.gyro_columns : a.accel_columns).empty();
    sensors.push_back({ChannelRole{gyro ? Sensor::gyro : Sensor::accel, static_cast<int>(c % 3)},
                       named ? (gyro ? "by --gyro" : "by --accel") : "by its name"});
  }
  const std::vector<ChannelUnit> units = channel_units_of(a.log, columns, sensors, false);
  // No unit given: the values are taken as SI (the unit checks' messages name it).
  const auto factor = [](const ChannelUnit& u) { return u.unit.empty() ? 1.0 : u.to_si; };
  const auto label = [](const ChannelUnit& u, const char* si) {
    return u.unit.empty() ? std::string(si) : u.unit;
  };
  plan.accel_factor = factor(units[0]);
  plan.accel_unit = label(units[0], increments ? "m/s" : "m/s^2");
  if (plan.gyro) {
    plan.gyro_factor = factor(units[3]);
    plan.gyro_unit = label(units[3], increments ? "rad" : "rad/s");
  }
  for (std::size_t c = 0; c < columns.size(); ++c) {
    plan.column.push_back(
        find_column(channel_names, a.log.input, columns[c], c < 3 ? "--accel" : "--gyro"));
  }
  // The temperature unit is checked whether or not the log has a temperature column: a wrong
  // --temp-unit is a mistake either way.
  parse_unit_as(a.temp_unit, dim::temperature, "--temp-unit");
  const std::string temp = a.temp_column.empty() ? "temp" : a.temp_column;
  if (!a.temp_column.empty() || has(temp)) {
    plan.temperature = true;
    plan.column.push_back(find_column(channel_names, a.log.input, temp, "--temp-column"));
    plan.temp_unit = parse_unit(a.temp_unit);
    plan.kelvin = parse_unit("K");
  }
  return plan;
}

/// Appends the rows of a block (values[column][row]) to the calibration log, in SI.
void append_rows(const ColumnPlan& plan, const std::vector<std::vector<double>>& values,
                 CalibrationLog& log, std::vector<double>& row_buffer) {
  const std::size_t rows = values.empty() ? 0 : values[0].size();
  const std::size_t c = plan.column.size();
  row_buffer.resize(rows * c);
  for (std::size_t r = 0; r < rows; ++r) {
    double* out = row_buffer.data() + r * c;
    for (std::size_t k = 0; k < 3; ++k) out[k] = values[plan.column[k]][r] * plan.accel_factor;
    if (plan.gyro)
      for (std::size_t k = 3; k < 6; ++k) out[k] = values[plan.column[k]][r] * plan.gyro_factor;
    if (plan.temperature) {
      const double v = values[plan.column[c - 1]][r];
      out[c - 1] = (v * plan.temp_unit.factor + plan.temp_unit.offset - plan.kelvin.offset) /
                   plan.kelvin.factor;
    }
  }
  log.append(row_buffer);
}

/// Fewest distinct orientations that can ever determine the accelerometer: its 9 unknowns
/// (3 gains, 3 cross-axis terms, 3 biases) meet one equation per orientation (gravity's magnitude).
constexpr int kMinPossibleOrientations = 9;

void run_calibrate(const CalibrateArguments& a) {
  if (a.min_orientations < kMinPossibleOrientations || a.min_orientations > 1000)
    throw Error("--min-orientations " + std::to_string(a.min_orientations) +
                ": must be 9 to 1000. Gravity's magnitude gives one equation per orientation and "
                "the accelerometer has 9 unknowns (3 gains, 3 cross-axis terms, 3 biases), so "
                "fewer than 9 distinct orientations can never determine them (the classic 6 faces "
                "need at least 3 more positions, e.g. tilted 45 deg between two faces)");
  if (a.format != "table" && a.format != "json")
    throw Error("--format must be table or json, got '" + a.format + "'");
  if (!a.log.unit.empty())
    throw Error("calibrate: use --gyro-unit and --accel-unit instead of --unit");
  if (!a.output.empty()) check_can_write(a.output, a.force);
  const std::int64_t memory = parse_bytes(a.memory);
  if (parse_data_kind(a.log.kind) == DataKind::phase)
    throw Error("calibrate: --kind must be rate or increment");
  const bool increments = parse_data_kind(a.log.kind) == DataKind::increment;
  const LogOptions options = log_options_from(a.log);
  // The rows go into a CalibrationLog: in memory up to --memory, beyond it in a temporary file.
  // --gaps fill needs the whole log in memory to interpolate (read_log), as the other verbs do.
  std::unique_ptr<CalibrationLog> log;
  ColumnPlan used;
  double rate_hz = 0;
  std::vector<double> row_buffer;
  const auto start = [&](const std::vector<std::string>& channel_names) {
    used = plan_columns(a, channel_names, increments);
    log = std::make_unique<CalibrationLog>(used.gyro, used.temperature, memory);
    return used;
  };
  bool noted = false;
  const auto note_spill = [&] {
    if (noted || !log->spilled()) return;
    noted = true;
    std::cerr << "sigmatau: note: " << a.log.input << ": more than --memory " << a.memory
              << " of samples; keeping them in a temporary file in " << log->directory()
              << " (bounded memory, the same results)\n";
  };
  if (options.gaps == GapPolicy::fill) {
    // Read as they are: plan_columns gives the sensors' columns their units (load_channels would
    // want a unit for every column, the temperature too).
    LogArguments as_read = a.log;
    as_read.gyro_unit.clear();
    as_read.accel_unit.clear();
    LoadedChannels loaded = load_channels(as_read);
    const ColumnPlan plan = start(loaded.log.channel_names);
    append_rows(plan, loaded.log.channels, *log, row_buffer);
    rate_hz = loaded.rate_hz;
  } else {
    LogReader reader(options);
    const ColumnPlan plan = start(reader.channel_names());
    Progress progress;
    SampleBlock block;
    while (reader.read_block(block)) {
      append_rows(plan, block.values, *log, row_buffer);
      progress.update(reader.bytes_read(), reader.total_bytes());
    }
    progress.finish();
    const TimingReport& timing = reader.timing();
    note_reading(a.log, options, timing);
    if (log->rows() == 0) {
      throw ParseError(options.path == "-" ? "<stdin>" : options.path, 0, 0,
                       "no samples: the input holds no data rows" +
                           std::string(timing.rows_skipped_nonfinite > 0
                                           ? " (every row held a non-finite value and was skipped)"
                                           : ""));
    }
    rate_hz = resolve_rate_hz(a.log.rate_hz, timing, a.log.input);
  }
  std::vector<double>().swap(row_buffer);
  note_spill();
  CalibrationOptions o;
  if (a.gravity && a.latitude_deg)
    throw Error("give --gravity or --latitude, not both (--latitude sets the normal gravity)");
  if (a.latitude_deg) {
    if (!(std::abs(*a.latitude_deg) <= 90)) throw Error("--latitude must be within +-90 deg");
    o.latitude_rad = *a.latitude_deg * std::numbers::pi / 180;
    o.gravity = normal_gravity(*o.latitude_rad);
  }
  if (a.gravity) o.gravity = *a.gravity;
  o.min_orientations = a.min_orientations;
  o.rotation_memory_bytes = memory / 4;
  o.confidence = a.confidence;
  {
    // "25 degC" is an absolute temperature: parse_quantity returns it in K with the offset.
    const Quantity q = parse_quantity(a.reference_temperature);
    if (!(q.dimension == dim::temperature))
      throw Error("--reference-temperature: expected a temperature, e.g. \"25 degC\"");
    o.reference_temperature_k = q.value_si;
  }
  const std::string path = a.log.input == "-" ? "<stdin>" : a.log.input;
  // A column in a wrong unit is named with the unit the user gave, before the calibration
  // (whose own magnitude check knows only SI).
  check_accel_unit(median_accel_magnitude(*log, rate_hz, increments), o.gravity, used.accel_unit,
                   used.accel_factor, increments, path);
  if (used.temperature) check_temperature_unit(median_temperature_k(*log), a.temp_unit, path);
  CalibrationResult result;
  try {
    result = calibrate(*log, rate_hz, increments, o);
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());  // the library's reasons do not know the file
  }
  check_temperature_unit(result, a.temp_unit, path);
  if (used.gyro) {
    check_gyro_rotation_angles(*log, rate_hz, increments, result, used.gyro_unit, path);
    check_gyro_unit(result, used.gyro_unit, path);
  }
  for (const auto& n : calibration_notes(result)) std::cerr << "sigmatau: note: " << n << "\n";
  if (!a.gravity && !a.latitude_deg) {
    // The accelerometer's gains are relative to the gravity assumed: local gravity is 0.26 %
    // below standard gravity at the equator and 0.26 % above it at the poles (normal_gravity).
    char text[320];
    std::snprintf(text, sizeof text,
                  "gravity taken as standard gravity, %.5f m/s^2 (no --latitude or --gravity): "
                  "local gravity differs from it by %+.2f %% at the equator and %+.2f %% at the "
                  "poles, and the accelerometer's gain errors absorb the difference",
                  o.gravity, 100 * (normal_gravity(0) / o.gravity - 1),
                  100 * (normal_gravity(std::numbers::pi / 2) / o.gravity - 1));
    std::cerr << "sigmatau: note: " << text << "\n";
  }
  const std::string text = a.format == "json" ? calibration_json(result) : calibration_table(result);
  if (a.output.empty()) {
    std::cout << text;
  } else {
    write_file_atomically(a.output, text, a.force);
    std::cout << "wrote " << a.output << "\n";
  }
}

}  // namespace

void add_calibrate_command(CLI::App& app) {
  auto args = std::make_shared<CalibrateArguments>();
  CLI::App* command = app.add_subcommand(
      "calibrate", "Scale factors, misalignment and biases (and their temperature dependence) "
                   "from a multi-position log, without a rate table");
  add_log_options(*command, args->log);
  command->add_option("--gyro", args->gyro_columns, "gyro columns x,y,z (default gx,gy,gz)");
  command->add_option("--accel", args->accel_columns, "accelerometer columns x,y,z (default ax,ay,az)");
  command->add_option("--temp-column", args->temp_column, "temperature column (default temp, when present)");
  // The shared --gyro-unit / --accel-unit, with calibrate's own help: its columns are chosen by
  // --gyro / --accel, --unit is refused, and a unit not given is SI.
  add_sensor_unit_options(*command, args->log);
  command->get_option("--gyro-unit")
      ->description("unit of the gyro columns (--gyro), e.g. deg/s; default rad/s (rad with "
                    "--kind increment)");
  command->get_option("--accel-unit")
      ->description("unit of the accelerometer columns (--accel), e.g. g or mg; default m/s^2 "
                    "(m/s with --kind increment)");
  command->add_option("--temp-unit", args->temp_unit, "unit of the temperature column (K, degC)")
      ->capture_default_str();
  command->add_option("--gravity", args->gravity, "local gravity [m/s^2] (default 9.80665)");
  command->add_option("--latitude", args->latitude_deg,
                      "latitude [deg]: normal gravity and the Earth rate's vertical part");
  command->add_option("--reference-temperature", args->reference_temperature,
                      "T0 of the bias temperature model")
      ->capture_default_str();
  command->add_option("--min-orientations", args->min_orientations,
                      "distinct orientations required (9 to 1000: fewer never determine the "
                      "accelerometer)")
      ->capture_default_str();
  command->add_option("--ci", args->confidence,
                      "two-sided confidence level of the intervals; 0.95 by default, as a "
                      "calibration's uncertainties are usually stated (adev's error bars default "
                      "to one sigma, 0.683)")
      ->capture_default_str();
  command->add_option("--format", args->format, "table | json")->capture_default_str();
  command->add_option("-o,--output", args->output, "write to FILE instead of stdout");
  command->add_flag("--force", args->force, "overwrite an existing output file");
  command->add_option("--memory", args->memory,
                      "memory for the samples, e.g. 1GiB: beyond it they are kept in a temporary "
                      "file (TMPDIR) and read back (same results); the gyroscope's rotations get "
                      "a quarter of it more, the detector about 40 MiB")
      ->capture_default_str();
  command->callback([args] { run_calibrate(*args); });
}

}  // namespace sigmatau::cli
