// `sigmatau calibrate`: scale factors, misalignment, biases and their temperature dependence from
// a multi-position log (calibrate.hpp).
#include <iostream>
#include <memory>
#include <numbers>

#include "log_options.hpp"
#include "sigmatau/calibrate.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/output_file.hpp"
#include "sigmatau/simulate.hpp"
#include "sigmatau/units.hpp"
#include "verbs.hpp"

namespace sigmatau::cli {
namespace {

struct CalibrateArguments {
  LogArguments log;
  std::string gyro_columns, accel_columns, temp_column;
  std::string gyro_unit = "rad/s", accel_unit = "m/s^2", temp_unit = "K";
  std::optional<double> gravity;
  std::optional<double> latitude_deg;
  std::string reference_temperature = "25 degC";
  int min_orientations = 9;
  double confidence = 0.95;
  std::string format = "table";
  std::string output;
  bool force = false;
};

std::size_t find_column(const Log& log, const std::string& name, const std::string& option) {
  for (std::size_t i = 0; i < log.channel_names.size(); ++i)
    if (log.channel_names[i] == name) return i;
  std::string known;
  for (const auto& n : log.channel_names) known += (known.empty() ? "" : ", ") + n;
  throw Error(log.path + ": no column '" + name + "' (" + option + "); the log has: " + known);
}

void run_calibrate(const CalibrateArguments& a) {
  if (a.format != "table" && a.format != "json")
    throw Error("--format must be table or json, got '" + a.format + "'");
  if (!a.log.unit.empty())
    throw Error("calibrate: use --gyro-unit and --accel-unit instead of --unit");
  if (!a.output.empty()) check_can_write(a.output, a.force);
  LoadedChannels loaded = load_channels(a.log);
  if (loaded.kind == DataKind::phase)
    throw Error("calibrate: --kind must be rate or increment");
  Log& log = loaded.log;
  std::vector<double>().swap(log.t_s);  // calibrate works on sample indices / rate
  // The columns move into the calibration input (no second copy of the log); a column named
  // twice is copied from where it went.
  std::vector<std::vector<double>*> moved_to(log.channels.size(), nullptr);
  const auto take = [&](std::size_t column, std::vector<double>& into) {
    if (moved_to[column]) {
      into = *moved_to[column];
    } else {
      into = std::move(log.channels[column]);
      moved_to[column] = &into;
    }
  };
  const auto column_values = [&](std::size_t column) -> const std::vector<double>& {
    return moved_to[column] ? *moved_to[column] : log.channels[column];
  };
  const auto has = [&](const std::string& n) {
    for (const auto& c : log.channel_names)
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
  CalibrationInput in;
  in.rate_hz = loaded.rate_hz;
  in.increments = loaded.kind == DataKind::increment;
  const Dimension accel_dim = in.increments ? dim::velocity : dim::acceleration;
  const Dimension gyro_dim = in.increments ? dim::angle : dim::angular_rate;
  const std::string accel_unit = in.increments && a.accel_unit == "m/s^2" ? "m/s" : a.accel_unit;
  const std::string gyro_unit = in.increments && a.gyro_unit == "rad/s" ? "rad" : a.gyro_unit;
  const double accel_factor = parse_unit_as(accel_unit, accel_dim, "--accel-unit").factor;
  const auto accel_names = names(a.accel_columns, "a", "--accel");
  for (int i = 0; i < 3; ++i) {
    take(find_column(log, accel_names[static_cast<std::size_t>(i)], "--accel"),
         in.accel[static_cast<std::size_t>(i)]);
  }
  const auto gyro_names = names(a.gyro_columns, "g", "--gyro");
  double gyro_factor = 1;
  if (!a.gyro_columns.empty() || has(gyro_names[0])) {
    gyro_factor = parse_unit_as(gyro_unit, gyro_dim, "--gyro-unit").factor;
    for (int i = 0; i < 3; ++i) {
      take(find_column(log, gyro_names[static_cast<std::size_t>(i)], "--gyro"),
           in.gyro[static_cast<std::size_t>(i)]);
    }
  }
  const std::string temp = a.temp_column.empty() ? "temp" : a.temp_column;
  if (!a.temp_column.empty() || has(temp)) {
    const auto& column = column_values(find_column(log, temp, "--temp-column"));
    const std::string unit = a.temp_unit;
    in.temperature_k.reserve(column.size());
    for (double v : column) in.temperature_k.push_back(convert(v, unit, "K"));
  }
  for (auto& channel : log.channels) std::vector<double>().swap(channel);  // the columns not used
  for (auto& axis : in.accel) {
    for (double& v : axis) v *= accel_factor;
  }
  for (auto& axis : in.gyro) {
    for (double& v : axis) v *= gyro_factor;
  }
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
  o.confidence = a.confidence;
  {
    // "25 degC" is an absolute temperature: parse_quantity returns it in K with the offset.
    const Quantity q = parse_quantity(a.reference_temperature);
    if (!(q.dimension == dim::temperature))
      throw Error("--reference-temperature: expected a temperature, e.g. \"25 degC\"");
    o.reference_temperature_k = q.value_si;
  }
  const CalibrationResult result = calibrate(in, o);
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
  command->add_option("--gyro-unit", args->gyro_unit, "unit of the gyro columns (deg/s, dps, ...)")
      ->capture_default_str();
  command->add_option("--accel-unit", args->accel_unit, "unit of the accelerometer columns (g, mg, ...)")
      ->capture_default_str();
  command->add_option("--temp-unit", args->temp_unit, "unit of the temperature column (K, degC)")
      ->capture_default_str();
  command->add_option("--gravity", args->gravity, "local gravity [m/s^2] (default 9.80665)");
  command->add_option("--latitude", args->latitude_deg,
                      "latitude [deg]: normal gravity and the Earth rate's vertical part");
  command->add_option("--reference-temperature", args->reference_temperature,
                      "T0 of the bias temperature model")
      ->capture_default_str();
  command->add_option("--min-orientations", args->min_orientations,
                      "distinct orientations required")
      ->capture_default_str();
  command->add_option("--ci", args->confidence, "two-sided confidence level of the intervals")
      ->capture_default_str();
  command->add_option("--format", args->format, "table | json")->capture_default_str();
  command->add_option("-o,--output", args->output, "write to FILE instead of stdout");
  command->add_flag("--force", args->force, "overwrite an existing output file");
  command->callback([args] { run_calibrate(*args); });
}

}  // namespace sigmatau::cli
