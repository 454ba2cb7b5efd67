#pragma once
// The options every log-reading verb shares (adev, psd, fit, analyze, calibrate), and turning
// them into channels in SI.
#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

#include "sigmatau/log_reader.hpp"
#include "sigmatau/noise_model.hpp"
#include "sigmatau/phase_series.hpp"
#include "sigmatau/units.hpp"

namespace sigmatau::cli {

struct LogArguments {
  std::string input;
  std::string columns;       // comma-separated names or indices
  std::string time_column;
  std::string time_unit = "s";
  std::optional<double> rate_hz;
  std::string kind = "rate";
  std::string unit;          // input unit; empty: numbers are taken as they are
  std::string binary;        // i16|i32|f32|f64
  int channels = 0;
  bool big_endian = false;
  std::int64_t skip_bytes = 0;
  std::string gaps = "error";      // error|split|fill|report
  std::string nonfinite = "error"; // error|skip
  // ROS bags:
  std::string topic;                          // sensor_msgs/Imu topic; empty: the only one
  std::string stamp;                          // header|receive; empty: header
  std::optional<std::int64_t> reorder_window; // [messages]; unset: LogOptions' default
  std::string truncated;                      // error|use (a recording cut short); empty: error
  // Per sensor, instead of --unit (adev, psd: add_sensor_unit_options); fit and analyze keep
  // their own.
  std::string gyro_unit;   // unit of the columns named as gyro axes (classify_channel)
  std::string accel_unit;  // unit of the columns named as accelerometer axes
};

/// Adds INPUT and the log options to `command`; returns the log options (all but INPUT), so a
/// verb can tell which were given (given_option_names).
std::vector<CLI::Option*> add_log_options(CLI::App& command, LogArguments& args);

/// A time or rate option: "100 s", "100s", "2 min", "200 Hz", or a bare number in `bare_unit`;
/// in SI. Throws UnitError naming `option` on another dimension or a malformed text.
double quantity_option(const std::string& text, const Dimension& d, const char* option,
                       const char* bare_unit);

/// The names of the options in `options` given on the command line, comma-separated in the
/// order of `options` ("" when none was given).
std::string given_option_names(const std::vector<CLI::Option*>& options);

/// Adds --gyro-unit and --accel-unit (into args.gyro_unit / accel_unit) to `command`.
void add_sensor_unit_options(CLI::App& command, LogArguments& args);

/// The unit of one channel's values, for labelling and converting its results.
struct ChannelUnit {
  std::string unit;         ///< as given or known ("" = unknown: numbers taken as they are)
  Dimension dimension;      ///< of `unit`
  double to_si = 1;         ///< one `unit` in SI
  double result_to_si = 1;  ///< computed value x this = SI value (1 when the samples were
                            ///< already scaled to SI as they were read, to_si otherwise)
  std::string source;       ///< where the unit comes from: "--unit", "--gyro-unit", ... or
                            ///< "ROS sensor_msgs/Imu (REP 103)"
};

/// A log read into memory and converted to SI (when --unit was given).
struct LoadedChannels {
  Log log;
  double rate_hz = 0;
  DataKind kind = DataKind::rate;
  std::string unit;              // the input unit as given ("" = as read)
  double to_si = 1;              // input value * to_si = SI value
  Dimension dimension;           // of the input unit
  /// One per channel (after resolve_channel_units): the unit its results are labelled with.
  std::vector<ChannelUnit> channel_units;
};

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

LoadedChannels load_channels(const LogArguments& args);

/// The reader options of the arguments (validated as load_channels does).
LogOptions log_options_from(const LogArguments& args);

/// The notes on stderr about how the log was read, from its timing report (nothing when there
/// is nothing to say): for a ROS bag read without --topic, the topic picked (the only
/// sensor_msgs/Imu one) and the bag's topics with types and counts; for a bag whose messages
/// arrived out of stamp order, how many were sorted within the reorder window and the largest
/// lateness [s]; with --nonfinite skip, how many rows were dropped; for a bag whose recording was
/// cut short, read under --truncated use, where it was cut and how many messages were used. Every path that reads a log
/// (load_channels, adev's stream and out-of-core paths) calls it once.
void note_reading(const LogArguments& args, const LogOptions& options, const TimingReport& timing);

/// The dimension of a gyro's (`gyro`) or accelerometer's unit for data of `kind`: a rate
/// (rad/s, m/s^2), or a per-sample amount for increments and phase (rad, m/s). For
/// --gyro-unit / --accel-unit in `fit` and `analyze`.
Dimension sensor_unit_dimension(bool gyro, DataKind kind);

/// The input unit of the arguments: fills unit, to_si and dimension of `loaded`.
void set_input_unit(const LogArguments& args, LoadedChannels& loaded);

/// A one-line progress display on stderr (only when stderr is a terminal): bytes read, of the
/// total when known, and the rate. Call update() often; it redraws at most 4 times a second.
class Progress {
 public:
  Progress();
  ~Progress();
  void update(std::int64_t bytes_read, std::int64_t total_bytes);
  void finish();

 private:
  bool enabled_;
  bool drawn_ = false;
  double start_s_;
  double last_s_ = -1;
};

/// Splits "a,b,c" (empty fields are an Error naming the option).
std::vector<std::string> split_list(const std::string& text, const std::string& option);

/// Whether stderr is a terminal (progress is shown only then).
bool stderr_is_tty();

}  // namespace sigmatau::cli
