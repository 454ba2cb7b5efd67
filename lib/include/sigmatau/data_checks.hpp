#pragma once
/// \file data_checks.hpp
/// Plausibility checks on channels in memory: saturation, stuck sensor, declared unit, outliers.
/// They never throw on suspicious data; they return warnings with a location (0-based row) for
/// the results and the report. Pure functions: no I/O, no global state.
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
/// - outliers: see check_outliers below (blocks of 4096 rows, 8 robust sigma).
///
/// Glossary: run = maximal sequence of consecutive rows holding the same value.

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace sigmatau {

enum class DataWarningKind { saturation, stuck, unit, outlier };

/// One warning about one channel (or one triad for unit checks). Runs are summarised: the first
/// run and the longest are located, all are counted. An outlier warning counts samples as runs
/// of one row: first_row is the first outlier, longest_row the largest (in robust sigma), runs
/// and rows_flagged both the number of outliers, value the largest outlier's value.
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
  double first_value = 0;         ///< outlier: the first outlier's value [as the values given]
  double largest_sigma = 0;       ///< outlier: the largest outlier's |x - median| / robust sigma
  std::string message;            ///< one line, e.g. "gyro_x: 2 runs of >= 5 samples at the
                                  ///< channel maximum 32767 (saturation?), first at row 1200
                                  ///< (120 rows), longest at row 5000 (300 rows)"
};

/// Human-readable kind: "saturation" | "stuck" | "unit" | "outlier".
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

/// Outlier check (spikes). The rows are cut into fixed blocks of options.block_rows by row index
/// (0-based, from the first value); each block gets its own centre and scale from a sample of at
/// most 1024 of its rows, evenly strided (every 4th of 4096):
///   median    m = the sample's median (upper median for an even count);
///   sigma     s = max(q90 / 1.6449, d_min), q90 = the 90th percentile of |x - m| over the sample
///             (1.6449 = the standard normal's |z| at 90 %, so s = sigma for Gaussian noise),
///             d_min = the smallest |x - m| > 0 in the sample (the data's resolution near m).
/// Every row of the block with |x - m| > k s (k = options.threshold_sigma) is an outlier. The
/// last, partial block takes m and s from the last block_rows rows of the channel (it shares
/// rows with the block before); a channel shorter than one block is one block, checked when it
/// has >= 64 rows. Non-finite values are never outliers and never enter m or s (as the run
/// checks never form runs of them). A block whose sample holds one value only (a constant
/// channel: check_stuck's business) has s = 0 and flags nothing. Nothing is removed or changed.
///
/// Why these choices (bench/bench_outliers.cpp, bench/results_outliers.md, November 2026):
/// - The scale is the 90th percentile, not the MAD (the 50th). On the real XSens MTi-G gyro
///   (shared/data/imu/xsens_mtig_cont_imu1, 500,000 rows) the healthy noise is a narrow core
///   plus a wide component, and the MAD sees only the core: 8736 rows beyond 8 MAD-sigma, a
///   smooth tail with no gap. With q90 the counts beyond 4, 5, 6, 7, 8, 10 sigma are 568, 161,
///   130, 127, 121, 102: a plateau from 6 to 8, the isolated spikes up to 0.297 rad/s (49.8
///   sigma, row 312386) the data set is known for; they raise its N by 6 %. On Gaussian noise
///   q90 is also the more precise scale (2.8 % spread from 1024 values; the MAD's is 3.6 %), and
///   a random walk cannot pull it far below the path's excursion (90 % of the block lies within
///   q90 of m). It breaks down only when > 10 % of a block's sample are outliers.
/// - k = 8. Expected false alarms on Gaussian white noise, from the tail at each block's own m
///   and s over 20,000 blocks: 6e-7 per 1e8 samples (7: 7e-4; 6: 0.33). Simulated (Simulator,
///   100 Hz, 1e8 samples each): white noise 0 beyond 6 sigma, largest 5.97; a rate random walk
///   whose step equals the white noise, and a pure random walk: 31 and 64 beyond 6, none beyond
///   7, largest 6.25; 0.5-LSB white noise through a real quantizer: none beyond 3. Real logs:
///   the ADIS16405 gyros (1e6 rows) and all six HiPNUC CH104 channels (321,253 rows, coarse
///   steps) reach 5.2 sigma at most; the ADIS accelerometers give 1 (x), 3 (y, single samples
///   of 8-10 LSB) and 11 (z: a shock at row 678, 17.3 sigma) outliers.
/// - d_min keeps quantized data quiet: with noise below ~0.9 LSB q90 is at most 1 LSB, s = 1 LSB,
///   and a jump must exceed 8 LSB; when > 90 % of a block sits on one code q90 is 0 and s alone
///   would flag every other code. A channel stored as float32 (1e6 + noise: steps of 0.0625) is
///   the same case.
/// - Blocks by row index make the result independent of how the values arrive, in O(1) memory
///   (two blocks); 4096 rows is 41 s at 100 Hz, short against bias drift. Cost 4.6-4.8 ns per
///   value (thread CPU time; one summing pass over the same values: 0.9-1.0 ns), about 3/4 of
///   it the two nth_element per block.
struct OutlierOptions {
  std::int64_t block_rows = 4096;  ///< rows per block; >= 64
  double threshold_sigma = 8;      ///< k: flag |x - median| > k robust sigma; > 0
  /// q in [0.5, 1): sigma from the q-quantile of |x - median| over the sample, divided by the
  /// standard normal's |z| at q (0.5 gives the MAD x 1.4826; see above for why 0.9).
  double scale_quantile = 0.9;
  /// Check the differences of consecutive values instead (phase data, where a spike in the rate
  /// is a step): row i is x[i] - x[i-1], row 0 has none.
  bool differences = false;
};

/// A block's centre and robust sigma, as the outlier check computes them (see OutlierOptions).
struct OutlierScale {
  double median = 0;  ///< m [as the values]
  double sigma = 0;   ///< s [as the values]; 0 when the sample holds fewer than two values
};

/// m and s of one window of values: from every stride-th finite value, stride =
/// max(1, size / 1024). Throws Error when scale_quantile is outside [0.5, 1).
OutlierScale outlier_scale(std::span<const double> window, double scale_quantile = 0.9);

/// check_outliers on a channel delivered in pieces: add() every value in order, then finish()
/// returns what check_outliers returns on the whole channel, bit for bit, however the values
/// were split. Memory: 2 blocks of values plus a 1024-value sample.
class OutlierChecker {
 public:
  /// `unit` and `to_si` only label values in the message (value / to_si, then the unit; no unit
  /// when empty). Throws Error when block_rows < 64, threshold_sigma is not > 0, scale_quantile
  /// is outside [0.5, 1) or to_si not > 0.
  explicit OutlierChecker(std::string channel, OutlierOptions options = {}, std::string unit = "",
                          double to_si = 1);
  void add(std::span<const double> values);
  /// The warning summarising every outlier, or nullopt when there is none.
  std::optional<DataWarning> finish();

 private:
  void push(std::span<const double> values);  ///< values of the checked series, in order
  void check_block(std::span<const double> window, std::size_t first, std::int64_t first_row);
  std::string channel_;
  OutlierOptions options_;
  double quantile_z_;              ///< the standard normal's |z| at options_.scale_quantile
  std::string unit_;
  double to_si_;
  std::int64_t row_ = 0;           ///< rows of the checked series pushed so far
  double last_ = 0;                ///< previous value (options.differences)
  bool have_last_ = false;
  std::vector<double> block_;      ///< rows of the open block
  std::vector<double> previous_;   ///< the last full block (the tail's statistics)
  std::vector<double> sample_;     ///< scratch: the strided sample
  DataWarning found_;
};

/// Outliers (spikes) of one channel: at most one warning counting every sample beyond
/// options.threshold_sigma robust sigma of its block, locating the first and the largest (see
/// OutlierOptions for the method and its numbers). Values are never changed. `unit` and `to_si`
/// label the values in the message (see OutlierChecker). Throws Error as OutlierChecker.
std::optional<DataWarning> check_outliers(std::span<const double> values,
                                          const std::string& channel,
                                          const OutlierOptions& options = {},
                                          const std::string& unit = "", double to_si = 1);

}  // namespace sigmatau
