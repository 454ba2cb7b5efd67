#pragma once
// Internal: the values of one channel kept in an unlinked temporary file, so that the bounded
// analyze path (analysis_bounded.cpp) reads the log itself only once and then streams each
// channel as often as its stages need (warm-up blocks, two phase passes, dynamic windows) at
// disk or page-cache speed. Written with write(2) and read back with pread(2) into small
// buffers: no mapping, so the pages stay in the kernel's page cache and out of the resident set.

#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace sigmatau::detail {

class ValueSpill {
 public:
  /// An unlinked file in `directory` (empty: $TMPDIR, else /tmp). Throws Error (with the
  /// directory and strerror) when it cannot be created.
  explicit ValueSpill(const std::string& directory);
  ~ValueSpill();
  ValueSpill(ValueSpill&& other) noexcept;
  ValueSpill& operator=(ValueSpill&&) = delete;
  ValueSpill(const ValueSpill&) = delete;
  ValueSpill& operator=(const ValueSpill&) = delete;

  /// Appends values (buffered). Throws Error when the disk is full.
  void append(std::span<const double> values);
  /// Writes out the buffer; call once after the last append.
  void flush();
  /// Values appended.
  std::int64_t size() const { return size_; }
  /// Calls each(values) on [begin, end) in order, in pieces of at most kReadValues values.
  /// Thread-safe once flushed (pread). Throws Error on a read error or a range outside the file.
  void for_each(std::int64_t begin, std::int64_t end,
                const std::function<void(std::span<const double>)>& each) const;

  /// Values per read and per write [values] (512 KiB).
  static constexpr std::int64_t kReadValues = 65536;

 private:
  int fd_ = -1;
  std::string directory_;
  std::int64_t size_ = 0;
  std::vector<double> buffer_;
};

}  // namespace sigmatau::detail
