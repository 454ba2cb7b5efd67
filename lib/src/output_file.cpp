// Atomic output: temp file in the target directory + fsync + rename(2).
#include "sigmatau/output_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <random>
#include <string>

#include "sigmatau/error.hpp"

namespace sigmatau {
namespace {

std::string errno_text() { return std::strerror(errno); }

std::filesystem::path temporary_name(const std::filesystem::path& path) {
  std::random_device device;
  std::uniform_int_distribution<unsigned> digits(0, 0xFFFFFF);
  char suffix[16];
  std::snprintf(suffix, sizeof suffix, ".tmp-%06x", digits(device));
  auto name = path;
  name += suffix;
  return name;
}

}  // namespace

void check_can_write(const std::filesystem::path& path, bool overwrite) {
  std::error_code ec;
  if (!overwrite && std::filesystem::exists(path, ec)) {
    throw Error(path.string() + " exists; use --force to overwrite it");
  }
  if (std::filesystem::is_directory(path, ec)) {
    throw Error(path.string() + " is a directory; expected a file name");
  }
}

AtomicOutputFile::AtomicOutputFile(std::filesystem::path path, bool overwrite)
    : path_(std::move(path)), overwrite_(overwrite) {
  check_can_write(path_, overwrite_);
  const auto parent = path_.has_parent_path() ? path_.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  std::filesystem::create_directories(parent, ec);
  if (ec) throw Error("cannot create directory " + parent.string() + ": " + ec.message());
  temporary_ = temporary_name(path_);
  fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd_ < 0) throw Error("cannot write " + path_.string() + ": " + errno_text());
}

AtomicOutputFile::~AtomicOutputFile() {
  if (committed_) return;
  if (fd_ >= 0) ::close(fd_);
  ::unlink(temporary_.c_str());
}

void AtomicOutputFile::write(std::string_view bytes) {
  if (fd_ < 0) throw Error("cannot write " + path_.string() + ": file already closed");
  const char* data = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t written = ::write(fd_, data, left);
    if (written < 0) {
      if (errno == EINTR) continue;
      throw Error("cannot write " + path_.string() + ": " + errno_text());
    }
    data += written;
    left -= static_cast<std::size_t>(written);
  }
}

void AtomicOutputFile::commit() {
  if (fd_ < 0) throw Error("cannot write " + path_.string() + ": file already closed");
  if (::fsync(fd_) != 0) throw Error("cannot flush " + path_.string() + ": " + errno_text());
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) throw Error("cannot write " + path_.string() + ": " + errno_text());
  // Re-check just before the rename so a file created meanwhile is not replaced silently.
  std::error_code ec;
  if (!overwrite_ && std::filesystem::exists(path_, ec)) {
    throw Error(path_.string() + " exists; use --force to overwrite it");
  }
  if (::rename(temporary_.c_str(), path_.c_str()) != 0) {
    throw Error("cannot rename into " + path_.string() + ": " + errno_text());
  }
  committed_ = true;
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content,
                           bool overwrite) {
  AtomicOutputFile file(path, overwrite);
  file.write(content);
  file.commit();
}

}  // namespace sigmatau
