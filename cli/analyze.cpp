// `sigmatau analyze`: the whole chain on one log into one output directory (the chain's options
// and output are shared with `demo`: analysis_chain.hpp).
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <future>
#include <iostream>
#include <optional>
#include <string>
#include <system_error>

#include "analysis_chain.hpp"
#include "channel_units.hpp"
#include "log_options.hpp"
#include "memory_budget.hpp"
#include "sigmatau/analysis.hpp"
#include "sigmatau/error.hpp"
#include "verbs.hpp"

namespace sigmatau::cli {
namespace {

struct AnalyzeArguments {
  LogArguments log;
  ChainArguments chain;
  std::string gyro;
  std::string accel;
  std::string memory = "4GiB";
};

/// Bytes the in-memory analysis needs per value (sample x channel) at its peak: the value as
/// read (8, and 16 while a column's vector grows), the double-double phase (16) and the sweep
/// copy (8) of every channel's series, and one channel's rate copy for the PSD (8 / channels).
/// Measured: 5.5 GiB peak for a 10 GB ROS 1 bag of 1.6e8 values (36 bytes per value; measured
/// while the fit's covariance still took FFT memory, so an upper bound).
constexpr std::int64_t kAnalyzeBytesPerValue = 40;

/// The channels analyze works on, chosen from the log's channel names: explicit --gyro / --accel
/// columns (only those), else every column with its role recognised by name; each with its unit
/// (channel_units_of: --unit, --gyro-unit / --accel-unit by the sensor, a ROS bag's own) and the
/// factor that takes its values, read as they are, to SI. `notes` as channel_units_of.
std::vector<BoundedChannel> choose_channels(const std::vector<std::string>& names,
                                            const AnalyzeArguments& args, bool notes) {
  std::map<std::string, ChannelRole> forced;
  auto force_roles = [&](const std::string& list, Sensor sensor, const char* option) {
    if (list.empty()) return;
    const auto columns = split_list(list, option);
    if (columns.size() != 3) throw Error(std::string(option) + " needs three columns x,y,z");
    for (int axis = 0; axis < 3; ++axis) {
      // A name that is not a channel used to be skipped silently (the sensor then had two axes
      // or none, and the run still exited 0).
      if (std::find(names.begin(), names.end(), columns[axis]) == names.end()) {
        std::string available;
        for (const auto& name : names) available += (available.empty() ? "" : ", ") + name;
        throw Error(std::string(option) + ": no channel \"" + columns[axis] + "\" in " +
                    args.log.input + " (channels: " + available + ")");
      }
      forced[columns[axis]] = {sensor, axis};
    }
  };
  force_roles(args.gyro, Sensor::gyro, "--gyro");
  force_roles(args.accel, Sensor::accel, "--accel");
  std::vector<BoundedChannel> chosen;
  std::vector<std::string> chosen_names;
  std::vector<ChannelSensor> sensors;
  std::string left_out;  // channels --gyro / --accel do not name: said, never dropped silently
  for (std::size_t c = 0; c < names.size(); ++c) {
    BoundedChannel channel;
    channel.column = c;
    channel.name = names[c];
    ChannelSensor sensor;
    if (const auto it = forced.find(channel.name); it != forced.end()) {
      channel.role = it->second;
      sensor = {it->second, it->second.sensor == Sensor::gyro ? "by --gyro" : "by --accel"};
    } else if (!forced.empty()) {
      left_out += (left_out.empty() ? "" : ", ") + names[c];
      continue;  // only the named columns
    } else {
      channel.role = classify_channel(channel.name);
      sensor = {channel.role};
    }
    chosen_names.push_back(channel.name);
    sensors.push_back(std::move(sensor));
    chosen.push_back(std::move(channel));
  }
  if (notes && !left_out.empty()) {
    std::cerr << "sigmatau: note: " << args.log.input << ": " << left_out
              << " not analysed (--gyro / --accel name the channels; --columns chooses what is "
                 "read)\n";
  }
  const std::vector<ChannelUnit> units = channel_units_of(args.log, chosen_names, sensors, notes);
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    chosen[i].input_unit = units[i].unit;
    chosen[i].to_si = units[i].to_si;  // the values are read as they are (log_as_read)
  }
  return chosen;
}

/// The log arguments the values are read with: without any unit (choose_channels gives each
/// channel its factor to SI, so the values are read as they are).
LogArguments log_as_read(const LogArguments& args) {
  LogArguments as_read = args;
  as_read.unit.clear();
  as_read.gyro_unit.clear();
  as_read.accel_unit.clear();
  return as_read;
}

/// What is checked before a long read, from the header's names (or a bag's channels): the units
/// (as adev and psd do: --unit against --kind, and the channels' units when a unit option is
/// given), and that the --spec sheet has a limit for a sensor of the log (check_sheet_applies).
void check_before_reading(const AnalyzeArguments& args) {
  LoadedChannels unit_only;
  set_input_unit(args.log, unit_only);
  const auto names = early_channel_names(args.log, !args.chain.spec.empty());
  if (!names) return;
  std::vector<SheetChannel> channels;
  for (const BoundedChannel& c : choose_channels(*names, args, false)) {
    channels.push_back({c.name, c.role ? std::optional<Sensor>(c.role->sensor) : std::nullopt});
  }
  check_sheet_applies(args.chain, args.log.input, channels);
}

/// The provenance fields of the input file (size and CRC-32; none for stdin); `crc32` when it
/// was computed already.
AnalysisInput input_provenance(const std::string& path, DataKind kind,
                               std::optional<std::string> crc32 = std::nullopt) {
  AnalysisInput input;
  input.path = path;
  input.kind = kind;
  if (input.path != "-") {
    std::error_code ec;
    input.bytes = static_cast<std::int64_t>(std::filesystem::file_size(input.path, ec));
    if (ec) input.bytes = -1;
    input.crc32 = crc32 ? std::move(*crc32) : file_crc32(input.path);
  }
  return input;
}

/// Whether the in-memory analysis of this input would need more than --memory: then it runs in
/// bounded memory. Never for stdin (a pipe cannot be re-read, and its size is unknown) nor for
/// --gaps split / fill (they need the whole log in memory).
bool needs_bounded(const AnalyzeArguments& args) {
  const std::int64_t memory = parse_bytes(args.memory);
  if (args.log.gaps == "split" || args.log.gaps == "fill") return false;
  const std::int64_t values = estimated_values(args.log, memory / kAnalyzeBytesPerValue);
  return values >= 0 && values > memory / kAnalyzeBytesPerValue;
}

void run_analyze_bounded(const AnalyzeArguments& args) {
  std::cerr << "sigmatau: " << args.log.input << " needs more than --memory " << args.memory
            << " in memory; analysing it in bounded memory (its values and phase in temporary "
               "files in "
            << (std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") << ")\n";
  const LogArguments log_args = log_as_read(args.log);
  const LogOptions options = log_options_from(log_args);
  const DataKind kind = parse_data_kind(log_args.kind);
  check_output(args.chain);
  Progress progress;
  BoundedAnalysisSource source;
  source.log = options;
  source.channels = [&](const std::vector<std::string>& names) { return choose_channels(names, args, true); };
  source.rate_hz = [&](const TimingReport& timing) {
    return resolve_rate_hz(args.log.rate_hz, timing, args.log.input);
  };
  source.progress = [&](std::int64_t done, std::int64_t total) { progress.update(done, total); };
  source.on_read = [&](const TimingReport& timing) {
    progress.finish();
    note_reading(log_args, options, timing);
  };
  finish([&](const AnalysisOptions& analysis_options) {
           return run_analysis_bounded(source, input_provenance(args.log.input, kind), analysis_options);
         },
         args.chain, {});
}

void run_analyze(const AnalyzeArguments& args) {
  // Before reading: the in-memory path used to read the whole log before this check.
  check_output(args.chain);
  check_before_reading(args);
  if (needs_bounded(args)) {
    run_analyze_bounded(args);
    return;
  }
  // The file's CRC-32 (a second pass over it) on another thread while it is read.
  std::future<std::string> crc32;
  if (args.log.input != "-") {
    try {
      crc32 = std::async(std::launch::async, [path = args.log.input] { return file_crc32(path); });
    } catch (const std::system_error&) {
      // no thread to be had: computed after the read, as before
    }
  }
  LoadedChannels loaded = load_channels(log_as_read(args.log));
  const bool same_file = crc32.valid() && loaded.log.path == args.log.input;
  AnalysisInput input = input_provenance(
      loaded.log.path, loaded.kind,
      same_file ? std::optional<std::string>(crc32.get()) : std::nullopt);
  input.rate_hz = loaded.rate_hz;
  if (loaded.log.timing.has_time) input.timing = loaded.log.timing;
  for (const BoundedChannel& chosen : choose_channels(loaded.log.channel_names, args, true)) {
    AnalysisChannel channel;
    channel.name = chosen.name;
    channel.role = chosen.role;
    channel.values = std::move(loaded.log.channels[chosen.column]);
    if (chosen.to_si != 1) {
      for (double& v : channel.values) v *= chosen.to_si;
    }
    input.input_units.push_back(chosen.input_unit);
    input.channels.push_back(std::move(channel));
  }
  finish([&](const AnalysisOptions& options) { return run_analysis(std::move(input), options); },
         args.chain, {});
}

}  // namespace

void add_analyze_command(CLI::App& app) {
  auto args = std::make_shared<AnalyzeArguments>();
  CLI::App* command = app.add_subcommand(
      "analyze", "The whole chain on one log: Allan curves, PSD, noise terms, filter covariances, "
                 "data-sheet check, plots and report.html in one directory");
  add_log_options(*command, args->log);
  command->add_option("--gyro", args->gyro, "gyro columns x,y,z (default: recognised by name)");
  command->add_option("--accel", args->accel, "accelerometer columns x,y,z (default: by name)");
  add_sensor_unit_options(*command, args->log);
  command->add_option("--memory", args->memory,
                      "memory for the analysis, e.g. 1GiB: a larger file is analysed in bounded "
                      "memory, with its values and phase in temporary files (TMPDIR) and the same "
                      "results; stdin and --gaps split/fill are always read into memory")
      ->capture_default_str();
  add_chain_options(*command, args->chain);
  command->callback([args] {
    args->chain.edf_model = edf_model_for(args->log);  // discrete for IMU data
    run_analyze(*args);
  });
}

}  // namespace sigmatau::cli
