// `sigmatau analyze` (the whole chain into one output directory) and `sigmatau demo` (the same on
// a log simulated from a shipped data sheet).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <limits>
#include <cstdlib>
#include <functional>
#include <filesystem>
#include <iostream>

#include "log_options.hpp"
#include "memory_budget.hpp"
#include "sigmatau/analysis.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/fit.hpp"
#include "sigmatau/output_file.hpp"
#include "sigmatau/report.hpp"
#include "sigmatau/resources.hpp"
#include "sigmatau/simulate.hpp"
#include "verbs.hpp"

namespace sigmatau::cli {
namespace {

struct ChainArguments {
  std::string statistics = "oadev";
  std::string taus = "octave";
  double ci = 0.683;
  double fit_tau_min_s = 0;
  double fit_tau_max_s = std::numeric_limits<double>::infinity();
  std::string spec;
  std::vector<double> rate_out;
  std::string trim = "auto";
  std::string plot_format = "svg";
  std::string convention = "two-sided";
  std::string bias_model = "rw";
  std::string output = "sigmatau-report";
  bool force = false;
  unsigned threads = 0;
  bool dynamic = false;
  int dynamic_windows = 8;
};

struct AnalyzeArguments {
  LogArguments log;
  ChainArguments chain;
  std::string gyro;
  std::string accel;
  std::string gyro_unit;
  std::string accel_unit;
  std::string memory = "4GiB";
};

/// Bytes the in-memory analysis needs per value (sample x channel) at its peak: the value as
/// read (8, and 16 while a column's vector grows), the double-double phase (16) and the sweep
/// copy (8) of every channel's series, and one channel's rate copy for the PSD (8 / channels).
/// Measured: 5.5 GiB peak for a 10 GB ROS 1 bag of 1.6e8 values (36 bytes per value, the noise
/// fit's covariance included).
constexpr std::int64_t kAnalyzeBytesPerValue = 40;

struct DemoArguments {
  ChainArguments chain;
  std::string sheet = "safran_stim300";
  double hours = 3.0;
  double rate_hz = 100.0;
  std::uint64_t seed = 1;
  /// The simulated unit's noise terms as a fraction of the sheet's typical values: a unit a
  /// little better than typical, so the demo shows margins rather than a coin toss at 1.0.
  double scale = 0.8;
};

void add_chain_options(CLI::App& command, ChainArguments& args) {
  command.add_option("--stat", args.statistics,
                     "statistics, comma-separated (the first is plotted and fitted)")
      ->capture_default_str();
  command.add_option("--taus", args.taus, "octave | decade | many[:P] | all | seconds list")
      ->capture_default_str();
  command.add_option("--ci", args.ci, "confidence level of every interval")->capture_default_str();
  command.add_option("--tau-min", args.fit_tau_min_s,
                     "the noise-term fit uses only taus >= this [s] (a sensor that filters its "
                     "output departs from the noise terms at the shortest taus)");
  command.add_option("--tau-max", args.fit_tau_max_s, "the noise-term fit uses only taus <= this [s]");
  command.add_option("--spec", args.spec, "data sheet to check against (file or name in specs/)");
  command.add_option("--rate-out", args.rate_out,
                     "filter rates [Hz] for the covariances and exports (default: the log's rate)");
  command.add_option("--trim", args.trim,
                     "warm-up: auto (detect and trim), none, or a duration in seconds")
      ->capture_default_str();
  command.add_option("--plot-format", args.plot_format, "svg | png | pdf (report.html always inlines SVG)")
      ->capture_default_str();
  command.add_option("--density-convention", args.convention,
                     "how the data sheet's noise density is read: two-sided (N = ND) or one-sided")
      ->capture_default_str();
  command.add_option("--bias-model", args.bias_model, "filter bias model: rw | gm")->capture_default_str();
  // "report/" names the directory "report": with the slash kept, the directory was created first
  // and then could not be moved into place ("cannot rename: Invalid argument").
  command.add_option("-o,--output", args.output, "output directory (written atomically)")
      ->capture_default_str()
      ->transform(
          [](std::string path) {
            while (path.size() > 1 && path.back() == '/') path.pop_back();
            return path;
          },
          "");
  command.add_flag("--force", args.force, "replace an existing output directory");
  command.add_option("--threads", args.threads, "worker threads (0: one per core)")->capture_default_str();
  command.add_flag("--dynamic", args.dynamic,
                   "also the dynamic Allan deviation (OADEV over sliding windows) of each channel");
  command.add_option("--dynamic-windows", args.dynamic_windows, "number of half-overlapping windows")
      ->capture_default_str();
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

AnalysisOptions chain_options(const ChainArguments& args) {
  AnalysisOptions options;
  options.statistics.clear();
  for (const auto& s : split_list(args.statistics, "--stat")) options.statistics.push_back(parse_statistic(s));
  options.taus = parse_tau_spec(args.taus);
  if (!(args.ci > 0 && args.ci < 1)) throw Error("--ci must be between 0 and 1, got " + std::to_string(args.ci));
  options.confidence = args.ci;
  check_tau_range(args.fit_tau_min_s, args.fit_tau_max_s);  // before the log is read
  options.fit_tau_min_s = args.fit_tau_min_s;
  options.fit_tau_max_s = args.fit_tau_max_s;
  if (args.trim == "auto") {
    options.trim = TrimMode::automatic;
  } else if (args.trim == "none") {
    options.trim = TrimMode::none;
  } else {
    options.trim = TrimMode::fixed;
    options.trim_s = parse_quantity_as(args.trim.find_first_not_of("0123456789.eE+-") == std::string::npos
                                           ? args.trim + " s" : args.trim,
                                       dim::time, "--trim");
  }
  for (double r : args.rate_out) {
    if (!(r > 0)) throw Error("--rate-out must be > 0 Hz, got " + std::to_string(r));
  }
  options.filter_rates_hz = args.rate_out;
  if (!args.spec.empty()) options.spec = load_data_sheet(find_data_sheet(args.spec, resource_dir("specs")));
  options.convention = parse_density_convention(args.convention);
  options.bias_model = parse_bias_model(args.bias_model);
  options.threads = args.threads;
  if (args.dynamic) {
    if (args.dynamic_windows < 2) throw Error("--dynamic-windows must be >= 2");
    options.dynamic_windows = args.dynamic_windows;
  }
  options.created_utc = utc_now();
  return options;
}

/// Refuses an existing output directory without --force, and one that could not be created
/// (an unwritable parent), before any reading.
void check_output(const ChainArguments& args) {
  std::error_code ec;
  if (std::filesystem::exists(args.output, ec) && !args.force) {
    throw Error(args.output + " exists; use --force to replace it");
  }
  check_can_create_in(args.output);
}

/// Runs the chain (`analyze(options)`: in memory or bounded) and writes the output directory.
void finish(const std::function<AnalysisOutput(const AnalysisOptions&)>& analyze,
            const ChainArguments& args, const std::map<std::string, std::string>& extra,
            std::int64_t flicker_taps = 0) {
  const PlotFormat plot_format = parse_plot_format(args.plot_format);
  check_output(args);
  AnalysisOptions options = chain_options(args);
  options.flicker_taps = flicker_taps;
  const auto start = std::chrono::steady_clock::now();
  AnalysisOutput analysis = analyze(options);
  ReportOptions report_options;
  report_options.plot_format = plot_format;
  ReportFiles files = build_report(analysis.results_json, report_options);
  files.files["results.json"] = analysis.results_json;
  for (const auto& [name, text] : analysis.filter_files) files.files[name] = text;
  for (const auto& [name, text] : extra) files.files[name] = text;
  write_output_directory(args.output, files, args.force);
  for (const auto& w : analysis.warnings) std::cerr << "sigmatau: warning: " << w << "\n";
  for (const auto& w : files.warnings) std::cerr << "sigmatau: warning: " << w << "\n";
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << files.files.at("summary.md") << "\nwrote " << args.output << "/ (" << files.files.size()
            << " files: report.html, results.json, summary.md, plots, filter files) in "
            << seconds << " s\n";
}

/// The channels analyze works on, chosen from the log's channel names: explicit --gyro / --accel
/// columns (only those), else every column with its role recognised by name; each with the
/// factor of its sensor's unit (--gyro-unit / --accel-unit, else --unit).
std::vector<BoundedChannel> choose_channels(const std::vector<std::string>& names,
                                            const AnalyzeArguments& args, DataKind kind) {
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
  const std::string gyro_unit = !args.gyro_unit.empty() ? args.gyro_unit : args.log.unit;
  const std::string accel_unit = !args.accel_unit.empty() ? args.accel_unit : args.log.unit;
  // A sensor unit is checked even when no column of that sensor is found: a wrong --accel-unit
  // on a gyro-only log used to pass unnoticed.
  const auto expected_dimension = [&](bool gyro) { return sensor_unit_dimension(gyro, kind); };
  if (!args.gyro_unit.empty()) parse_unit_as(args.gyro_unit, expected_dimension(true), "--gyro-unit");
  if (!args.accel_unit.empty()) {
    parse_unit_as(args.accel_unit, expected_dimension(false), "--accel-unit");
  }
  // --unit of one sensor's dimension beside that sensor's own option: one of the two was
  // silently ignored (--unit deg/s --gyro-unit rad/s read the gyros as rad/s).
  std::optional<Unit> common;
  try {
    if (!args.log.unit.empty()) common = parse_unit(args.log.unit);
  } catch (const UnitError&) {
    // a bad --unit is reported, named, where the columns take it
  }
  if (common) {
    for (const bool gyro : {true, false}) {
      const std::string& own = gyro ? args.gyro_unit : args.accel_unit;
      if (own.empty() || common->dimension != expected_dimension(gyro)) continue;
      if (parse_unit(own).factor == common->factor) continue;
      throw Error("--unit " + args.log.unit + " and " + (gyro ? "--gyro-unit " : "--accel-unit ") + own +
                  " both name the unit of the " + (gyro ? "gyro" : "accelerometer") +
                  " columns and disagree: give one of them");
    }
  }
  std::vector<BoundedChannel> chosen;
  for (std::size_t c = 0; c < names.size(); ++c) {
    BoundedChannel channel;
    channel.column = c;
    channel.name = names[c];
    if (forced.count(channel.name)) {
      channel.role = forced[channel.name];
    } else if (forced.empty()) {
      channel.role = classify_channel(channel.name);
    }
    if (!forced.empty() && !forced.count(channel.name)) continue;  // only the named columns
    if (channel.role) channel.input_unit = channel.role->sensor == Sensor::gyro ? gyro_unit : accel_unit;
    if (!channel.input_unit.empty()) {
      const bool gyro = channel.role->sensor == Sensor::gyro;
      // The option the unit came from: --gyro-unit / --accel-unit, or --unit for both.
      const bool own = !(gyro ? args.gyro_unit : args.accel_unit).empty();
      const std::string field = own ? (gyro ? "--gyro-unit" : "--accel-unit")
                                    : "--unit (applied to the " + std::string(gyro ? "gyro" : "accelerometer") +
                                          " column " + channel.name + "; give --gyro-unit and --accel-unit apart)";
      channel.to_si = parse_unit_as(channel.input_unit, expected_dimension(gyro), field).factor;
    }
    chosen.push_back(std::move(channel));
  }
  return chosen;
}

/// The provenance fields of the input file (size and CRC-32; none for stdin).
AnalysisInput input_provenance(const std::string& path, DataKind kind) {
  AnalysisInput input;
  input.path = path;
  input.kind = kind;
  if (input.path != "-") {
    std::error_code ec;
    input.bytes = static_cast<std::int64_t>(std::filesystem::file_size(input.path, ec));
    if (ec) input.bytes = -1;
    input.crc32 = file_crc32(input.path);
  }
  return input;
}

/// Whether the in-memory analysis of this input would need more than --memory: then it runs in
/// bounded memory. Never for stdin (a pipe cannot be re-read, and its size is unknown) nor for
/// --gaps split / fill (they need the whole log in memory).
bool needs_bounded(const AnalyzeArguments& args) {
  const std::int64_t memory = parse_bytes(args.memory);
  if (args.log.gaps == "split" || args.log.gaps == "fill") return false;
  const std::int64_t values = estimated_values(args.log);
  return values >= 0 && values > memory / kAnalyzeBytesPerValue;
}

void run_analyze_bounded(const AnalyzeArguments& args) {
  std::cerr << "sigmatau: " << args.log.input << " needs more than --memory " << args.memory
            << " in memory; analysing it in bounded memory (its values and phase in temporary "
               "files in "
            << (std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") << ")\n";
  LogArguments log_args = args.log;
  log_args.unit.clear();  // per-sensor units are applied by choose_channels
  const LogOptions options = log_options_from(log_args);
  LoadedChannels kind_only;
  set_input_unit(log_args, kind_only);
  const DataKind kind = kind_only.kind;
  check_output(args.chain);
  Progress progress;
  BoundedAnalysisSource source;
  source.log = options;
  source.channels = [&](const std::vector<std::string>& names) { return choose_channels(names, args, kind); };
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
  if (needs_bounded(args)) {
    run_analyze_bounded(args);
    return;
  }
  LogArguments log_args = args.log;
  log_args.unit.clear();  // per-sensor units are applied below
  LoadedChannels loaded = load_channels(log_args);
  AnalysisInput input = input_provenance(loaded.log.path, loaded.kind);
  input.rate_hz = loaded.rate_hz;
  if (loaded.log.timing.has_time) input.timing = loaded.log.timing;
  for (const BoundedChannel& chosen : choose_channels(loaded.log.channel_names, args, loaded.kind)) {
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

void run_demo(const DemoArguments& args) {
  const DataSheet sheet = load_data_sheet(find_data_sheet(args.sheet, resource_dir("specs")));
  if (!(args.hours > 0) || !(args.rate_hz > 0) || !(args.scale > 0)) {
    throw Error("--hours, --rate and --scale must be > 0");
  }
  check_output(args.chain);  // before the simulation
  SimulationConfig config;
  config.rate_hz = args.rate_hz;
  config.samples = static_cast<std::int64_t>(std::llround(args.hours * 3600 * args.rate_hz));
  config.seed = args.seed;
  StaticPose pose;
  pose.latitude_rad = 45.0 * 3.14159265358979323846 / 180.0;
  config.truth = static_truth(pose);
  config.threads = args.chain.threads == 0 ? 2 : args.chain.threads;
  for (Sensor sensor : {Sensor::gyro, Sensor::accel}) {
    if (!sheet.sensor(sensor)) continue;
    const TriadNoise triad = triad_from_data_sheet(sheet, sensor, parse_density_convention(args.chain.convention));
    ErrorModel model;
    model.noise = triad.axes;
    for (auto& axis : model.noise) {
      for (auto* term : {&axis.quantization, &axis.white, &axis.bias_instability,
                         &axis.rate_random_walk, &axis.rate_ramp}) {
        if (*term) **term *= args.scale;
      }
    }
    (sensor == Sensor::gyro ? config.gyro : config.accel) = model;
  }
  Simulator simulator(config);
  AnalysisInput input;
  char description[256];
  std::snprintf(description, sizeof description,
                "demo: %s %s simulated from specs/%s.yaml with %g x its typical noise terms "
                "(%g h at %g Hz, seed %llu)",
                sheet.manufacturer.c_str(), sheet.part.c_str(), sheet.name.c_str(), args.scale,
                args.hours, args.rate_hz, static_cast<unsigned long long>(args.seed));
  input.path = description;
  input.rate_hz = args.rate_hz;
  const auto names = simulator.channel_names();
  for (const auto& name : names) {
    AnalysisChannel channel;
    channel.name = name;
    channel.role = classify_channel(name);
    channel.values.reserve(static_cast<std::size_t>(config.samples));
    input.channels.push_back(std::move(channel));
    input.input_units.push_back("");
  }
  std::vector<double> block(static_cast<std::size_t>(65536) * names.size());
  while (true) {
    const std::int64_t rows = simulator.next(block, 65536);
    if (rows == 0) break;
    for (std::int64_t r = 0; r < rows; ++r) {
      for (std::size_t c = 0; c < names.size(); ++c) input.channels[c].values.push_back(block[r * names.size() + c]);
    }
  }
  ChainArguments chain = args.chain;
  if (chain.spec.empty()) chain.spec = args.sheet;
  if (chain.trim == "auto") chain.trim = "none";  // a simulated log has no warm-up
  finish([&](const AnalysisOptions& options) { return run_analysis(std::move(input), options); },
         chain, {{"truth.json", simulation_sidecar_json(config)}}, flicker_taps(config));
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
  command->add_option("--gyro-unit", args->gyro_unit, "unit of the gyro columns (default rad/s)");
  command->add_option("--accel-unit", args->accel_unit, "unit of the accelerometer columns (default m/s^2)");
  command->add_option("--memory", args->memory,
                      "memory for the analysis, e.g. 1GiB: a larger file is analysed in bounded "
                      "memory, with its values and phase in temporary files (TMPDIR) and the same "
                      "results; stdin and --gaps split/fill are always read into memory")
      ->capture_default_str();
  add_chain_options(*command, args->chain);
  command->callback([args] { run_analyze(*args); });
}

void add_demo_command(CLI::App& app) {
  auto args = std::make_shared<DemoArguments>();
  args->chain.output = "demo-output";
  CLI::App* command = app.add_subcommand(
      "demo", "Simulate a log from a shipped data sheet and run `analyze` on it (the built-in demo)");
  command->add_option("--sheet", args->sheet, "data sheet to simulate (name in specs/)")->capture_default_str();
  command->add_option("--hours", args->hours, "simulated duration [h]")->capture_default_str();
  command->add_option("--rate", args->rate_hz, "simulated sample rate [Hz]")->capture_default_str();
  command->add_option("--seed", args->seed, "random seed")->capture_default_str();
  command->add_option("--scale", args->scale,
                      "simulated noise terms as a fraction of the sheet's typical values")
      ->capture_default_str();
  add_chain_options(*command, args->chain);
  command->callback([args] { run_demo(*args); });
}

}  // namespace sigmatau::cli
