#pragma once
// The unit of every channel of a log, for every verb that reads one (adev, psd, fit, analyze,
// calibrate): one --unit, --gyro-unit / --accel-unit by the columns' sensors (their names,
// classify_channel, or analyze's and calibrate's --gyro / --accel), or the units a ROS bag's
// sensor_msgs/Imu fixes; and the printed unit of each channel's results (--out-unit, one per
// sensor).
#include <optional>
#include <string>
#include <vector>

#include "log_options.hpp"
#include "sigmatau/channel_names.hpp"

namespace sigmatau::cli {

/// Adds --gyro-unit and --accel-unit (into args.gyro_unit / accel_unit) to `command`.
void add_sensor_unit_options(CLI::App& command, LogArguments& args);

/// A channel's sensor as a verb knows it, and how (for messages).
struct ChannelSensor {
  std::optional<ChannelRole> role;  ///< nullopt: neither a gyro nor an accelerometer axis
  std::string by = "by its name";   ///< how the role is known: "by its name", "by --gyro", ...
};

/// The sensors of `names` by name (classify_channel).
std::vector<ChannelSensor> sensors_by_name(const std::vector<std::string>& names);

/// The unit of each channel `names[c]` whose sensor is `sensors[c]`, by the rules and with the
/// errors of resolve_channel_units (which calls it with sensors_by_name). A ROS bag's channel
/// takes its unit from its name (the message field it was read from), whatever `sensors` says.
std::vector<ChannelUnit> channel_units_of(const LogArguments& args,
                                          const std::vector<std::string>& names,
                                          const std::vector<ChannelSensor>& sensors,
                                          bool notes = true);

/// The sensor a channel's unit names for data of `kind` (deg/s: gyro, g: accelerometer; for
/// increments and phase deg and m/s); nullopt when the unit is unknown or neither (s, a clock).
std::optional<Sensor> sensor_of_unit(const ChannelUnit& unit, DataKind kind);

/// Fills loaded.channel_units from the channel names (loaded.log.channel_names), the options
/// and, for a ROS bag, the units sensor_msgs/Imu fixes (gx gy gz rad/s, ax ay az m/s^2, REP
/// 103). Throws Error (exit 2) naming the column and the options to use when
/// - a single --unit's sensor (an angular rate or an acceleration) contradicts a column that is
///   a gyro or accelerometer axis by its name (deg/s on accel_x): one unit cannot be both;
/// - --unit, --gyro-unit or --accel-unit contradicts a bag channel's unit (even deg/s against
///   rad/s: the message's units are fixed);
/// - --gyro-unit / --accel-unit is given and a column is neither sensor by its name.
/// Call once the names are known, on every path (in memory, stream, out of core).
/// `notes`: print the note about a sensor left without a unit (off for early_channel_units).
void resolve_channel_units(const LogArguments& args, LoadedChannels& loaded, bool notes = true);

/// The channel names known before the log is read: from the header (a LogReader opened and
/// dropped), or for a ROS bag --columns or the six Imu channels. nullopt for stdin (it cannot be
/// read twice) and, unless `always`, when no unit option is given to a text or binary log
/// (nothing to check). Throws as the reader does.
std::optional<std::vector<std::string>> early_channel_names(const LogArguments& args,
                                                            bool always = false);

/// The channel units known before the log is read (so a contradiction is an error at once, not
/// after a long read): the channel names from the header (a LogReader opened and dropped), or
/// for a ROS bag from --columns or the six Imu channels; resolve_channel_units on them.
/// nullopt for stdin (it cannot be read twice) and when no unit option is given to a text or
/// binary log (nothing to check). Throws as resolve_channel_units and the reader do.
std::optional<LoadedChannels> early_channel_units(const LogArguments& args);

/// True when --gyro-unit or --accel-unit was given or the input is a ROS bag: then the samples
/// are not scaled on reading (loaded.to_si stays 1) and each channel's results are scaled by
/// its ChannelUnit::result_to_si.
bool per_channel_units(const LogArguments& args);

/// The unit a channel's rate-domain results (deviations of rate data, densities) are in:
/// "" when unknown. For increments and phase, "(unit)/s"; a clock phase in s gives "1".
struct RateUnit {
  std::string label;     ///< "" when the channel's unit is unknown
  Dimension dimension;   ///< of the rate (angular rate, acceleration, 1 for a clock)
  double from_result = 1;///< printed in `label` = computed value x this
};
RateUnit rate_unit(const ChannelUnit& unit, DataKind kind);

/// Picks, from an --out-unit list ("deg/h" or "deg/h,ug"), the unit of dimension `wanted` for
/// each channel; returns one index into `units_text` per channel (-1: none matches, the channel
/// keeps its own unit). Throws Error when an --out-unit matches no channel ("... but `what`
/// <dimensions>", e.g. what = "the deviations are") or when no channel has a known unit.
std::vector<int> match_out_units(const std::vector<std::string>& units_text,
                                 const std::vector<Dimension>& wanted,
                                 const std::vector<bool>& known, const std::string& what);

}  // namespace sigmatau::cli
