#pragma once
/// \file log_reader.hpp
/// Reading multi-channel logs as a stream of blocks: CSV / TSV / whitespace text (optional header,
/// # or % comments, gzip transparently, "-" for stdin) and raw interleaved binary. Values are
/// returned as they are in the file (no unit conversion here); the time column, when given, is
/// converted to seconds.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sigmatau {

enum class TimeUnit { s, ms, us, ns };
enum class BinaryFormat { none, i16, i32, f32, f64 };

/// "s" | "ms" | "us" | "ns"; "i16" | "i32" | "f32" | "f64". Throw Error otherwise.
TimeUnit parse_time_unit(std::string_view text);
BinaryFormat parse_binary_format(std::string_view text);

struct LogOptions {
  std::string path;                   ///< file, or "-" for stdin; gzip detected by magic bytes
  std::vector<std::string> columns;   ///< header names or 0-based indices; empty: every numeric
                                      ///< column except the time column
  std::string time_column;            ///< header name or 0-based index; empty: no time column
  TimeUnit time_unit = TimeUnit::s;
  // Raw binary input (interleaved samples, channel-major per row):
  BinaryFormat binary = BinaryFormat::none;
  int binary_channels = 0;
  bool big_endian = false;
  std::int64_t skip_bytes = 0;
};

/// A block of rows, stored per channel: values[c][r].
struct SampleBlock {
  std::vector<std::vector<double>> values;
  std::vector<double> t_s;  ///< time of each row [s] when a time column is read, else empty
  std::int64_t rows() const { return values.empty() ? 0 : static_cast<std::int64_t>(values[0].size()); }
};

/// An interval between consecutive time stamps larger than 1.5 nominal intervals.
struct Gap {
  std::int64_t row = 0;     ///< 0-based index of the sample after the gap
  std::int64_t line = 0;    ///< 1-based line in the file (text input), 0 for binary
  double start_s = 0;       ///< time stamp before the gap [s]
  double length_s = 0;      ///< interval [s]
};

/// Statistics of the time column, accumulated while reading.
struct TimingReport {
  std::int64_t samples = 0;
  bool has_time = false;
  double rate_hz = 0;         ///< 1 / median interval (0 without a time column)
  double mean_interval_s = 0;
  double jitter_s = 0;        ///< standard deviation of the intervals [s]
  std::int64_t non_increasing = 0;  ///< intervals <= 0 (duplicated or backwards stamps)
  std::vector<Gap> gaps;      ///< intervals > 1.5 x the nominal one
};

/// Streaming reader. Throws ParseError (file, line, column, what was expected) on bad input:
/// empty file, no numeric column, ragged row, non-numeric field, NaN/Inf, unknown column,
/// truncated binary record.
class LogReader {
 public:
  explicit LogReader(const LogOptions& options);
  ~LogReader();
  LogReader(const LogReader&) = delete;
  LogReader& operator=(const LogReader&) = delete;

  /// Names of the selected channels (header names, or "c<index>" without a header).
  const std::vector<std::string>& channel_names() const;
  bool has_time() const;
  /// Reads up to max_rows rows into `block` (replacing its contents). Returns false, with an
  /// empty block, at the end of the input.
  bool read_block(SampleBlock& block, std::int64_t max_rows = 65536);
  /// Timing statistics of what has been read so far.
  const TimingReport& timing() const;
  /// Bytes consumed so far and the total size when known (for progress display), else -1.
  std::int64_t bytes_read() const;
  std::int64_t total_bytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// A whole log in memory (one vector per channel), for the exact in-memory estimators.
struct Log {
  std::string path;
  std::vector<std::string> channel_names;
  std::vector<std::vector<double>> channels;
  std::vector<double> t_s;       ///< empty without a time column
  TimingReport timing;
};

/// Reads everything through LogReader. Throws like LogReader, and Error "no samples" when the
/// input holds no data rows.
Log read_log(const LogOptions& options);

/// The sample rate to use: `rate_hz` when given (must be > 0), else the rate measured from the
/// time column; throws Error "no --rate and no time column" otherwise.
double resolve_rate_hz(std::optional<double> rate_hz, const TimingReport& timing,
                       const std::string& path);

}  // namespace sigmatau
