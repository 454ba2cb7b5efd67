#pragma once
// The options every log-reading verb shares (adev, psd, fit, analyze, calibrate), and turning
// them into channels in SI.
#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

#include "sigmatau/confidence.hpp"
#include "sigmatau/log_reader.hpp"
#include "sigmatau/noise_model.hpp"
#include "sigmatau/phase_series.hpp"
#include "sigmatau/units.hpp"

namespace sigmatau::cli {

struct LogArguments {
  std::string input;
  std::string columns;       // comma-separated names or indices
  std::string time_column;
  std::string time_unit;     // s|ms|us|ns|min|h|d; empty: the time column's name suffix, else s
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
  // Per sensor, instead of --unit (add_sensor_unit_options: adev, psd, fit, analyze, calibrate).
  std::string gyro_unit;   // unit of the columns named as gyro axes (classify_channel)
  std::string accel_unit;  // unit of the columns named as accelerometer axes
  // Found in the file's header once the command line is parsed (apply_file_header), not options:
  std::string time_column_found;  // the time column found by its name ("" when none or given)
};

/// Adds INPUT and the log options to `command`; returns the log options (all but INPUT), so a
/// verb can tell which were given (given_option_names). Once the command line is parsed, the
/// file's header is looked at (apply_file_header).
std::vector<CLI::Option*> add_log_options(CLI::App& command, LogArguments& args);

/// What a text log file's header says, applied before any verb reads it: a Stable32 data file's
/// declared Type (phase or frequency) becomes --kind and its Tau --rate where those were not
/// given (a note on stderr says so; a contradicting --kind or --rate is warned about), and the
/// time column found by its name is recorded in args.time_column_found. Nothing for stdin, a
/// bag, raw binary, or a file that cannot be read (the verb's own read reports that).
void apply_file_header(LogArguments& args, bool kind_given, bool rate_given);

/// The notes on stderr about what a text log's header told the reader: the time column found by
/// name, the text columns left out, a Stable32 file's time tags left out (note_reading calls it).
void note_header(const std::string& input, const TextHeader& header);

/// A time or rate option: "100 s", "100s", "2 min", "200 Hz", or a bare number in `bare_unit`;
/// in SI. Throws UnitError naming `option` on another dimension or a malformed text.
double quantity_option(const std::string& text, const Dimension& d, const char* option,
                       const char* bare_unit);

/// The names of the options in `options` given on the command line, comma-separated in the
/// order of `options` ("" when none was given).
std::string given_option_names(const std::vector<CLI::Option*>& options);

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

LoadedChannels load_channels(const LogArguments& args);

/// The reader options of the arguments (validated as load_channels does).
LogOptions log_options_from(const LogArguments& args);

/// The notes on stderr about how the log was read, from its timing report (nothing when there
/// is nothing to say): for a ROS bag read without --topic, the topic picked (the only
/// sensor_msgs/Imu one) and the bag's topics with types and counts; for a bag whose messages
/// arrived out of stamp order, how many were sorted within the reorder window and the largest
/// lateness [s]; with --nonfinite skip, how many rows were dropped; for a bag whose recording
/// was cut short, read under --truncated use, where it was cut and how many messages were used;
/// with --gaps report, the gaps found. Every path that reads a log (load_channels, adev's stream
/// and out-of-core paths) calls it once.
void note_reading(const LogArguments& args, const LogOptions& options, const TimingReport& timing);

/// The dimension of a gyro's (`gyro`) or accelerometer's unit for data of `kind`: a rate
/// (rad/s, m/s^2), or a per-sample amount for increments and phase (rad, m/s). For
/// --gyro-unit / --accel-unit (channel_units.hpp) and --kind checks.
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
  /// Starts a new pass over the input, shown as "LABEL: read ..." with its own rate (a log
  /// read several times restarts at 0 % each time, and says which pass it is).
  void stage(const std::string& label);
  void finish();

 private:
  bool enabled_;
  bool drawn_ = false;
  std::string label_;
  double start_s_;
  double last_s_ = -1;
};

/// The EDF model for the log's data (default_edf_model): EdfModel::discrete for IMU data (a ROS
/// bag, --gyro-unit / --accel-unit, a --unit of an angular rate or acceleration, of an angle or
/// velocity with --kind increment or phase, or raw counts), EdfModel::greenhall for clock data
/// and values without a unit.
EdfModel edf_model_for(const LogArguments& args);

/// adev's --edf: `given` when set, else edf_model_for's ("discrete" or "greenhall"); always
/// "greenhall" by default in stream mode (`stream`), whose strided EDF follows Greenhall's.
std::string edf_model_name(const std::string& given, const LogArguments& args, bool stream);

/// Splits "a,b,c" (empty fields are an Error naming the option).
std::vector<std::string> split_list(const std::string& text, const std::string& option);

/// Whether stderr is a terminal (progress is shown only then).
bool stderr_is_tty();

}  // namespace sigmatau::cli
