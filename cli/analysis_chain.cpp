// The chain `analyze` and `demo` share: its options and running it into the output directory.
#include "analysis_chain.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <iostream>

#include <nlohmann/json.hpp>

#include "json_text.hpp"
#include "log_options.hpp"
#include "sigmatau/compliance.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/fit.hpp"
#include "sigmatau/output_file.hpp"
#include "sigmatau/report.hpp"
#include "sigmatau/resources.hpp"
#include "sigmatau/sampling_limits.hpp"

namespace sigmatau::cli {
namespace {

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
  options.fit_added_terms = !args.ieee_terms_only;
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
  for (double r : args.rate_out) checked_rate_hz(r, "--rate-out");
  options.filter_rates_hz = args.rate_out;
  if (!args.spec.empty()) options.spec = load_data_sheet(find_data_sheet(args.spec, resource_dir("specs")));
  options.convention = parse_density_convention(args.convention);
  options.bias_model = parse_bias_model(args.bias_model);
  options.threads = args.threads;
  options.edf_model = args.edf_model;
  if (args.dynamic) {
    if (args.dynamic_windows < 2) throw Error("--dynamic-windows must be >= 2");
    options.dynamic_windows = args.dynamic_windows;
  }
  options.created_utc = utc_now();
  return options;
}

/// The measured quantities the chain checks against a sheet (analysis_results.cpp: the joint
/// fit's N, B and K of every sensor channel).
constexpr MeasuredQuantity kChainQuantities[] = {MeasuredQuantity::white_noise,
                                                 MeasuredQuantity::bias_instability,
                                                 MeasuredQuantity::rate_random_walk};

/// Whether `sheet` gives a limit for any quantity the chain measures of `sensor`: whether a
/// detected term would get a verdict other than "not specified" (which depends on the sheet's
/// fields, not on the value; 1 is any positive value).
bool sheet_limits(const DataSheet& sheet, Sensor sensor, DensityConvention convention) {
  std::vector<MeasuredParameter> probe;
  for (const MeasuredQuantity q : kChainQuantities) probe.push_back({sensor, q, "x", 1, 1, 1});
  ComplianceOptions options;
  options.convention = convention;
  return items_checked(check_compliance(probe, sheet, options)) > 0;
}

/// "nothing to check: NAME (PART) prints no limit for ... of INPUT: the log has ...; the
/// sheet's noise limits are for ...", and what to do; `why` is said after the log's channels.
std::string nothing_to_check(const DataSheet& sheet, DensityConvention convention,
                             const std::string& input, const std::vector<SheetChannel>& channels,
                             const std::string& why) {
  std::string has;
  for (const Sensor sensor : {Sensor::gyro, Sensor::accel}) {
    std::string names;
    for (const auto& c : channels) {
      if (c.sensor == sensor) names += (names.empty() ? "" : ", ") + c.name;
    }
    if (names.empty()) continue;
    has += std::string(has.empty() ? "" : " and ") +
           (sensor == Sensor::gyro ? "gyro channels " : "accelerometer channels ") + names;
  }
  if (has.empty()) has = "no gyro or accelerometer channel (by name, or --gyro / --accel)";
  std::string limits;
  for (const Sensor sensor : {Sensor::gyro, Sensor::accel}) {
    if (!sheet_limits(sheet, sensor, convention)) continue;
    limits += std::string(limits.empty() ? "" : " and ") +
              (sensor == Sensor::gyro ? "the gyro" : "the accelerometer");
  }
  if (limits.empty()) limits = "no sensor";
  return "nothing to check: " + sheet.name + " (" + sheet.part + ") prints no limit on the noise "
         "terms measured in " + input + ": the log has " + has + why + "; the sheet's white "
         "noise, bias instability and rate random walk limits are for " + limits +
         " (use the sheet of this part, or a log of the sensors it specifies; nothing written)";
}

}  // namespace

void check_sheet_applies(const ChainArguments& args, const std::string& input,
                         const std::vector<SheetChannel>& channels) {
  if (args.spec.empty()) return;
  const DataSheet sheet = load_data_sheet(find_data_sheet(args.spec, resource_dir("specs")));
  const DensityConvention convention = parse_density_convention(args.convention);
  for (const auto& c : channels) {
    if (c.sensor && sheet_limits(sheet, *c.sensor, convention)) return;
  }
  throw Error(nothing_to_check(sheet, convention, input, channels, ""));
}

void add_chain_options(CLI::App& command, ChainArguments& args) {
  command.add_option("--stat", args.statistics,
                     "statistics, comma-separated (the first is plotted and fitted)")
      ->capture_default_str();
  command.add_option("--taus", args.taus, "octave | decade | many[:P] | all | seconds list")
      ->capture_default_str();
  command.add_option("--ci", args.ci,
                     "two-sided confidence level of every interval; 0.683 (one sigma) by default, "
                     "as the ADEV error bars Stable32 and SP 1065 print, so a pass is a one-sigma "
                     "statement: give 0.95 for a production gate (fit and calibrate default to it)")
      ->capture_default_str();
  command.add_option("--tau-min", args.fit_tau_min_s,
                     "the noise-term fit uses only taus >= this [s] (a sensor that filters its "
                     "output departs from the noise terms at the shortest taus)");
  command.add_option("--tau-max", args.fit_tau_max_s, "the noise-term fit uses only taus <= this [s]");
  command.add_flag("--ieee-terms-only", args.ieee_terms_only,
                   "the noise-term fit keeps to Q, N, B, K, R even where they do not describe the "
                   "curve (by default it then adds Gauss-Markov terms or a sinusoid and leaves out "
                   "the shortest taus a sensor's filter bends: docs/fit.md)");
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
  command.add_flag("--force", args.force,
                   "replace an earlier report in the output directory (never another directory, "
                   "nor one holding an input)");
  command.add_option("--threads", args.threads, "worker threads (0: one per core)")->capture_default_str();
  command.add_flag("--dynamic", args.dynamic,
                   "also the dynamic Allan deviation (OADEV over sliding windows) of each channel");
  command.add_option("--dynamic-windows", args.dynamic_windows, "number of half-overlapping windows")
      ->capture_default_str();
}

void check_output(const ChainArguments& args) {
  // Also refuses a device, pipe or socket (even with --force) and follows a link, early.
  check_output_directory(args.output, args.force);
}

void finish(const std::function<AnalysisOutput(const AnalysisOptions&)>& analyze,
            const ChainArguments& args, const std::map<std::string, std::string>& extra,
            std::int64_t flicker_taps, const std::vector<std::string>& notes) {
  const PlotFormat plot_format = parse_plot_format(args.plot_format);
  check_output(args);
  AnalysisOptions options = chain_options(args);
  options.flicker_taps = flicker_taps;
  const auto start = std::chrono::steady_clock::now();
  AnalysisOutput analysis = analyze(options);
  if (options.spec) {
    // A sheet that checked nothing gives no verdict: not a pass (as `check`), and no output.
    const nlohmann::json results = nlohmann::json::parse(analysis.results_json);
    const auto& items = results["compliance"]["items"];
    const bool checked = std::any_of(items.begin(), items.end(), [](const nlohmann::json& item) {
      return item.value("verdict", "") != std::string(to_string(Verdict::not_specified));
    });
    if (!checked) {
      std::vector<SheetChannel> channels;
      bool covered = false;
      for (const auto& c : results["channels"]) {
        SheetChannel channel{c.value("name", ""), std::nullopt};
        if (c.contains("sensor")) {
          channel.sensor = c["sensor"] == "gyro" ? Sensor::gyro : Sensor::accel;
          covered = covered || sheet_limits(*options.spec, *channel.sensor, options.convention);
        }
        channels.push_back(channel);
      }
      if (covered) {
        for (const auto& w : analysis.warnings) std::cerr << "sigmatau: warning: " << w << "\n";
      }
      const std::string input = results["input"].value("path", std::string("-"));
      throw Error(nothing_to_check(*options.spec, options.convention,
                                   input == "-" ? std::string("stdin") : input, channels,
                                   covered ? ", but no noise term of theirs was fitted (the "
                                             "warnings say why)"
                                           : ""));
    }
  }
  if (!notes.empty()) {
    // results.json is the record the report is drawn from: the notes go into its warnings.
    nlohmann::json results = nlohmann::json::parse(analysis.results_json);
    nlohmann::json warnings = notes;
    for (const auto& w : results["warnings"]) warnings.push_back(w);
    results["warnings"] = warnings;
    analysis.results_json = json_text(results, 1) + "\n";
    analysis.warnings.insert(analysis.warnings.begin(), notes.begin(), notes.end());
  }
  ReportOptions report_options;
  report_options.plot_format = plot_format;
  ReportFiles files = build_report(analysis.results_json, report_options, analysis.filter_files);
  files.files["results.json"] = analysis.results_json;
  for (const auto& [name, text] : analysis.filter_files) files.files[name] = text;
  for (const auto& [name, text] : extra) files.files[name] = text;
  write_output_directory(args.output, files, args.force);
  for (const auto& w : analysis.warnings) std::cerr << "sigmatau: warning: " << w << "\n";
  for (const auto& w : files.warnings) std::cerr << "sigmatau: warning: " << w << "\n";
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // The filter files are named only when there are some (a log without a fitted sensor has none).
  std::cout << files.files.at("summary.md") << "\nwrote " << args.output << "/ (" << files.files.size()
            << " files: report.html, results.json, summary.md, plots"
            << (analysis.filter_files.empty() ? "" : ", filter files") << ") in " << seconds << " s\n";
}

}  // namespace sigmatau::cli
