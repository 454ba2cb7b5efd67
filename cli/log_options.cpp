#include "log_options.hpp"

#include "channel_units.hpp"

#include <unistd.h>

#include <filesystem>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "sigmatau/error.hpp"
#include "sigmatau/sampling_limits.hpp"

namespace sigmatau::cli {

std::vector<std::string> split_list(const std::string& text, const std::string& option) {
  std::vector<std::string> items;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    std::string item = text.substr(start, end - start);
    while (!item.empty() && item.front() == ' ') item.erase(item.begin());
    while (!item.empty() && item.back() == ' ') item.pop_back();
    if (item.empty()) throw Error(option + ": empty item in list \"" + text + "\"");
    items.push_back(item);
    start = end + 1;
  }
  return items;
}

bool stderr_is_tty() { return ::isatty(STDERR_FILENO) == 1; }

std::vector<CLI::Option*> add_log_options(CLI::App& command, LogArguments& args) {
  const std::size_t options_before = command.get_options().size();
  const CLI::Option* input = command.add_option("INPUT", args.input,
                     "log file (CSV/TSV/whitespace text, .gz, raw binary), - for stdin, or a ROS "
                     "bag (ROS 1 .bag, ROS 2 .mcap or .db3, a rosbag2 folder): its "
                     "sensor_msgs/Imu messages as channels gx gy gz [rad/s] ax ay az [m/s^2]")
      ->required();
  command.add_option("--columns", args.columns,
                     "channels to analyse: header names or 0-based indices, comma-separated "
                     "(default: every numeric column except the time column)");
  command.add_option("--time-column", args.time_column,
                     "time stamp column (name or index; default: the column named t, time or "
                     "timestamp, any case, e.g. t_ms or Timestamp_ns)");
  command.add_option("--time-unit", args.time_unit,
                     "unit of the time column: s|ms|us|ns|min|h|d (d: days, e.g. MJD; default: "
                     "the unit suffix of its name, as in t_ms, else s)");
  CLI::Option* const rate = command.add_option("--rate", args.rate_hz,
                     "sample rate [Hz], e.g. 100 or \"100 Hz\" (default: measured from the time column)")
      ->transform(
          [](const std::string& text) {
            // "100 Hz" or "2 kHz" as convert reads its --rate: the same parser, in Hz.
            char hz[40];
            std::snprintf(hz, sizeof hz, "%.17g",
                          checked_rate_hz(quantity_option(text, dim::frequency, "--rate", "Hz"),
                                          "--rate"));
            return std::string(hz);
          },
          "", "Hz");
  CLI::Option* const kind = command.add_option("--kind", args.kind,
                     "what the values are: rate (e.g. deg/s, m/s^2), increment (delta angle or "
                     "velocity per sample), phase (integrated angle, or clock phase in s)")
      ->capture_default_str();
  command.add_option("--unit", args.unit,
                     "unit of the values, e.g. deg/s, rad/s, mdps, g, m/s^2, deg, s "
                     "(default: taken as they are)");
  command.add_option("--binary", args.binary, "raw interleaved binary samples: i16|i32|f32|f64");
  command.add_option("--channels", args.channels, "number of interleaved channels (--binary)");
  command.add_flag("--big-endian", args.big_endian, "binary samples are big-endian");
  command.add_option("--skip-bytes", args.skip_bytes, "bytes of header to skip (--binary)");
  command.add_option("--gaps", args.gaps,
                     "time-stamp gaps (> 1.5 intervals) and backwards or duplicated stamps: "
                     "error (default; the message says where), split (analyse the contiguous "
                     "segments apart and combine them), fill (linear interpolation), report "
                     "(only count them and analyse the log as if contiguous)")
      ->capture_default_str();
  command.add_option("--nonfinite", args.nonfinite,
                     "NaN/Inf, or a field that is not a number in a data column: error (default; "
                     "the message names the file, line and column) or skip the row")
      ->capture_default_str();
  command.add_option("--topic", args.topic,
                     "ROS bag: the sensor_msgs/Imu topic to read (default: the bag's only Imu "
                     "topic; otherwise the error lists the topics)");
  command.add_option("--stamp", args.stamp,
                     "ROS bag: time column from the message's header stamp (default) or the "
                     "recorder's receive time: header|receive");
  command.add_option("--reorder-window", args.reorder_window,
                     "ROS bag: out-of-order stamps are sorted within this many messages "
                     "(default 10000); a message later than that is an error");
  command.add_option("--truncated", args.truncated,
                     "ROS bag whose recording was cut short (its recorder died: no index or "
                     "summary, the file ends inside a record): error (default; the message says "
                     "where and how many messages precede the cut) or use (analyse the complete "
                     "messages before the cut, with a note)");
  command.parse_complete_callback([&args, kind, rate] {
    apply_file_header(args, kind->count() > 0, rate->count() > 0);
  });
  std::vector<CLI::Option*> added;
  const std::vector<CLI::Option*> all = command.get_options();
  for (std::size_t i = options_before; i < all.size(); ++i) {
    if (all[i] != input) added.push_back(all[i]);
  }
  return added;
}

std::string given_option_names(const std::vector<CLI::Option*>& options) {
  std::string names;
  for (const CLI::Option* option : options) {
    if (option->count() > 0) names += (names.empty() ? "" : ", ") + option->get_name();
  }
  return names;
}

LogOptions log_options_from(const LogArguments& args) {
  LogOptions options;
  options.path = args.input;
  if (!args.columns.empty()) options.columns = split_list(args.columns, "--columns");
  options.time_column = args.time_column;
  if (!args.time_unit.empty()) options.time_unit = parse_time_unit(args.time_unit);
  options.gaps = parse_gap_policy(args.gaps);
  options.nonfinite = parse_nonfinite_policy(args.nonfinite);
  if (is_bag_path(args.input)) {
    if (!args.time_column.empty() || !args.time_unit.empty()) {
      throw Error(args.input + ": --time-column and --time-unit are for text logs; a ROS bag has "
                               "its own stamps (choose with --stamp header|receive)");
    }
    if (!args.binary.empty() || args.channels != 0 || args.big_endian || args.skip_bytes != 0) {
      throw Error(args.input + ": --binary, --channels, --big-endian and --skip-bytes are for raw "
                               "binary logs, not for a ROS bag");
    }
    options.topic = args.topic;
    if (!args.stamp.empty()) options.stamp = parse_bag_stamp(args.stamp);
    if (args.reorder_window) {
      if (*args.reorder_window < 0) throw Error("--reorder-window must be >= 0 messages");
      options.reorder_window = *args.reorder_window;
    }
    if (!args.truncated.empty()) options.truncated = parse_truncated_policy(args.truncated);
    return options;
  }
  if (!args.truncated.empty()) {
    throw Error(args.input + ": --truncated is for ROS bags (.bag, .mcap or a rosbag2 folder) "
                             "whose recording was cut short");
  }
  if (!args.topic.empty() || !args.stamp.empty() || args.reorder_window) {
    throw Error(args.input + ": --topic, --stamp and --reorder-window are for ROS bags (.bag, "
                             ".mcap, .db3 or a rosbag2 folder)");
  }
  if (!args.binary.empty()) {
    options.binary = parse_binary_format(args.binary);
    if (!(args.channels > 0)) throw Error("--binary needs --channels C (C >= 1)");
    if (!args.time_column.empty()) throw Error("--time-column is for text logs; use --rate with --binary");
    options.binary_channels = args.channels;
    options.big_endian = args.big_endian;
    if (args.skip_bytes < 0) throw Error("--skip-bytes must be >= 0");
    options.skip_bytes = args.skip_bytes;
  } else if (args.channels != 0 || args.big_endian || args.skip_bytes != 0) {
    throw Error("--channels, --big-endian and --skip-bytes are for --binary input");
  } else {
    options.find_time_column = true;  // a text log: the column named t, time or timestamp
  }
  return options;
}

namespace {

void note_topic_choice(const std::string& input, const TimingReport& timing) {
  if (timing.bag_topics.empty()) return;
  std::string list;
  for (const BagTopic& t : timing.bag_topics) {
    if (!list.empty()) list += ", ";
    list += t.name + " (" + t.type + ", " +
            (t.messages < 0 ? std::string("count not stated")
                            : std::to_string(t.messages) + (t.messages == 1 ? " message" : " messages")) +
            ")";
  }
  std::fprintf(stderr,
               "sigmatau: note: %s: reading %s, the only sensor_msgs/Imu topic (choose with "
               "--topic); its topics: %s\n",
               input.c_str(), timing.bag_topic.c_str(), list.c_str());
}

void note_reordering(const std::string& input, const TimingReport& timing,
                     std::int64_t reorder_window) {
  if (timing.reordered_samples <= 0) return;
  std::fprintf(stderr,
               "sigmatau: note: %s: %lld message%s arrived out of stamp order and %s put back in "
               "order (the latest %g s late; --reorder-window %lld messages)\n",
               input.c_str(), static_cast<long long>(timing.reordered_samples),
               timing.reordered_samples == 1 ? "" : "s",
               timing.reordered_samples == 1 ? "was" : "were", timing.max_reorder_s,
               static_cast<long long>(reorder_window));
}

/// A bag read under --truncated use whose recording was cut short: where, and what was used.
void note_truncation(const std::string& input, const TimingReport& timing) {
  if (timing.truncated_at_byte < 0) return;
  // A rosbag2 folder names the file of it that was cut.
  const std::string of_file =
      timing.truncated_file == input ? std::string() : " of " + timing.truncated_file;
  std::fprintf(stderr,
               "sigmatau: warning: %s: the recording was cut short at byte %lld%s (its recorder "
               "stopped without closing the file); the %lld complete message%s of %s before the "
               "cut %s used (--truncated use)\n",
               input.c_str(), static_cast<long long>(timing.truncated_at_byte), of_file.c_str(),
               static_cast<long long>(timing.samples),
               timing.samples == 1 ? "" : "s", timing.bag_topic.c_str(),
               timing.samples == 1 ? "is" : "are");
}

}  // namespace

namespace {

const char* time_unit_name(TimeUnit unit) {
  switch (unit) {
    case TimeUnit::s: return "s";
    case TimeUnit::ms: return "ms";
    case TimeUnit::us: return "us";
    case TimeUnit::ns: return "ns";
    case TimeUnit::min: return "min";
    case TimeUnit::h: return "h";
    case TimeUnit::d: return "d";
  }
  return "s";
}

}  // namespace

void note_header(const std::string& input, const TextHeader& header) {
  if (!header.time_column_found.empty()) {
    std::fprintf(stderr,
                 "sigmatau: note: %s: time column \"%s\" found by its name (stamps in %s%s; "
                 "--time-column names another, --time-unit sets the unit)\n",
                 input.c_str(), header.time_column_found.c_str(), time_unit_name(header.time_unit),
                 header.time_unit_from_name ? ", from its name" : "");
  }
  if (!header.time_column_not_increasing.empty()) {
    std::fprintf(stderr,
                 "sigmatau: note: %s: column \"%s\" is named like time stamps but its values do "
                 "not increase: it is read as a channel, not as the time column (--time-column "
                 "makes it one)\n",
                 input.c_str(), header.time_column_not_increasing.c_str());
  }
  for (const TextColumn& t : header.text_columns) {
    std::fprintf(stderr,
                 "sigmatau: note: %s: column \"%s\" holds text, not numbers (line %lld: \"%s\"), "
                 "and is not analysed (--columns chooses the columns)\n",
                 input.c_str(), t.name.c_str(), static_cast<long long>(t.line),
                 t.first_field.c_str());
  }
  if (!header.time_tag_column.empty()) {
    std::fprintf(stderr,
                 "sigmatau: note: %s: a Stable32 data file: column %s holds its time tags, which "
                 "are not analysed (as in Stable32; --columns or --time-column to use them)\n",
                 input.c_str(), header.time_tag_column.c_str());
  }
}

void apply_file_header(LogArguments& args, bool kind_given, bool rate_given) {
  if (args.input.empty() || args.input == "-" || !args.binary.empty() || is_bag_path(args.input)) {
    return;
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(args.input, ec)) return;
  TextHeader header;
  bool has_time = false;
  try {
    const LogReader reader(log_options_from(args));
    header = reader.timing().header;
    has_time = reader.has_time();
  } catch (const std::exception&) {
    return;  // the verb's own read says what is wrong
  }
  if (args.time_column.empty()) args.time_column_found = header.time_column_found;
  if (!header.declared_type.empty()) {
    const std::string kind = header.declared_type == "phase" ? "phase" : "rate";
    if (!kind_given) {
      args.kind = kind;
      std::fprintf(stderr,
                   "sigmatau: note: %s: its header declares %s data (Type:): read as --kind %s\n",
                   args.input.c_str(), header.declared_type.c_str(), kind.c_str());
    } else if (args.kind != kind) {
      std::fprintf(stderr,
                   "sigmatau: warning: %s: its header declares %s data (Type:), but --kind %s "
                   "is given\n",
                   args.input.c_str(), header.declared_type.c_str(), args.kind.c_str());
    }
  }
  if (header.declared_tau_s > 0 && !has_time) {
    const double rate_hz = 1.0 / header.declared_tau_s;
    if (!rate_given) {
      args.rate_hz = rate_hz;
      std::fprintf(stderr,
                   "sigmatau: note: %s: its header declares Tau %.10g s: read at --rate %.10g Hz\n",
                   args.input.c_str(), header.declared_tau_s, rate_hz);
    } else if (std::abs(*args.rate_hz / rate_hz - 1) > 1e-9) {
      std::fprintf(stderr,
                   "sigmatau: warning: %s: its header declares Tau %.10g s (%.10g Hz), but --rate "
                   "%.10g Hz is given\n",
                   args.input.c_str(), header.declared_tau_s, rate_hz, *args.rate_hz);
    }
  }
}

double quantity_option(const std::string& text, const Dimension& d, const char* option,
                       const char* bare_unit) {
  char* end = nullptr;
  [[maybe_unused]] const double bare = std::strtod(text.c_str(), &end);
  if (end != text.c_str() && *end == '\0') return parse_quantity_as(text + " " + bare_unit, d, option);
  return parse_quantity_as(text, d, option);
}

void note_reading(const LogArguments& args, const LogOptions& options, const TimingReport& timing) {
  note_header(args.input, timing.header);
  note_topic_choice(args.input, timing);
  note_reordering(args.input, timing, options.reorder_window);
  note_truncation(args.input, timing);
  for (const std::string& warning : timing.warnings) {
    std::fprintf(stderr, "sigmatau: warning: %s: %s\n", args.input.c_str(), warning.c_str());
  }
  if (timing.rows_skipped_nonfinite > 0) {
    std::fprintf(stderr,
                 "sigmatau: note: %s: %lld row%s with a non-finite or non-numeric value skipped "
                 "(--nonfinite skip)\n",
                 args.input.c_str(), static_cast<long long>(timing.rows_skipped_nonfinite),
                 timing.rows_skipped_nonfinite == 1 ? "" : "s");
  }
  if (options.gaps == GapPolicy::report && (timing.gap_count > 0 || timing.non_increasing > 0)) {
    // --gaps report: the gaps are in the JSON; the one-line summary goes here for every format.
    std::string text;
    if (timing.gap_count > 0) {
      char gaps[200];
      std::snprintf(gaps, sizeof gaps,
                    "%lld time stamp gap%s (> 1.5 intervals), the largest %.6g s before line %lld",
                    static_cast<long long>(timing.gap_count), timing.gap_count == 1 ? "" : "s",
                    timing.largest_gap_s, static_cast<long long>(timing.largest_gap_line));
      text = gaps;
    }
    if (timing.non_increasing > 0) {
      char back[200];
      std::snprintf(back, sizeof back, "%lld backwards or duplicated stamp%s (the first at line %lld)",
                    static_cast<long long>(timing.non_increasing),
                    timing.non_increasing == 1 ? "" : "s",
                    static_cast<long long>(timing.first_non_increasing_line));
      text += (text.empty() ? "" : "; ") + std::string(back);
    }
    std::fprintf(stderr,
                 "sigmatau: note: %s: --gaps report: %s; analysed as if contiguous\n",
                 args.input.c_str(), text.c_str());
  }
  if (timing.has_time && timing.rate_hz > 0) {
    // --rate wins over the stamps; say so when they disagree (more than 1 %).
    if (args.rate_hz && std::abs(*args.rate_hz / timing.rate_hz - 1) > 0.01) {
      std::fprintf(stderr,
                   "sigmatau: warning: %s: --rate %.6g Hz is used, but the time stamps measure "
                   "%.6g Hz\n",
                   args.input.c_str(), *args.rate_hz, timing.rate_hz);
    }
    // Stamps in ms or us read as seconds give a rate far below any IMU's.
    if (!args.rate_hz && (args.time_unit.empty() || args.time_unit == "s") &&
        !timing.header.time_unit_from_name && timing.rate_hz < 1) {
      std::fprintf(stderr,
                   "sigmatau: note: %s: the time stamps, read in seconds, measure %.6g Hz; if "
                   "they are in ms, us or ns, give --time-unit\n",
                   args.input.c_str(), timing.rate_hz);
    }
  }
}

Dimension sensor_unit_dimension(bool gyro, DataKind kind) {
  Dimension d = gyro ? dim::angular_rate : dim::acceleration;
  if (kind != DataKind::rate) d.time2 += 2;  // increments and phase: rad, m/s
  return d;
}

void set_input_unit(const LogArguments& args, LoadedChannels& loaded) {
  loaded.kind = parse_data_kind(args.kind);
  loaded.unit = args.unit;
  if (!args.unit.empty()) {
    const Unit unit = parse_unit(args.unit);
    // Increments and phase are amounts (deg, m/s, s), never rates: a rate unit with them is a
    // mix-up of --kind or --unit that would otherwise give deviations in deg/s^2 or m/s^3.
    if (loaded.kind != DataKind::rate &&
        (unit.dimension == dim::angular_rate || unit.dimension == dim::acceleration)) {
      throw Error("--unit " + args.unit + " is " +
                  (unit.dimension == dim::angular_rate ? "an angular rate" : "an acceleration") +
                  ", but --kind " + std::string(to_string(loaded.kind)) +
                  " says the values are " +
                  (loaded.kind == DataKind::increment ? "per-sample increments" : "an integrated phase") +
                  " (e.g. deg, rad, m/s); give --kind rate for rates, or the unit of the " +
                  (loaded.kind == DataKind::increment ? "increments" : "phase"));
    }
    // The reverse: an amount (deg, m/s) with --kind rate would give deviations that are off by
    // the sample rate and labelled as rates.
    if (loaded.kind == DataKind::rate && (unit.dimension == sensor_unit_dimension(true, DataKind::increment) ||
                                          unit.dimension == sensor_unit_dimension(false, DataKind::increment))) {
      throw Error("--unit " + args.unit + " is " +
                  (unit.dimension == sensor_unit_dimension(true, DataKind::increment)
                       ? "an angle"
                       : "a velocity") +
                  " (neither an angular rate nor an acceleration), but --kind rate says the "
                  "values are rates (e.g. deg/s, m/s^2); give --kind "
                  "increment for per-sample increments or --kind phase for an integrated angle "
                  "or velocity, or the unit of the rates");
    }
    loaded.to_si = unit.factor;
    loaded.dimension = unit.dimension;
  }
  // Per-channel units: the samples stay as read and each channel's results are scaled by its
  // own factor (deviations and densities scale with the unit; noise identification and EDF do
  // not depend on it).
  if (per_channel_units(args)) loaded.to_si = 1;
}

EdfModel edf_model_for(const LogArguments& args) {
  const DataKind kind = parse_data_kind(args.kind);
  // Units known from the data (a bag: rad/s and m/s^2) or named per sensor are IMU units.
  if (is_bag_path(args.input) || !args.gyro_unit.empty() || !args.accel_unit.empty()) {
    return default_edf_model(kind, sensor_unit_dimension(true, kind));
  }
  if (args.unit.empty()) return EdfModel::greenhall;  // unknown: as Stable32
  return default_edf_model(kind, parse_unit(args.unit).dimension);
}

std::string edf_model_name(const std::string& given, const LogArguments& args, bool stream) {
  if (!given.empty()) return given;
  if (stream) return "greenhall";
  return edf_model_for(args) == EdfModel::discrete ? "discrete" : "greenhall";
}

LoadedChannels load_channels(const LogArguments& args) {
  const LogOptions options = log_options_from(args);
  LoadedChannels loaded;
  set_input_unit(args, loaded);
  Progress progress;
  loaded.log = read_log(options, [&](std::int64_t done, std::int64_t total) {
    progress.update(done, total);
  });
  progress.finish();
  Log& log = loaded.log;
  note_reading(args, options, log.timing);
  if (options.gaps == GapPolicy::fill) fill_gaps(log);
  if (log.channels.empty() || log.channels[0].empty()) {
    throw ParseError(options.path == "-" ? "<stdin>" : options.path, 0, 0,
                     "no samples: the input holds no data rows");
  }
  loaded.rate_hz = resolve_rate_hz(args.rate_hz, loaded.log.timing, args.input);
  resolve_channel_units(args, loaded);
  if (loaded.to_si != 1.0) {
    for (auto& channel : loaded.log.channels) {
      for (double& v : channel) v *= loaded.to_si;
    }
  }
  return loaded;
}

namespace {
double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
/// Seconds between redraws of the progress line.
constexpr double kProgressPeriod = 0.25;
}  // namespace

Progress::Progress() : enabled_(stderr_is_tty()), start_s_(now_s()) {}
Progress::~Progress() { finish(); }

void Progress::update(std::int64_t bytes_read, std::int64_t total_bytes) {
  if (!enabled_) return;
  const double t = now_s();
  if (last_s_ >= 0 && t - last_s_ < kProgressPeriod) return;
  last_s_ = t;
  const double mb = static_cast<double>(bytes_read) / 1e6;
  const double rate = mb / std::max(t - start_s_, 1e-9);
  const std::string prefix = label_.empty() ? std::string("  ") : "  " + label_ + ": ";
  if (total_bytes > 0) {
    std::fprintf(stderr, "\r%sread %.1f of %.1f MB (%.0f%%), %.0f MB/s   ", prefix.c_str(), mb,
                 static_cast<double>(total_bytes) / 1e6,
                 100.0 * static_cast<double>(bytes_read) / static_cast<double>(total_bytes), rate);
  } else {
    std::fprintf(stderr, "\r%sread %.1f MB, %.0f MB/s   ", prefix.c_str(), mb, rate);
  }
  drawn_ = true;
}

void Progress::stage(const std::string& label) {
  if (!enabled_) return;
  if (drawn_) std::fputs("\r\033[K", stderr);  // back to the line start, erase it
  drawn_ = false;
  label_ = label;
  start_s_ = now_s();
  last_s_ = -1;
}

void Progress::finish() {
  if (drawn_) std::fputs("\r\033[K", stderr);  // back to the line start, erase it
  drawn_ = false;
}

}  // namespace sigmatau::cli
