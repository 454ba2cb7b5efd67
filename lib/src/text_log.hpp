#pragma once
// Internal: the text (CSV / TSV / whitespace) log parser behind LogReader. Format rules are
// listed once in sigmatau/log_reader.hpp.
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "byte_source.hpp"
#include "log_internal.hpp"

namespace sigmatau::detail {

class TextLog {
 public:
  /// Reads up to the first data row: detects header and delimiter, resolves the columns.
  TextLog(ByteSource& source, const LogOptions& options, std::size_t buffer_bytes,
          TimingAccumulator& timing);

  const ColumnSelection& selection() const { return selection_; }

  /// Appends up to max_rows rows to `block` (values sized to the channels, t_s when timed).
  /// Returns the number of rows appended; 0 at the end of the input.
  std::int64_t read_rows(SampleBlock& block, std::int64_t max_rows);

 private:
  enum class Mode { delimited, whitespace };
  /// Of the rows looked at ahead, how many hold a number in a column.
  struct RowCount {
    std::int64_t rows = 0;
    std::int64_t numbers = 0;
  };
  /// Rows looked at after the first data row to tell a data column with a bad first field from
  /// a text column: enough for a clear majority, few enough to cost nothing (one buffer at most).
  static constexpr std::int64_t kLookaheadRows = 1000;

  /// A preamble line before the header: its first blank-separated field ends in ':' ("Type:",
  /// "File:"); a data row's first field is a number, a header's a name.
  static bool is_preamble_line(const char* b, const char* e);
  /// Reads "Type: Phase|Freq" and "Tau: <seconds>" (Stable32 data files) into `notes`.
  static void read_declaration(const char* b, const char* e, TextHeader& notes);
  /// A number written with a decimal comma: "1,288185", "-0,5e-3".
  static bool has_decimal_comma(std::string_view field);
  [[noreturn]] void fail_decimal_comma(std::int64_t line, std::size_t column,
                                       std::string_view field, const std::string& name) const;
  /// For each of `columns`, how many of the next kLookaheadRows content rows (those in the
  /// buffer, topped up by one read) hold a number there; begin_ must be at the first data row.
  /// A field with a decimal comma is an error.
  std::vector<RowCount> numbers_in_rows_ahead(const std::vector<std::size_t>& columns,
                                              const std::function<std::string(std::size_t)>& label);
  /// A column found by name is taken as the time column when at least this share of the
  /// intervals looked at increase: a time column's all do but after a logger restart, a
  /// temperature column named T goes up and down and repeats its quantized values.
  static constexpr double kIncreasingShare = 0.9;
  /// Whether `column` increases from the first data row (at begin_) through the rows ahead.
  bool increases_ahead(std::size_t column);
  /// Calls each(line, fields) for the next kLookaheadRows content rows of the full width in the
  /// buffer (topped up by one read), begin_ being at the first data row.
  void scan_rows_ahead(
      const std::function<void(std::int64_t, const std::vector<std::string_view>&)>& each);

  bool next_line(const char*& b, const char*& e);
  bool next_content_line(const char*& b, const char*& e);
  void refill();
  template <Mode M>
  std::int64_t read_rows_as(SampleBlock& block, std::int64_t max_rows);
  template <Mode M>
  bool parse_row(const char* b, const char* e);
  double number_or_fail(const char* b, const char* e, std::size_t field) const;
  void time_or_fail(const char* b, const char* e, std::size_t field);
  [[noreturn]] void fail_nonfinite() const;
  [[noreturn]] void fail_ragged(const char* b, const char* e) const;
  [[noreturn]] void fail(std::int64_t line, std::int64_t column, const std::string& message) const;

  ByteSource& source_;
  TimingAccumulator& timing_;
  NonFinitePolicy nonfinite_;
  std::size_t block_bytes_;
  std::vector<char> buffer_;
  const char* begin_ = nullptr;  // first unread byte
  const char* end_ = nullptr;    // end of valid data
  bool eof_ = false;
  std::int64_t line_ = 0;  // lines returned by next_line so far (= 1-based current line)
  Mode mode_ = Mode::delimited;
  char delimiter_ = ',';
  std::size_t fields_ = 0;  // fields per row
  ColumnSelection selection_;
  std::vector<double> row_;  // one parsed row, per channel
  TimeStamp stamp_;
};

}  // namespace sigmatau::detail
