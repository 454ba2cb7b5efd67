#pragma once
// The part of `analyze` that `demo` shares: the chain's options (statistics, taus, interval,
// data sheet, filter rates, plots, output directory) and running the chain into the output
// directory (results.json, report, plots, filter files).
#include <CLI/CLI.hpp>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "sigmatau/analysis.hpp"

namespace sigmatau::cli {

/// The options of the chain itself, as given on the command line (not yet checked).
struct ChainArguments {
  std::string statistics = "oadev";
  std::string taus = "octave";
  double ci = 0.683;
  double fit_tau_min_s = 0;                                        ///< [s]
  bool ieee_terms_only = false;  ///< --ieee-terms-only
  double fit_tau_max_s = std::numeric_limits<double>::infinity();  ///< [s]
  std::string spec;
  std::vector<double> rate_out;  ///< [Hz]
  std::string trim = "auto";
  std::string plot_format = "svg";
  std::string convention = "two-sided";
  std::string bias_model = "rw";
  std::string output = "sigmatau-report";
  bool force = false;
  unsigned threads = 0;
  bool dynamic = false;
  int dynamic_windows = 8;
  EdfModel edf_model = EdfModel::greenhall;  ///< of the curves' intervals (set from the data)
};

/// Adds the chain's options (--stat, --taus, --ci, --spec, -o, ...) to `command`.
void add_chain_options(CLI::App& command, ChainArguments& args);

/// Refuses an existing output directory without --force, and one that could not be created
/// (an unwritable parent), before any reading.
void check_output(const ChainArguments& args);

/// One channel of the log as the data-sheet check sees it: its name and sensor (nullopt: neither,
/// so it has no noise terms to check).
struct SheetChannel {
  std::string name;
  std::optional<Sensor> sensor;
};

/// Refuses (Error, exit 2, as `check` does) a --spec sheet that prints no limit for the noise
/// terms the chain measures (white noise, bias instability, rate random walk) of any sensor
/// among `channels` of `input`: a run that checks nothing must not read as a pass. Called before
/// the log is read, when its channels are known from the header (the sheet is loaded from
/// args.spec; nothing without --spec).
void check_sheet_applies(const ChainArguments& args, const std::string& input,
                         const std::vector<SheetChannel>& channels);

/// Runs the chain (`analyze(options)`: in memory or bounded) and writes the output directory:
/// report files, results.json, the filter files and `extra` (name -> text, e.g. truth.json).
/// `notes` are warnings from before the chain (e.g. the demo's sensors left out): they come
/// first in results.json's "warnings" (so the report's Warnings section shows them) and on
/// stderr. `flicker_taps` as AnalysisOptions::flicker_taps (0 for a real log).
/// With --spec, a result in which the sheet checked nothing (no item but "not specified") is an
/// Error (exit 2) naming the sheet and the log's channels, and nothing is written.
void finish(const std::function<AnalysisOutput(const AnalysisOptions&)>& analyze,
            const ChainArguments& args, const std::map<std::string, std::string>& extra,
            std::int64_t flicker_taps = 0, const std::vector<std::string>& notes = {});

}  // namespace sigmatau::cli
