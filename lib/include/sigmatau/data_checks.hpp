#pragma once
/// \file data_checks.hpp
/// Plausibility checks on channels in memory: saturation, stuck sensor, declared unit. They never
/// throw on suspicious data; they return warnings with a location (0-based row) for the results
/// and the report. Pure functions: no I/O, no global state.
///
/// Thresholds (named constants in lib/src/data_checks.cpp, overridable in DataCheckOptions):
/// - stuck: a run of >= 50 identical consecutive values anywhere. A working sensor repeats a
///   value by chance only through quantization; even when the most frequent code has probability
///   0.5 per sample (noise sigma ~ 0.8 LSB), a chance run of 50 has probability 2^-49 ~ 1.8e-15
///   per sample, i.e. < 1e-5 false alarms in 10^9 samples.
/// - saturation: a run of >= 5 identical consecutive values equal to the channel's minimum or
///   maximum. The extreme of an unsaturated noisy channel is, by definition, its rarest value
///   (continuous data: one sample; quantized Gaussian noise: a handful of samples scattered over
///   the log), so 5 in a row means the signal was clipped at the range limit.
/// - units: a static gyro whose mean rate magnitude exceeds 0.5 rad/s (~29 deg/s, beyond the
///   largest zero-rate offsets of consumer MEMS gyros, e.g. +-20 deg/s for the MPU-6050, plus the
///   Earth rate 7.3e-5 rad/s); an accelerometer triad whose mean norm is outside 0.75..1.25 g
///   (a static accelerometer reads 1 g; 25 % covers bias and scale-factor errors of the worst
///   consumer parts many times over, while a wrong unit is off by >= 3.3x: ft/s^2 vs m/s^2).
///
/// Glossary: run = maximal sequence of consecutive rows holding the same value.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace sigmatau {

enum class DataWarningKind { saturation, stuck, unit };

/// One warning about one channel (or one triad for unit checks). Runs are summarised: the first
/// run and the longest are located, all are counted.
struct DataWarning {
  DataWarningKind kind = DataWarningKind::stuck;
  std::string channel;            ///< channel name (triad: names joined by "+")
  std::int64_t first_row = -1;    ///< 0-based row where the first flagged run starts (-1: n/a)
  std::int64_t first_rows = 0;    ///< length of the first flagged run [rows]
  std::int64_t longest_row = -1;  ///< 0-based row where the longest flagged run starts
  std::int64_t longest_rows = 0;  ///< length of the longest flagged run [rows]
  std::int64_t runs = 0;          ///< flagged runs in the channel
  std::int64_t rows_flagged = 0;  ///< rows inside flagged runs
  double value = 0;               ///< the repeated value (runs), or the mean magnitude [SI] (unit)
  std::string likely_unit;        ///< unit check: the unit the data most likely are in ("" unknown)
  std::string message;            ///< one line, e.g. "gyro_x: 2 runs of >= 5 samples at the
                                  ///< channel maximum 32767 (saturation?), first at row 1200
                                  ///< (120 rows), longest at row 5000 (300 rows)"
};

/// Human-readable kind: "saturation" | "stuck" | "unit".
std::string to_string(DataWarningKind kind);

struct DataCheckOptions {
  std::int64_t stuck_min_run = 50;      ///< rows; see the file comment for why 50
  std::int64_t saturation_min_run = 5;  ///< rows; see the file comment for why 5
};

/// Runs of >= options.saturation_min_run identical values at the channel's minimum or maximum.
/// Returns at most two warnings (one per extreme). Nothing for a constant channel (min == max:
/// that is check_stuck's business) or one shorter than the threshold. Non-finite values never
/// form runs. Throws Error when the threshold is < 2.
std::vector<DataWarning> check_saturation(std::span<const double> values,
                                          const std::string& channel,
                                          const DataCheckOptions& options = {});

/// Runs of >= options.stuck_min_run identical values anywhere: at most one warning summarising
/// all of them. Throws Error when the threshold is < 2.
std::optional<DataWarning> check_stuck(std::span<const double> values, const std::string& channel,
                                       const DataCheckOptions& options = {});

/// Both run checks on one channel: saturation first, then stuck (a run at an extreme that is long
/// enough for both is reported in both: it is both clipped and constant).
std::vector<DataWarning> check_runs(std::span<const double> values, const std::string& channel,
                                    const DataCheckOptions& options = {});

/// The value of a channel that is one run of identical values from start to end: the stuck
/// warning of check_runs / RunChecker::finish (or check_stuck) as long as the channel's `rows`;
/// nullopt otherwise. Such a channel has no noise to measure (a stuck sensor, or precision lost).
std::optional<double> whole_run_value(const std::vector<DataWarning>& run_warnings,
                                      std::int64_t rows);

/// "channel NAME is constant (HOW): a stuck sensor, or precision lost (e.g. a large offset
/// stored as float32)", HOW e.g. "every value is 0.123"; the caller adds what it means for its
/// results.
std::string constant_channel_text(const std::string& channel, const std::string& how);

/// check_runs on a channel delivered in pieces (a log read block by block): add() every value in
/// order, then finish() returns what check_runs returns on the whole channel, bit for bit, in
/// constant memory. Saturation runs are kept for the running minimum and maximum and dropped
/// when a new extreme appears (every run at the final extreme comes after its first occurrence).
class RunChecker {
 public:
  /// Throws Error like check_runs when a threshold is < 2.
  explicit RunChecker(std::string channel, DataCheckOptions options = {});
  void add(std::span<const double> values);
  /// The warnings (saturation at the minimum, at the maximum, then stuck), as check_runs.
  std::vector<DataWarning> finish();

 private:
  void close_run();
  std::string channel_;
  DataCheckOptions options_;
  std::int64_t row_ = 0;        ///< rows seen
  std::int64_t run_start_ = 0;  ///< row where the open run starts
  double run_value_ = 0;        ///< value of the open run (its first value)
  double lo_;                   ///< running finite minimum (+inf before the first)
  double hi_;                   ///< running finite maximum (-inf before the first)
  DataWarning at_lo_, at_hi_, stuck_;
};

/// check_gyro_unit from the per-axis sums of the SI values (taken in row order) over `rows`
/// rows: the same result as check_gyro_unit on the axes, bit for bit. Throws Error for 0 or > 3
/// sums, a name count that differs, rows < 1 or to_si not > 0.
std::optional<DataWarning> check_gyro_unit_sums(const std::vector<double>& sums_si,
                                                std::int64_t rows,
                                                const std::vector<std::string>& names,
                                                const std::string& declared_unit, double to_si);

/// check_accel_unit from the sum over rows of the SI norm (std::hypot of the three axes, taken in
/// row order) over `rows` rows: the same result as check_accel_unit, bit for bit. Throws Error
/// unless there are 3 names, rows >= 1 and to_si > 0.
std::optional<DataWarning> check_accel_unit_sums(double norm_sum_si, std::int64_t rows,
                                                 const std::vector<std::string>& names,
                                                 const std::string& declared_unit, double to_si);

/// Declared-unit sanity of a static gyro: `axes_si` are 1..3 rate channels already converted to
/// rad/s with `to_si` (the factor the declared unit `declared_unit` gave). Warns when the
/// magnitude of the vector of per-axis means exceeds 0.5 rad/s; likely_unit is the first of
/// deg/s, deg/h, mrad/s (whichever is closest to the declared factor and puts the mean in the
/// plausible range), or "raw counts (LSB)" when none does. Throws Error for 0 or > 3 axes, empty
/// or unequal lengths, or to_si not > 0.
std::optional<DataWarning> check_gyro_unit(const std::vector<std::span<const double>>& axes_si,
                                           const std::vector<std::string>& names,
                                           const std::string& declared_unit, double to_si);

/// Declared-unit sanity of a static accelerometer triad in m/s^2 (converted with `to_si` from
/// `declared_unit`): warns when the mean of the per-row norms is outside 0.75..1.25 g
/// (g = 9.80665 m/s^2); likely_unit is the unit among m/s^2, g, mg, ft/s^2 that puts it inside,
/// or "" when none does. Throws Error unless there are exactly 3 non-empty axes of equal length
/// and to_si > 0.
std::optional<DataWarning> check_accel_unit(const std::vector<std::span<const double>>& axes_si,
                                            const std::vector<std::string>& names,
                                            const std::string& declared_unit, double to_si);

}  // namespace sigmatau
