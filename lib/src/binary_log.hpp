#pragma once
// Internal: raw interleaved binary samples (i16 | i32 | f32 | f64, little or big endian) behind
// LogReader.
#include <cstdint>
#include <vector>

#include "byte_source.hpp"
#include "log_internal.hpp"

namespace sigmatau::detail {

class BinaryLog {
 public:
  /// Skips the header and checks that at least one byte of samples follows.
  BinaryLog(ByteSource& source, const LogOptions& options, std::size_t buffer_bytes,
            TimingAccumulator& timing);

  const ColumnSelection& selection() const { return selection_; }

  /// Appends up to max_rows records to `block`; returns the count, 0 at the end.
  std::int64_t read_rows(SampleBlock& block, std::int64_t max_rows);

  /// Records still to read, from the file's size (a plain file, not gzip or a pipe), or -1 when
  /// the input does not tell. An upper bound on the rows to come (skipped non-finite rows and a
  /// file that grows aside).
  std::int64_t records_left() const;

 private:
  bool fill();
  /// read_rows' loop: `rows` counts the records kept so far (also when it throws).
  void read_records(SampleBlock& block, std::int64_t max_rows, std::int64_t& rows);
  template <class T, bool kSwap>
  std::int64_t decode(SampleBlock& block, std::int64_t records);

  ByteSource& source_;
  TimingAccumulator& timing_;
  NonFinitePolicy nonfinite_;
  BinaryFormat format_;
  bool swap_;
  std::size_t value_bytes_;
  std::size_t record_bytes_;
  std::int64_t skip_bytes_;
  std::vector<char> buffer_;
  std::size_t pos_ = 0;
  std::size_t end_ = 0;
  bool eof_ = false;
  std::int64_t records_ = 0;  // complete records consumed (kept or skipped)
  ColumnSelection selection_;
  std::vector<double> row_;
};

}  // namespace sigmatau::detail
