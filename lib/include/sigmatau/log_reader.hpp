#pragma once
/// \file log_reader.hpp
/// Reading multi-channel logs as a stream of blocks: CSV / TSV / whitespace text (optional header,
/// # or % comments, gzip transparently, "-" for stdin) and raw interleaved binary. Values are
/// returned as they are in the file (no unit conversion here); the time column, when given, is
/// converted to seconds.
///
/// Text format rules (one place; lib/src/text_log.cpp implements them):
/// - Lines end in LF or CRLF. Blank lines and lines whose first non-blank character is '#' or '%'
///   are skipped anywhere in the file. A UTF-8 byte-order mark at the start is ignored.
/// - The delimiter is chosen from the first data line: a tab if it holds one, else a comma if it
///   holds one, else runs of spaces/tabs. Spaces around a field, a leading '+' and one pair of
///   surrounding double quotes are tolerated; quoted fields may not contain the delimiter.
/// - Lines before the header or first data row whose first field ends in ':' ("Type: Phase",
///   "File: AUTO.DAT", "Date: 01/01/21 15:34:21") are a file preamble, skipped like comments; a
///   Stable32 data file's "Type:" and "Tau:" (in such lines or in '#' comments) are reported in
///   TimingReport::header.
/// - The first non-comment row is a header when any of its fields is not a number.
/// - A column is read as data, by default, when its first data field is a number, or when it is
///   not but the column holds numbers in most of the rows after it (a typo in the first row:
///   then that field is an error, like any field that is not a number). A field that is a number
///   with a decimal comma ("1,288") is an error naming it. Other columns are text and left out,
///   each listed in TimingReport::header.text_columns.
/// - Limits (for bounded memory on hostile input): a line holds at most 1 MiB and at most 100000
///   fields; longer lines or wider rows are a ParseError.
/// Memory stays bounded: the reader holds one read buffer (default 4 MiB) plus one line.
///
/// ROS bags are read without ROS: a ROS 1 bag (v2.0, chunks uncompressed, bz2 or lz4), a ROS 2
/// MCAP file (chunks uncompressed, zstd or lz4; messages CDR or ROS 1 encoded), a rosbag2 SQLite
/// file (.db3, CDR little or big endian, zstd per message), or a rosbag2 folder holding
/// metadata.yaml and its .db3/.mcap files. They are recognised by their magic bytes or extension
/// (or by being a folder with metadata.yaml). A bag yields the sensor_msgs/Imu messages of one
/// topic as channels gx, gy, gz (angular_velocity [rad/s]) and ax, ay, az (linear_acceleration
/// [m/s^2]) with a time column from header.stamp (or the receive time, LogOptions::stamp). For a
/// bag, SampleBlock::t_s counts from the stamp of the first message delivered (so nanosecond
/// epoch stamps keep nanosecond resolution in the double).
/// Memory stays bounded by one chunk (a few MiB in practice) plus the reorder window.

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sigmatau {

/// Unit of a time column: seconds, milli-, micro- or nanoseconds, minutes, hours or days (e.g. a
/// Modified Julian Date).
enum class TimeUnit { s, ms, us, ns, min, h, d };
/// Type of each value of a raw binary log (none: the log is text or a ROS bag): 16- or 32-bit
/// signed integers, 32- or 64-bit IEEE floats (value_bytes gives the size).
enum class BinaryFormat { none, i16, i32, f32, f64 };

/// What to do with NaN or Inf in a selected column (or the time column).
enum class NonFinitePolicy {
  error,     ///< throw ParseError "non-finite value" (default)
  skip_row,  ///< drop the whole row and count it in TimingReport::rows_skipped_nonfinite
};

/// What to do with gaps in the time column (intervals > 1.5 nominal intervals) and with
/// non-increasing (duplicated or backwards) stamps. Without a time column there is nothing to do.
enum class GapPolicy {
  report,  ///< count and report them in TimingReport only (the LogOptions default: a library
           ///< caller decides; the CLI's --gaps default is `error`)
  error,   ///< ParseError once the input is read, at the line of the first gap or non-increasing
           ///< stamp (whichever comes first), with its length, the counts, and the options to use
  split,   ///< TimingReport::segment_starts lists where the contiguous segments begin (every gap
           ///< and every non-increasing stamp starts one); estimators compute each segment's
           ///< Allan sums apart and add them, so no difference spans a gap
  fill,    ///< read_log inserts linearly interpolated samples into each gap (counted in
           ///< TimingReport::filled_samples); non-increasing stamps are an error as under `error`.
           ///< LogReader alone streams the rows as read and only reports the gaps.
};

/// Time stamp of a bag message: the message's own header.stamp (when the sensor sampled) or the
/// time the recorder received it.
enum class BagStamp { header, receive };

/// What to do with a ROS bag whose recording was cut short: a file without index or summary
/// (its recorder died: a crash, a full disk, Ctrl-C) that ends inside a record. A file with an
/// index, summary or footer that ends inside a record is corrupt and always a ParseError.
enum class TruncatedPolicy {
  error,  ///< ParseError naming the byte offset of the cut and how many complete messages of the
          ///< topic precede it (the default)
  use,    ///< read the complete messages before the cut, then end as at a normal end;
          ///< TimingReport::truncated_at_byte says where the recording was cut
};

/// "error" | "use". Throws Error otherwise.
TruncatedPolicy parse_truncated_policy(std::string_view text);

/// "s" | "ms" | "us" | "ns" | "min" | "h" | "d"; "i16" | "i32" | "f32" | "f64"; "report" | "error" | "split" |
/// "fill"; "skip" | "error". Throw Error otherwise.
TimeUnit parse_time_unit(std::string_view text);
BinaryFormat parse_binary_format(std::string_view text);
/// Bytes of one value of a raw binary log: 2 (i16), 4 (i32, f32), 8 (f64). Throws Error for
/// BinaryFormat::none.
std::int64_t value_bytes(BinaryFormat format);
GapPolicy parse_gap_policy(std::string_view text);
NonFinitePolicy parse_nonfinite_policy(std::string_view text);
/// "header" | "receive". Throws Error otherwise.
BagStamp parse_bag_stamp(std::string_view text);

/// What to read from a log and how (text columns, raw binary layout, ROS bag topic).
struct LogOptions {
  std::string path;                  ///< file, or "-" for stdin; gzip detected by magic bytes
  std::vector<std::string> columns;  ///< header names or 0-based indices (an all-digit entry is
                                     ///< an index; without a header "c<index>" names work too);
                                     ///< empty: every column whose first data field is a number,
                                     ///< except the time column, in file order
  std::string time_column;           ///< header name or 0-based index; empty: no time column
                                     ///< (or the one found by name, find_time_column)
  /// When time_column is empty: the header column named t, time or timestamp (any case), alone
  /// or with a unit suffix ("_s", "_ms", "_us", "_ns", "_min", "_h", "_d", "_mjd", or in brackets:
  /// "time [ms]"), is the time column. A column named in `columns` is never taken, nor one whose
  /// values do not increase in the first rows (TextHeader::time_column_not_increasing: of t and
  /// a temperature named T, t is taken); two that both increase are a ParseError.
  bool find_time_column = false;
  /// Unit of the time column's values; unset: the unit suffix of its name (t_ms: ms), else s.
  std::optional<TimeUnit> time_unit;
  NonFinitePolicy nonfinite = NonFinitePolicy::error;
  GapPolicy gaps = GapPolicy::report;  ///< see GapPolicy (needs a time column to do anything)
  // Raw binary input (interleaved samples, channel-major per row):
  BinaryFormat binary = BinaryFormat::none;
  int binary_channels = 0;      ///< values per row (interleaved channels)
  bool big_endian = false;      ///< byte order of the values (default little-endian)
  std::int64_t skip_bytes = 0;  ///< header bytes to skip (of the decompressed stream)
  /// Size of each read [bytes]; 0 means the default (4 MiB). Small values exist for tests of rows
  /// split across buffer boundaries; memory use is about this plus the 1 MiB line limit.
  std::int64_t read_buffer_bytes = 0;
  // ROS bags (see the file comment). A bag always has a time column: time_column must stay empty
  // and time_unit is not used; `columns` picks among gx, gy, gz, ax, ay, az (default: all six).
  std::string topic;  ///< sensor_msgs/Imu topic; empty: the bag's only sensor_msgs/Imu topic
  BagStamp stamp = BagStamp::header;  ///< which time stamp is the time column
  /// Out-of-order stamps are sorted within this many messages [messages, >= 0]: a message may
  /// arrive up to this many messages after one with a later stamp. A stamp that is later still
  /// is a ParseError naming its location. Memory: about 80 bytes per message of window.
  std::int64_t reorder_window = 10000;
  /// A recording cut short (see TruncatedPolicy): an error, or its complete messages are used.
  TruncatedPolicy truncated = TruncatedPolicy::error;
};

/// A topic of a bag, as listed by list_bag_topics and in "which topic?" errors.
struct BagTopic {
  std::string name;           ///< e.g. "/imu/data"
  std::string type;           ///< e.g. "sensor_msgs/msg/Imu" (ROS 2) or "sensor_msgs/Imu" (ROS 1)
  std::int64_t messages = -1; ///< message count, -1 when the bag does not say
};

/// Whether LogReader reads `path` as a ROS bag (magic bytes, extension, or a folder holding
/// metadata.yaml). "-" (stdin) is never a bag.
bool is_bag_path(const std::string& path);

/// The topics of a bag with their types and message counts (from the bag's index or summary
/// when it has one, else by reading it through). Throws Error / ParseError like LogReader.
std::vector<BagTopic> list_bag_topics(const std::string& path);

/// The number of messages on `topic` (empty: the only sensor_msgs/Imu topic) as the bag's index
/// (ROS 1) or summary (MCAP) states it, without reading any message: cheap at any size. -1 when
/// the bag states none (unindexed, no summary or no counts in it; rosbag2 SQLite, whose count
/// needs a query over every message) or has no such topic. Throws Error / ParseError like
/// LogReader.
std::int64_t indexed_bag_messages(const std::string& path, const std::string& topic = "");

/// A block of rows, stored per channel: values[c][r].
struct SampleBlock {
  std::vector<std::vector<double>> values;
  std::vector<double> t_s;  ///< time of each row [s] when a time column is read, else empty
  std::int64_t rows() const {
    return values.empty() ? 0 : static_cast<std::int64_t>(values[0].size());
  }
};

/// An interval between consecutive time stamps larger than 1.5 nominal intervals.
struct Gap {
  std::int64_t row = 0;   ///< 0-based index of the sample after the gap
  std::int64_t line = 0;  ///< 1-based line in the file (text input), 0 for binary
  double start_s = 0;     ///< time stamp before the gap [s]
  double length_s = 0;    ///< interval [s]
};

/// Whether the file at `path` starts with the gzip magic bytes 1f 8b, i.e. whether LogReader
/// inflates it; false when it cannot be opened or holds fewer than 2 bytes.
bool is_gzip_file(const std::string& path);

/// Intervals whose exact median is TimingReport's nominal interval: the first this many (the
/// whole log when it is shorter). TimingReport::rate_hz is final once kRateMedianIntervals + 1
/// stamps have been read.
inline constexpr std::int64_t kRateMedianIntervals = 100000;

/// A column left out of the default selection: its first data field is not a number, and nor are
/// most of the fields after it (text: a status word, a date).
struct TextColumn {
  std::int64_t column = 0;  ///< 0-based
  std::string name;         ///< header name, or "c<index>"
  std::string first_field;  ///< its first data field, as written (cut to 40 characters)
  std::int64_t line = 0;    ///< the line of that field
};

/// What a text log's header told the reader besides its column names (empty for other inputs).
struct TextHeader {
  std::vector<TextColumn> text_columns;  ///< columns left out as text, in file order
  std::string time_column_found;  ///< the time column found by name (find_time_column), or ""
  /// The columns named as time stamps whose values do not increase (a temperature named T),
  /// comma-separated: read as channels, not as the time column; "" when none.
  std::string time_column_not_increasing;
  TimeUnit time_unit = TimeUnit::s;  ///< the time column's unit as used
  bool time_unit_from_name = false;  ///< whether that unit came from the column's name
  /// A Stable32 data file's declarations ("Type: Phase", "Tau: 1.0e+00", with or without '#'):
  /// "phase" or "frequency" ("" when not declared), the sample interval [s] (0 when not).
  std::string declared_type;
  double declared_tau_s = 0;
  /// A Stable32 data file of two columns (a time tag, then the value) read without `columns`:
  /// the time-tag column, left out (Stable32 ignores the tags and uses its Tau); "" otherwise.
  std::string time_tag_column;
};

/// Statistics of the time column, accumulated while reading. The nominal interval is the exact
/// median of the first kRateMedianIntervals intervals (bounded memory; the whole log when it is
/// shorter).
/// Intervals are differences of the stamps as written (integer parts subtracted exactly), so
/// nanosecond epoch stamps keep their resolution even though t_s itself is a double.
struct TimingReport {
  std::int64_t samples = 0;  ///< rows delivered (after skipped rows)
  bool has_time = false;
  double rate_hz = 0;          ///< 1 / nominal (median) interval; 0 without a time column or
                               ///< when fewer than 2 stamps or the median interval is <= 0
  double mean_interval_s = 0;  ///< mean of all intervals [s] = (t_last - t_first) / (samples - 1)
  double jitter_s = 0;         ///< standard deviation of the regular intervals [s]: gaps and
                               ///< non-increasing steps are excluded (they are reported apart)
  std::int64_t non_increasing = 0;  ///< intervals <= 0 (duplicated or backwards stamps)
  std::int64_t gap_count = 0;       ///< all intervals > 1.5 x nominal (the list below is capped)
  std::vector<Gap> gaps;            ///< the first 1000 gaps, in file order
  std::int64_t rows_skipped_nonfinite = 0;  ///< rows dropped by NonFinitePolicy::skip_row
  // Locations (0 / -1 when there is none):
  std::int64_t first_non_increasing_row = -1;   ///< 0-based row of the first stamp <= its previous
  std::int64_t first_non_increasing_line = 0;   ///< its 1-based line (text input)
  double first_non_increasing_step_s = 0;       ///< its interval [s] (<= 0)
  double largest_gap_s = 0;                     ///< longest gap [s] (0 without gaps)
  std::int64_t largest_gap_line = 0;            ///< its line (the sample after it)
  /// GapPolicy::split: 0-based first row of each contiguous segment, ascending, starting with 0
  /// (one entry when there is no break); empty under the other policies. Segment k is rows
  /// [segment_starts[k], segment_starts[k+1]) (the last ends at `samples`). Capped at 10^6
  /// segments (ParseError beyond: such a log has no usable contiguous stretch).
  std::vector<std::int64_t> segment_starts;
  std::int64_t filled_samples = 0;  ///< GapPolicy::fill: samples interpolated by fill_gaps
  /// ROS bags: messages that arrived after a message with a later stamp and were put back in
  /// order within LogOptions::reorder_window, and the largest such lateness [s].
  std::int64_t reordered_samples = 0;
  double max_reorder_s = 0;
  std::string bag_topic;  ///< ROS bags: the topic read (empty for other inputs)
  /// ROS bags read without LogOptions::topic: the bag's topics as listed when its only
  /// sensor_msgs/Imu topic was picked (counts -1 where the bag does not state them without a
  /// full scan); empty when a topic was given and for other inputs.
  std::vector<BagTopic> bag_topics;
  /// ROS bags read under TruncatedPolicy::use: byte offset in `truncated_file` of the first
  /// incomplete record, where the recording was cut short (the messages before it were read,
  /// `samples` of them delivered); -1 when the recording is complete, and for other inputs.
  std::int64_t truncated_at_byte = -1;
  std::string truncated_file;  ///< the file cut short (one of a rosbag2 folder's files), or ""
  TextHeader header;  ///< text logs: what their header told the reader
  /// What the reader met that did not stop it and the user should hear, one sentence each
  /// (without the file name): header names that are not UTF-8 and how they were read; bag
  /// messages on a connection no record declares (skipped, counted); a bag whose stated message
  /// count differs from the messages found. Empty when there is nothing to say.
  std::vector<std::string> warnings;
};

/// Streaming reader. The constructor opens the input and reads up to the first data row (so the
/// channel names are known); read_block() then parses one buffer-sized piece at a time.
/// Throws Error when the file cannot be opened (with strerror), and ParseError (file, 1-based
/// line, 1-based column = field number, what was expected) on bad input: no data rows, no numeric
/// column, ragged row, non-numeric field, NaN/Inf, unknown column name, column index out of range,
/// line or row over the limits, corrupt gzip, truncated binary record (byte offset in the message).
/// For stdin the file name in messages is "<stdin>".
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
  /// empty block, at the end of the input. When it throws (bad input), `block` holds the whole
  /// rows read in this call before the row in error, so that a caller may keep them (`adev
  /// --partial`); the reader must not be read again after a throw.
  bool read_block(SampleBlock& block, std::int64_t max_rows = 65536);
  /// As read_block, but the rows are appended to what `block` holds (its values must have one
  /// array per channel, or none): a caller that keeps the whole log reads straight into its
  /// final arrays instead of copying each block. When it throws, `block` holds what it held
  /// plus the whole rows read in this call before the row in error.
  bool append_block(SampleBlock& block, std::int64_t max_rows = 65536);
  /// Timing statistics of what has been read so far (final once read_block returned false).
  const TimingReport& timing() const;
  /// Bytes consumed so far and the total size when known (for progress display), else -1.
  /// Both count the file as stored (compressed bytes for gzip).
  std::int64_t bytes_read() const;
  std::int64_t total_bytes() const;
  /// Rows still to read, for sizing arrays once: for a raw binary file (not gzip, not a pipe)
  /// its remaining size / record size, an upper bound (rows skipped as non-finite count); for a
  /// plain text file, once a block has been read, an estimate from the bytes per row so far
  /// (with a 25 % margin); for a bag, the messages its index or summary states are left on the
  /// topic; -1 for gzip, pipes, a bag that states no count and a text file before its first
  /// block.
  std::int64_t rows_left_hint() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// A whole log in memory (one vector per channel), for the exact in-memory estimators.
struct Log {
  std::string path;
  std::vector<std::string> channel_names;
  std::vector<std::vector<double>> channels;
  std::vector<double> t_s;  ///< empty without a time column
  TimingReport timing;
};

/// Reads everything through LogReader. Throws like LogReader (an input without data rows is
/// ParseError "no data rows"), and Error "no samples" when no row is left after skipping rows
/// under NonFinitePolicy::skip_row. `progress(bytes_read, total_bytes)` is called after each
/// block when set (total -1 when unknown, e.g. stdin).
Log read_log(const LogOptions& options,
             const std::function<void(std::int64_t, std::int64_t)>& progress = {});

/// GapPolicy::fill on a log in memory: inserts into every gap of > 1.5 nominal intervals
/// (nominal = 1 / log.timing.rate_hz) round(dt / nominal) - 1 samples, with time stamps and every
/// channel interpolated linearly between the samples around the gap; adds the count to
/// log.timing.filled_samples and returns it. read_log calls it under GapPolicy::fill. Throws
/// ParseError when a stamp does not increase (nothing to interpolate), and Error when the log has
/// no time column or rate, or when filling would more than double the log (a stamp typo such as a
/// 1 h jump in a 10 min log: use split).
std::int64_t fill_gaps(Log& log);

/// The sample rate to use [Hz]: `rate_hz` when given (must be > 0 and finite), else the rate
/// measured from the time column; throws Error "no --rate and no time column" otherwise, and
/// Error when the time column gives no usable rate.
double resolve_rate_hz(std::optional<double> rate_hz, const TimingReport& timing,
                       const std::string& path);

}  // namespace sigmatau
