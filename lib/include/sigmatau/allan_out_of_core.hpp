#pragma once
/// \file allan_out_of_core.hpp
/// Exact Allan-family curves of logs larger than memory ("out of core"), with the same numbers
/// as the in-memory path (compute_allan_curves on PhaseSeries::from_samples), bit for bit.
///
/// How: the log (a seekable file) is read twice per group of channels, once to count the
/// samples and take their mean, once to integrate them (PhaseSeriesBuilder); the double-double
/// phase, the sweep copy and the long noise-identification series live in unlinked temporary
/// files that are memory-mapped (PhaseStorage::spill). The kernel's page cache holds what fits
/// in RAM; the process maps at most about PhaseStorage::resident_bytes of those files at once.
///
/// Memory bound (resident set): the reader's buffers (~4 MiB + one block of 65536 rows) +
/// PhaseStorage::resident_bytes (default 256 MiB) + a few tens of MiB of overshoot between two
/// checks of the page watchdog + O(taus) per curve, whatever the length of the log.
/// Disk: 32 bytes per sample for each channel of the group being computed (`threads` channels
/// at a time): 16 for the phase, 8 for the sweep copy, 8 for the noise-identification series.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "sigmatau/allan_curve.hpp"
#include "sigmatau/log_reader.hpp"
#include "sigmatau/phase_series.hpp"

namespace sigmatau {

/// compute_allan_curve with noise identification that keeps long series in `storage` (spilled
/// when storage.spill) instead of anonymous memory. Identical results.
AllanCurve compute_allan_curve_bounded(const PhaseSeries& series, Statistic statistic,
                                       const TauSpec& taus, double confidence_level,
                                       const PhaseStorage& storage,
                                       EdfModel edf_model = EdfModel::greenhall);

/// identify_noise with the averaged (or decimated) series kept in `storage` when it is longer
/// than a few MiB. Identical results.
NoiseIdentification identify_noise_bounded(const PhaseSeries& series, Statistic statistic,
                                           std::int64_t m, const PhaseStorage& storage);

struct OutOfCoreSettings {
  PhaseStorage storage = spilled_storage();  ///< where the phase goes (spilled for out of core)
  unsigned threads = 0;  ///< channels computed at a time (0: one per core)
  EdfModel edf_model = EdfModel::greenhall;  ///< EDF of the intervals (see equivalent_dof)
  /// Called once per read pass with (bytes read, total bytes or -1), after each block.
  std::function<void(std::int64_t, std::int64_t)> progress;
  /// Called before each read pass with what it is for: "pass 1 (scan)", then e.g. "pass 2 of 4
  /// (phase, channels 1-2 of 3)": the file is read twice per group of `threads` channels, so a
  /// progress display restarts at 0 % that many times.
  std::function<void(const std::string&)> stage;
  /// Called in the first read pass after each block with the log's channel names and the block
  /// (every channel, values in SI: x to_si, in row order), so that a caller can check the values
  /// (adev's outlier check) without reading the log a third time. Not called in later passes.
  std::function<void(const std::vector<std::string>& channel_names, const SampleBlock& block)>
      first_pass_block;
};

struct OutOfCoreResult {
  std::vector<std::string> channel_names;
  TimingReport timing;  ///< of the (last) read pass
  double rate_hz = 0;
  std::int64_t samples = 0;
  std::vector<std::vector<AllanCurve>> curves;  ///< [channel][statistic]
};

/// Reads `log` (a file, not stdin: it is read twice per group of `threads` channels), multiplies
/// each value by to_si, and computes every statistic of every channel. rate_hz(timing of the
/// first full pass) gives the sample rate [Hz] (it may throw). Throws ParseError / Error like
/// LogReader, Error if the file changes length between passes, and Error if the temporary
/// files cannot be created.
OutOfCoreResult compute_allan_curves_out_of_core(
    const LogOptions& log, DataKind kind, double to_si,
    const std::function<double(const TimingReport&)>& rate_hz,
    const std::vector<Statistic>& statistics, const TauSpec& taus, double confidence_level,
    const OutOfCoreSettings& settings = {});

/// The taus of each statistic, chosen once the log's length is known (after the first pass):
/// called with the number of phase points and the sample interval tau0_s [s], returns one
/// TauSpec per statistic (e.g. an explicit list with the taus a statistic cannot reach left
/// out, as adev does with several statistics).
using TausForLength = std::function<std::vector<TauSpec>(std::int64_t n_phase_points, double tau0_s)>;

/// As above, with each statistic's taus from taus_for.
OutOfCoreResult compute_allan_curves_out_of_core(
    const LogOptions& log, DataKind kind, double to_si,
    const std::function<double(const TimingReport&)>& rate_hz,
    const std::vector<Statistic>& statistics, const TausForLength& taus_for,
    double confidence_level, const OutOfCoreSettings& settings = {});

}  // namespace sigmatau
