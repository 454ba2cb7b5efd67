#pragma once
// Internal: the text (CSV / TSV / whitespace) log parser behind LogReader. Format rules are
// listed once in sigmatau/log_reader.hpp.
#include <cstdint>
#include <string>
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
