// Channel values in an unlinked temporary file (see analysis_spill.hpp).
#include "analysis_spill.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "phase_spill.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau::detail {

ValueSpill::ValueSpill(const std::string& directory)
    : directory_(temporary_directory(directory)) {
  fd_ = open_unlinked_temporary(directory_, "values");
  buffer_.reserve(static_cast<std::size_t>(kReadValues));
}

ValueSpill::~ValueSpill() {
  if (fd_ >= 0) close(fd_);
}

ValueSpill::ValueSpill(ValueSpill&& other) noexcept
    : fd_(other.fd_), directory_(std::move(other.directory_)), size_(other.size_),
      buffer_(std::move(other.buffer_)) {
  other.fd_ = -1;
}

void ValueSpill::append(std::span<const double> values) {
  for (const double v : values) {
    buffer_.push_back(v);
    if (static_cast<std::int64_t>(buffer_.size()) == kReadValues) flush();
  }
}

void ValueSpill::flush() {
  const auto* bytes = reinterpret_cast<const char*>(buffer_.data());
  std::size_t left = buffer_.size() * sizeof(double);
  off_t offset = static_cast<off_t>(size_) * static_cast<off_t>(sizeof(double));
  while (left > 0) {
    const ssize_t wrote = pwrite(fd_, bytes, left, offset);
    if (wrote < 0 && errno == EINTR) continue;
    if (wrote <= 0) {
      throw Error("cannot write the log's values to a temporary file in " + directory_ + ": " +
                  std::strerror(errno) + " (free some space or choose another directory with TMPDIR)");
    }
    bytes += wrote;
    left -= static_cast<std::size_t>(wrote);
    offset += wrote;
  }
  size_ += static_cast<std::int64_t>(buffer_.size());
  buffer_.clear();
}

void ValueSpill::for_each(std::int64_t begin, std::int64_t end,
                          const std::function<void(std::span<const double>)>& each) const {
  if (begin < 0 || end > size_ || begin > end) {
    throw Error("internal: values [" + std::to_string(begin) + ", " + std::to_string(end) +
                ") outside the temporary file's " + std::to_string(size_));
  }
  std::vector<double> piece(static_cast<std::size_t>(std::min(kReadValues, end - begin)));
  while (begin < end) {
    const std::int64_t count = std::min(kReadValues, end - begin);
    auto* bytes = reinterpret_cast<char*>(piece.data());
    std::size_t left = static_cast<std::size_t>(count) * sizeof(double);
    off_t offset = static_cast<off_t>(begin) * static_cast<off_t>(sizeof(double));
    while (left > 0) {
      const ssize_t got = pread(fd_, bytes, left, offset);
      if (got < 0 && errno == EINTR) continue;
      if (got <= 0) {
        throw Error("cannot read back the log's values from a temporary file in " + directory_ +
                    ": " + (got == 0 ? std::string("unexpected end") : std::strerror(errno)));
      }
      bytes += got;
      left -= static_cast<std::size_t>(got);
      offset += got;
    }
    each(std::span<const double>(piece.data(), static_cast<std::size_t>(count)));
    begin += count;
  }
}

}  // namespace sigmatau::detail
