#pragma once
/// \file analysis.hpp
/// The whole chain for one log (what `sigmatau analyze` runs): warm-up trim -> Allan curves with
/// intervals -> Welch PSD and noise density -> noise-term fit -> filter covariances at the asked
/// rates -> data-sheet compliance, all written into one results.json (SI), which the report
/// stage (report.hpp) turns into plots, summary.md and report.html.

#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sigmatau/allan.hpp"
#include "sigmatau/channel_names.hpp"
#include "sigmatau/compliance.hpp"
#include "sigmatau/confidence.hpp"
#include "sigmatau/convert.hpp"
#include "sigmatau/log_reader.hpp"
#include "sigmatau/noise_model.hpp"
#include "sigmatau/phase_series.hpp"
#include "sigmatau/psd.hpp"
#include "sigmatau/spec.hpp"
#include "sigmatau/taus.hpp"

namespace sigmatau {

/// One channel in SI (rad/s or m/s^2 for rate input).
struct AnalysisChannel {
  std::string name;
  std::optional<ChannelRole> role;  ///< nullopt: analysed, but not fitted against a sensor model
  std::vector<double> values;
};

struct AnalysisInput {
  std::string path;
  std::int64_t bytes = -1;     ///< file size, -1 when unknown (stdin)
  std::string crc32;           ///< hex CRC-32 of the file, empty when unknown
  double rate_hz = 0;
  DataKind kind = DataKind::rate;
  std::optional<TimingReport> timing;
  std::vector<std::string> input_units;  ///< per channel, as given ("deg/s"; "" = SI)
  std::vector<AnalysisChannel> channels;
};

enum class TrimMode { automatic, none, fixed };

struct AnalysisOptions {
  std::vector<Statistic> statistics{Statistic::oadev};  ///< the first one is plotted and fitted
  TauSpec taus;
  double confidence = 0.683;
  /// Taus the noise-term fit uses (FitOptions::tau_min_s / tau_max_s); the curves keep all.
  double fit_tau_min_s = 0;
  double fit_tau_max_s = std::numeric_limits<double>::infinity();
  /// FitOptions::added_terms: the joint fit may add Gauss-Markov terms and a sinusoid and leave
  /// out filter-bent taus when the IEEE terms do not describe a curve.
  bool fit_added_terms = true;
  WelchOptions welch;
  int psd_bins_per_decade = 20;  ///< PSD stored log-binned (the raw PSD of a long log is huge)
  TrimMode trim = TrimMode::automatic;
  double trim_s = 0;             ///< for TrimMode::fixed [s]
  std::vector<double> filter_rates_hz;  ///< empty: the log's rate
  std::optional<DataSheet> spec;
  DensityConvention convention = DensityConvention::two_sided;
  BiasModel bias_model = BiasModel::random_walk;
  unsigned threads = 0;
  /// EDF model of the curves' intervals (the CLI takes EdfModel::discrete for IMU data).
  EdfModel edf_model = EdfModel::greenhall;
  /// Dynamic Allan deviation: OADEV over this many half-overlapping windows of the (trimmed)
  /// log, so a change of the noise during the run shows; 0: off.
  int dynamic_windows = 0;
  /// Taps of the Kasdin flicker filter when the log is a sigmatau simulation (the demo), so
  /// the fit models the simulated flicker exactly; 0 for real sensors.
  std::int64_t flicker_taps = 0;
  std::string created_utc;  ///< recorded as is
};

/// What the chain produces: results.json text and the filter files (name -> text, e.g.
/// "kalibr_200Hz.yaml"), which carry the same numbers as results.json's "filter" section.
struct AnalysisOutput {
  std::string results_json;
  std::map<std::string, std::string> filter_files;
  std::vector<std::string> warnings;
};

/// Runs the chain. Throws Error on unusable input (no channel, too short for one tau, trim
/// longer than the log).
AnalysisOutput run_analysis(AnalysisInput input, const AnalysisOptions& options);

/// One channel of a log for run_analysis_bounded: which column, and what it is.
struct BoundedChannel {
  std::size_t column = 0;  ///< index into the log's channel names (LogReader::channel_names)
  std::string name;
  std::optional<ChannelRole> role;  ///< as AnalysisChannel::role
  double to_si = 1;        ///< every value is multiplied by this (1: taken as read)
  std::string input_unit;  ///< as AnalysisInput::input_units ("" = SI)
};

/// Where run_analysis_bounded reads its log and how it reports.
struct BoundedAnalysisSource {
  /// The log: a file or a ROS bag, not stdin (its values are read once, into temporary files).
  /// gaps must be report or error (split and fill need the whole log in memory).
  LogOptions log;
  /// The channels to analyse, chosen from the log's channel names (called once, before reading).
  std::function<std::vector<BoundedChannel>(const std::vector<std::string>&)> channels;
  /// The sample rate [Hz] from the timing of the whole log (may throw, e.g. resolve_rate_hz).
  std::function<double(const TimingReport&)> rate_hz;
  /// Called with (bytes read, total bytes or -1) after each block of the read; may be empty.
  std::function<void(std::int64_t, std::int64_t)> progress;
  /// Called once with the timing report when the log has been read; may be empty.
  std::function<void(const TimingReport&)> on_read;
  /// Where the values and the phase go: temporary files in storage.directory ($TMPDIR, /tmp),
  /// at most about storage.resident_bytes of them mapped at once.
  PhaseStorage storage = spilled_storage();
};

/// run_analysis on a log that need not fit in memory, with the same results.json and filter
/// files, bit for bit. The log is read once: data checks and sample count on the way, every
/// selected channel's values (in SI) into a temporary file (8 bytes per value); the warm-up
/// blocks, the phase of each curve (PhaseSeriesBuilder into spilled storage, --threads channels
/// at a time: 32 bytes per sample each on disk), the Welch PSD and the dynamic windows then
/// stream from those files. Resident memory of these stages: the reader's buffers +
/// storage.resident_bytes + one Welch accumulator per channel of the group (<= ~40 MiB each at
/// the 2^20-sample segment cap), whatever the length. The noise-term fit (fit.hpp) that follows
/// works on the curves alone: its exact OAVAR covariance takes O(1) memory per pair of averaging
/// factors, O(taus^2) in all, independent of the log's length.
/// `input` carries path, bytes, crc32 and kind (channels, rate and timing are filled in here).
/// Throws like LogReader and run_analysis, and Error for --gaps split/fill with more than one
/// segment, or when a temporary file cannot be written.
AnalysisOutput run_analysis_bounded(const BoundedAnalysisSource& source, AnalysisInput input,
                                    const AnalysisOptions& options);

/// CRC-32 (zlib) of a file as 8 hex digits, or "" when it cannot be read (stdin).
std::string file_crc32(const std::string& path);

}  // namespace sigmatau
