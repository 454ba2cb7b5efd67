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

void write_file_atomically(const std::filesystem::path& path, std::string_view content,
                           bool overwrite) {
  check_can_write(path, overwrite);
  const auto parent = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  std::filesystem::create_directories(parent, ec);
  if (ec) throw Error("cannot create directory " + parent.string() + ": " + ec.message());

  const auto tmp = temporary_name(path);
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) throw Error("cannot write " + path.string() + ": " + errno_text());
  auto fail = [&](const std::string& what) {
    const std::string reason = errno_text();
    ::close(fd);
    ::unlink(tmp.c_str());
    throw Error(what + " " + path.string() + ": " + reason);
  };
  const char* data = content.data();
  std::size_t left = content.size();
  while (left > 0) {
    const ssize_t written = ::write(fd, data, left);
    if (written < 0) {
      if (errno == EINTR) continue;
      fail("cannot write");
    }
    data += written;
    left -= static_cast<std::size_t>(written);
  }
  if (::fsync(fd) != 0) fail("cannot flush");
  if (::close(fd) != 0) {
    const std::string reason = errno_text();
    ::unlink(tmp.c_str());
    throw Error("cannot write " + path.string() + ": " + reason);
  }
  // Re-check just before the rename so a file created meanwhile is not replaced silently.
  if (!overwrite && std::filesystem::exists(path, ec)) {
    ::unlink(tmp.c_str());
    throw Error(path.string() + " exists; use --force to overwrite it");
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string reason = errno_text();
    ::unlink(tmp.c_str());
    throw Error("cannot rename into " + path.string() + ": " + reason);
  }
}

}  // namespace sigmatau
