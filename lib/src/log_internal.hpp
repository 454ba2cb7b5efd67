#pragma once
// Internal pieces shared by the text and binary log readers: limits, number parsing, column
// selection, and the timing accumulator.
#include <charconv>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sigmatau/log_reader.hpp"

namespace sigmatau::detail {

/// Default read size: large enough that syscall and refill overhead vanish next to parsing,
/// small enough to stay in L2/L3-friendly territory and cheap on small machines.
constexpr std::size_t kDefaultBufferBytes = std::size_t{4} << 20;
/// Longest accepted text line [bytes]. A real log row is < 10 kB; a longer "line" is almost
/// always a binary file read as text, and the limit keeps memory bounded.
constexpr std::size_t kMaxLineBytes = std::size_t{1} << 20;
/// Most fields accepted in one row (bounded memory for the per-column tables).
constexpr std::size_t kMaxColumns = 100000;
/// Longest field text quoted in an error message [characters].
constexpr std::size_t kMaxQuotedField = 40;

/// An interval of 2 nominal periods is one missing sample; 1.5 is halfway between 1 and 2, so
/// jitter of up to +-50 % of a period is not mistaken for a gap: a gap is dt > kGapFactor x the
/// nominal interval.
inline constexpr double kGapFactor = 1.5;

/// "c<index>", the name of a column without a header (or with an empty name).
std::string unnamed_column(std::size_t index);

/// A duration for a message: "40 ms", "2.5 s", "-3 us" (4 significant digits).
std::string format_seconds(double s);

/// Field slots: what to do with each column of the file.
constexpr int kSkipColumn = -1;
constexpr int kTimeColumn = -2;

/// Strips surrounding spaces/tabs, one pair of double quotes, and a leading '+' before a digit
/// or '.'.
std::string_view trim_field(std::string_view field);

/// Parses a whole (trimmed) field as a double. nullopt when it is not a number. Values beyond
/// the double range come back as +-inf (and are caught as non-finite), tiny ones as 0 or
/// subnormal.
std::optional<double> to_number(std::string_view field);

/// A header name as every output shows it: UTF-8 unchanged, anything else read as
/// Windows-1252 (text_encoding.hpp).
std::string shown_name(std::string_view raw);

/// `field` in double quotes for a message, cut to kMaxQuotedField characters ("..." appended).
std::string quote_field(std::string_view field);

/// The hint for text whose fields are separated by ';' (a European CSV, which the reader does
/// not split), `where` naming it ("the header", "the line"): "; <where> holds ';': ...".
std::string semicolon_hint(const std::string& where);

/// The outcome of matching LogOptions::columns / time_column against a file's columns.
struct ColumnSelection {
  std::vector<int> slots;            ///< per file column: channel index, kSkipColumn, kTimeColumn
  std::vector<int> channel_columns;  ///< per channel: its file column
  std::vector<std::string> channel_names;  ///< UTF-8 (names that are not: utf8_from_windows1252)
  bool has_time = false;
  TimeUnit time_unit = TimeUnit::s;  ///< of the time column (LogOptions, else its name's suffix)
  bool time_unit_from_name = false;
  std::string time_column_found;     ///< found by name (LogOptions::find_time_column), or ""
  /// The columns named as time stamps (LogOptions::find_time_column); with two or more none is
  /// taken here: the text reader keeps the one whose values increase.
  std::vector<int> time_candidates;
  /// One per selected column whose header name is not UTF-8: how it was read (TimingReport).
  std::vector<std::string> warnings;
};

/// The unit a time column's name gives ("t_ms", "time [us]", "Timestamp_ns", "t_mjd": days),
/// nullopt when the name carries none; `is_time` says whether the name is that of a time column
/// (t, time or timestamp, any case, with or without such a suffix).
struct TimeColumnName {
  bool is_time = false;
  std::optional<TimeUnit> unit;
};
TimeColumnName time_column_name(std::string_view name);

/// Resolves the selection. `names` holds one entry per file column (header names as read, or
/// empty strings without a header; a name that is not UTF-8 is read as Windows-1252, matched
/// both ways, and said in ColumnSelection::warnings); `numeric[c]` says whether the first data
/// row holds a number there.
/// `what` is "column" (text) or "channel" (binary). Errors are ParseError at (file, names_line, 0)
/// for names and indices, at (file, data_line, 0) for "no numeric columns".
ColumnSelection select_columns(const std::vector<std::string>& names, bool has_header,
                               const std::vector<bool>& numeric, const LogOptions& options,
                               const std::string& file, std::int64_t names_line,
                               std::int64_t data_line, const std::string& what);

/// A time stamp as written: integer part exact, fraction separately, in the file's unit.
struct TimeStamp {
  std::int64_t whole = 0;
  double frac = 0;
};

/// Parses a time field ("1700000000123456789", "1700000000.123456", "1.5e3"). false when it is
/// not a number; a non-finite value gives true with a non-finite frac.
bool parse_time_stamp(std::string_view field, TimeStamp& stamp);

/// Accumulates TimingReport with bounded memory (see TimingReport).
class TimingAccumulator {
 public:
  void start(bool has_time, TimeUnit unit);
  /// The gap policy and the file name for its errors (the parsers call it from their
  /// constructors; start() leaves it alone).
  void set_policy(GapPolicy policy, const std::string& file) {
    policy_ = policy;
    file_ = file;
  }
  /// Adds one time-stamped sample found on `line` (0 for none).
  void add(const TimeStamp& stamp, std::int64_t line);
  /// Adds `n` samples without time stamps.
  void add_untimed(std::int64_t n) { samples_ += n; }
  void add_skipped() { ++skipped_; }
  /// What the text log's header told the reader (reported as TimingReport::header).
  void set_header(TextHeader header) { header_ = std::move(header); }
  double seconds(const TimeStamp& stamp) const;
  /// Call once at the end of the input: freezes the nominal interval; under GapPolicy::error
  /// (and ::fill, for non-increasing stamps) throws the ParseError described there.
  void finish();
  /// The report of everything added so far.
  TimingReport report() const;

 private:
  struct Interval {
    double dt_s;
    double start_s;
    std::int64_t line;
  };
  struct Classified {
    std::int64_t gap_count = 0;
    std::vector<Gap> gaps;
    double largest_gap_s = 0;
    std::int64_t largest_gap_line = 0;
    /// Positive intervals under half the nominal one: lost samples make none, jittered stamps
    /// (receive times) about as many as their "gaps".
    std::int64_t short_count = 0;
    std::vector<std::int64_t> breaks;  // rows starting a segment (GapPolicy::split only)
    std::int64_t regular = 0;  // Welford over regular intervals
    double mean = 0;
    double m2 = 0;
  };
  static double median(std::vector<double> values);
  void classify(Classified& c, double nominal_s, std::int64_t row, std::int64_t line,
                double start_s, double dt_s) const;
  void freeze();
  /// The end of the gap error when the gaps look like jittered stamps (see kShortFactor).
  std::string jitter_advice() const;

  bool has_time_ = false;
  double divisor_ = 1;     // file unit -> s (divided by, so ms -> s is exactly rounded)
  double multiplier_ = 1;  // ... then multiplied by (min, h, d)
  TextHeader header_;
  std::int64_t samples_ = 0;
  std::int64_t skipped_ = 0;
  TimeStamp prev_;
  double prev_s_ = 0;
  std::int64_t intervals_ = 0;
  double mean_all_ = 0;
  std::int64_t non_increasing_ = 0;
  std::int64_t first_ni_row_ = -1;
  std::int64_t first_ni_line_ = 0;
  double first_ni_step_s_ = 0;
  GapPolicy policy_ = GapPolicy::report;
  std::string file_;
  bool frozen_ = false;
  double nominal_s_ = 0;
  std::vector<Interval> window_;
  Classified classified_;
};

}  // namespace sigmatau::detail
