#pragma once
/// \file analysis.hpp
/// The whole chain for one log (what `sigmatau analyze` runs): warm-up trim -> Allan curves with
/// intervals -> Welch PSD and noise density -> noise-term fit -> filter covariances at the asked
/// rates -> data-sheet compliance, all written into one results.json (SI), which the report
/// stage (report.hpp) turns into plots, summary.md and report.html.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sigmatau/allan.hpp"
#include "sigmatau/compliance.hpp"
#include "sigmatau/convert.hpp"
#include "sigmatau/log_reader.hpp"
#include "sigmatau/noise_model.hpp"
#include "sigmatau/phase_series.hpp"
#include "sigmatau/psd.hpp"
#include "sigmatau/spec.hpp"
#include "sigmatau/taus.hpp"

namespace sigmatau {

/// Which sensor and axis a column holds, from its name: gx / gyro_x / wx / omega_x /
/// angular_velocity_x -> gyro; ax / acc_x / accel_x / linear_acceleration_x -> accel; the last
/// letter x / y / z is the axis. nullopt for anything else (temperature, time, counters).
struct ChannelRole {
  Sensor sensor = Sensor::gyro;
  int axis = 0;  ///< 0 x, 1 y, 2 z
};
std::optional<ChannelRole> classify_channel(std::string_view name);

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
  WelchOptions welch;
  int psd_bins_per_decade = 20;  ///< PSD stored log-binned (the raw PSD of a long log is huge)
  TrimMode trim = TrimMode::automatic;
  double trim_s = 0;             ///< for TrimMode::fixed [s]
  std::vector<double> filter_rates_hz;  ///< empty: the log's rate
  std::optional<DataSheet> spec;
  DensityConvention convention = DensityConvention::two_sided;
  BiasModel bias_model = BiasModel::random_walk;
  unsigned threads = 0;
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

/// CRC-32 (zlib) of a file as 8 hex digits, or "" when it cannot be read (stdin).
std::string file_crc32(const std::string& path);

}  // namespace sigmatau
