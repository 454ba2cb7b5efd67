#include "channel_units.hpp"

#include <algorithm>
#include <cstdio>

#include "sigmatau/channel_names.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau::cli {

void add_sensor_unit_options(CLI::App& command, LogArguments& args) {
  command.add_option("--gyro-unit", args.gyro_unit,
                     "unit of the gyro columns (named gx / gyro_x / wx ...), instead of --unit "
                     "(which names one unit for every column), e.g. deg/s");
  command.add_option("--accel-unit", args.accel_unit,
                     "unit of the accelerometer columns (named ax / accel_x ...), instead of "
                     "--unit, e.g. g");
}

bool per_channel_units(const LogArguments& args) {
  return !args.gyro_unit.empty() || !args.accel_unit.empty() || is_bag_path(args.input);
}

namespace {

/// The sensor a unit of dimension `d` names for data of `kind` (nullopt: neither an angular
/// rate nor an acceleration, e.g. s for a clock).
std::optional<Sensor> sensor_of_dimension(const Dimension& d, DataKind kind) {
  if (d == sensor_unit_dimension(true, kind)) return Sensor::gyro;
  if (d == sensor_unit_dimension(false, kind)) return Sensor::accel;
  return std::nullopt;
}

const char* sensor_words(Sensor s) { return s == Sensor::gyro ? "a gyro" : "an accelerometer"; }

/// ROS REP 103 / sensor_msgs/Imu: angular_velocity in rad/s, linear_acceleration in m/s^2.
ChannelUnit bag_unit(Sensor s) {
  ChannelUnit u;
  u.unit = s == Sensor::gyro ? "rad/s" : "m/s^2";
  u.dimension = s == Sensor::gyro ? dim::angular_rate : dim::acceleration;
  u.source = "ROS sensor_msgs/Imu (REP 103)";
  return u;
}

}  // namespace

std::optional<Sensor> sensor_of_unit(const ChannelUnit& unit, DataKind kind) {
  if (unit.unit.empty()) return std::nullopt;
  return sensor_of_dimension(unit.dimension, kind);
}

std::vector<ChannelSensor> sensors_by_name(const std::vector<std::string>& names) {
  std::vector<ChannelSensor> sensors;
  sensors.reserve(names.size());
  for (const auto& name : names) sensors.push_back({classify_channel(name)});
  return sensors;
}

namespace {
/// Whether early_channel_names reads the names (see there).
bool names_known_early(const LogArguments& args, bool always) {
  const bool any_unit = !args.unit.empty() || !args.gyro_unit.empty() || !args.accel_unit.empty();
  return args.input != "-" && (is_bag_path(args.input) || any_unit || always);
}
}  // namespace

std::optional<std::vector<std::string>> early_channel_names(const LogArguments& args, bool always) {
  if (!names_known_early(args, always)) return std::nullopt;
  const LogOptions options = log_options_from(args);
  if (is_bag_path(args.input)) {
    return options.columns.empty() ? std::vector<std::string>{"gx", "gy", "gz", "ax", "ay", "az"}
                                   : options.columns;
  }
  return LogReader(options).channel_names();
}

std::optional<LoadedChannels> early_channel_units(const LogArguments& args) {
  if (!names_known_early(args, false)) return std::nullopt;
  LoadedChannels loaded;
  set_input_unit(args, loaded);  // a bad --unit is named before the file is opened
  loaded.log.channel_names = *early_channel_names(args);
  resolve_channel_units(args, loaded, false);
  return loaded;
}

void resolve_channel_units(const LogArguments& args, LoadedChannels& loaded, bool notes) {
  loaded.channel_units =
      channel_units_of(args, loaded.log.channel_names, sensors_by_name(loaded.log.channel_names), notes);
}

std::vector<ChannelUnit> channel_units_of(const LogArguments& args,
                                          const std::vector<std::string>& names,
                                          const std::vector<ChannelSensor>& sensors, bool notes) {
  std::vector<ChannelUnit> units(names.size());
  const bool bag = is_bag_path(args.input);
  const bool per_sensor = !args.gyro_unit.empty() || !args.accel_unit.empty();
  const DataKind kind = parse_data_kind(args.kind);
  if (bag && kind != DataKind::rate) {
    throw Error(args.input + ": a ROS bag's sensor_msgs/Imu messages are rates (rad/s, m/s^2): "
                "leave out --kind " + args.kind);
  }
  if (per_sensor && !args.unit.empty()) {
    throw Error("--unit " + args.unit + " names one unit for every column; with --gyro-unit / "
                "--accel-unit leave it out");
  }
  // The units given, parsed once: --gyro-unit / --accel-unit, or one --unit for all.
  std::optional<ChannelUnit> given_gyro, given_accel, given_all;
  auto given = [&](const std::string& text, const Dimension& d, const char* option) {
    const Unit u = parse_unit_as(text, d, option);
    return ChannelUnit{text, u.dimension, u.factor, u.factor, option};
  };
  if (!args.gyro_unit.empty()) given_gyro = given(args.gyro_unit, sensor_unit_dimension(true, kind), "--gyro-unit");
  if (!args.accel_unit.empty()) given_accel = given(args.accel_unit, sensor_unit_dimension(false, kind), "--accel-unit");
  if (!args.unit.empty()) {
    // load_channels scaled the samples to SI already, except with per-channel units (a bag).
    const Unit u = parse_unit(args.unit);  // loaded.to_si is 1 for a bag (not scaled on reading)
    given_all = ChannelUnit{args.unit, u.dimension, u.factor, bag ? u.factor : 1.0, "--unit"};
  }
  std::string left_out;  // columns of the sensor whose --gyro-unit / --accel-unit is missing
  for (std::size_t c = 0; c < names.size(); ++c) {
    ChannelUnit& unit = units[c];
    if (bag) {
      // The message field the channel was read from fixes its unit.
      const auto field = classify_channel(names[c]);
      if (!field) continue;  // not an Imu axis (cannot happen with the bag reader's names)
      unit = bag_unit(field->sensor);
      const std::optional<ChannelUnit>& other =
          given_all ? given_all : (field->sensor == Sensor::gyro ? given_gyro : given_accel);
      if (other && !(other->dimension == unit.dimension && other->to_si == 1.0)) {
        throw Error(args.input + ": channel " + names[c] + " is " + unit.unit +
                    " (a ROS bag's sensor_msgs/Imu, whose units REP 103 fixes), but " +
                    other->source + " " + other->unit + " says otherwise; leave " +
                    other->source + " out (adev and psd print the results in another unit with "
                    "--out-unit)");
      }
      continue;
    }
    const std::optional<ChannelRole>& role = sensors[c].role;
    if (given_all) {
      unit = *given_all;
      const auto unit_sensor = sensor_of_dimension(unit.dimension, kind);
      if (role && unit_sensor && *unit_sensor != role->sensor) {
        throw Error("--unit " + args.unit + " is " +
                    (*unit_sensor == Sensor::gyro ? "an angular rate" : "an acceleration") +
                    " (" + sensor_words(*unit_sensor) + "'s unit), but column " + names[c] +
                    " is " + sensor_words(role->sensor) + " axis " + sensors[c].by +
                    "; give each sensor its unit with --gyro-unit and "
                    "--accel-unit (e.g. --gyro-unit deg/s --accel-unit g), or choose the columns "
                    "of one sensor with --columns");
      }
      continue;
    }
    if (!per_sensor) continue;  // no unit at all: numbers as they are
    if (!role) {
      throw Error(args.input + ": column \"" + names[c] + "\" is neither a gyro nor an "
                  "accelerometer by its name (gx / gyro_x / wx, ax / accel_x), so --gyro-unit / "
                  "--accel-unit cannot say its unit; choose the sensor columns with --columns");
    }
    const auto& chosen = role->sensor == Sensor::gyro ? given_gyro : given_accel;
    if (chosen) {
      unit = *chosen;
    } else {
      left_out += (left_out.empty() ? "" : ", ") + names[c];
    }
  }
  if (notes && !left_out.empty()) {
    std::fprintf(stderr, "sigmatau: note: %s: no %s: %s left in the input unit\n", args.input.c_str(),
                 args.gyro_unit.empty() ? "--gyro-unit" : "--accel-unit", left_out.c_str());
  }
  return units;
}

RateUnit rate_unit(const ChannelUnit& unit, DataKind kind) {
  RateUnit r;
  if (unit.unit.empty()) return r;
  r.dimension = unit.dimension;
  r.from_result = unit.result_to_si / unit.to_si;  // computed -> SI -> the input unit
  if (kind == DataKind::rate) {
    r.label = unit.unit;
    return r;
  }
  r.dimension.time2 -= 2;
  if (unit.dimension == dim::time) {
    r.label = "1";  // clock phase in s: fractional frequency
    r.from_result = unit.result_to_si;
    return r;
  }
  r.label = "(" + unit.unit + ")/s";
  return r;
}

std::vector<int> match_out_units(const std::vector<std::string>& units_text,
                                 const std::vector<Dimension>& wanted,
                                 const std::vector<bool>& known, const std::string& what) {
  std::vector<int> chosen(wanted.size(), -1);
  if (units_text.empty()) return chosen;
  if (std::none_of(known.begin(), known.end(), [](bool k) { return k; })) {
    throw Error("--out-unit needs --unit (the unit of the input values; or --gyro-unit / "
                "--accel-unit for a log with both sensors)");
  }
  for (std::size_t i = 0; i < units_text.size(); ++i) {
    const Unit unit = parse_unit(units_text[i]);
    bool used = false;
    for (std::size_t c = 0; c < wanted.size(); ++c) {
      if (known[c] && wanted[c] == unit.dimension) {
        if (chosen[c] >= 0) throw Error("--out-unit gives two units of " + to_string(unit.dimension));
        chosen[c] = static_cast<int>(i);
        used = true;
      }
    }
    if (!used) {
      std::string dims;
      for (std::size_t c = 0; c < wanted.size(); ++c) {
        if (!known[c]) continue;
        const std::string d = to_string(wanted[c]);
        if (dims.find(d) == std::string::npos) dims += (dims.empty() ? "" : " or ") + d;
      }
      throw Error("--out-unit " + units_text[i] + " is " + to_string(unit.dimension) + ", but " +
                  what + " " + dims);
    }
  }
  return chosen;
}

}  // namespace sigmatau::cli
