// Atomic output: temp file in the target's directory (locked while its writer lives) + fsync +
// rename(2), which without --force never replaces; devices, FIFOs and open descriptors written
// straight into; symbolic links followed, never replaced; inputs never written.
#include "sigmatau/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <string_view>

#include "output_internal.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau {

using detail::describe;
using detail::directory_of;
using detail::resolve_target;
using detail::Target;
using detail::TargetKind;
using detail::without_trailing_separator;

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

// Symbolic links followed before giving up (Linux's own limit, MAXSYMLINKS, is 40).
constexpr int kMaxLinks = 40;

// Parses "<digits>" at `text`'s start; the number (or -1) and what follows.
long leading_number(std::string_view& text) {
  std::size_t n = 0;
  while (n < text.size() && n < 9 && text[n] >= '0' && text[n] <= '9') ++n;
  if (n == 0) return -1;
  const long value = std::stol(std::string(text.substr(0, n)));
  text.remove_prefix(n);
  return value;
}

// True when `path` is an entry of a /proc/<pid>/fd (or /proc/<pid>/task/<tid>/fd) directory,
// which is what /dev/stdout, /dev/fd/N and a shell's process substitution lead to: `pid` and
// `descriptor` then say whose descriptor and which.
bool descriptor_entry(const std::filesystem::path& path, long& pid, int& descriptor) {
  const std::filesystem::path filename = path.filename();  // the view below must not outlive it
  std::string_view name = filename.native();
  const long number = leading_number(name);
  if (number < 0 || !name.empty()) return false;
  char resolved[PATH_MAX];
  if (::realpath(directory_of(path).c_str(), resolved) == nullptr) return false;
  std::string_view dir(resolved);
  if (!dir.starts_with("/proc/")) return false;
  dir.remove_prefix(6);
  pid = leading_number(dir);
  if (pid < 0) return false;
  if (dir.starts_with("/task/")) {
    dir.remove_prefix(6);
    if (leading_number(dir) < 0) return false;
  }
  if (dir != "/fd") return false;
  descriptor = static_cast<int>(number);
  return true;
}

// The refusals every kind of output shares: a socket and a block device.
void refuse_unwritable_kinds(const std::filesystem::path& requested, const Target& target) {
  if (target.kind == TargetKind::socket) {
    throw Error("cannot write " + describe(requested, target) +
                ": it is a socket; expected a file, a device or a pipe");
  }
  if (target.kind == TargetKind::block_device) {
    throw Error("cannot write " + describe(requested, target) +
                ": it is a block device; expected a file, a character device or a pipe");
  }
}

// Early checks of a target written straight into: the descriptor is open for writing, or the
// device / FIFO is writable by this user. Opens nothing.
void check_direct_target(const std::filesystem::path& requested, const Target& target) {
  if (target.kind == TargetKind::descriptor) {
    const int flags = ::fcntl(target.descriptor, F_GETFL);
    if (flags < 0) {
      throw Error("cannot write " + requested.string() + ": file descriptor " +
                  std::to_string(target.descriptor) + " is not open");
    }
    if ((flags & O_ACCMODE) == O_RDONLY) {
      throw Error("cannot write " + requested.string() + ": file descriptor " +
                  std::to_string(target.descriptor) + " is open for reading only");
    }
    return;
  }
  if (::access(target.path.c_str(), W_OK) != 0) {
    throw Error("cannot write " + describe(requested, target) + ": " + errno_text());
  }
}

}  // namespace

namespace detail {

std::filesystem::path directory_of(const std::filesystem::path& path) {
  return path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
}

std::filesystem::path without_trailing_separator(std::filesystem::path path) {
  if (!path.has_filename() && path.has_relative_path()) path = path.parent_path();
  return path;
}

Target resolve_target(const std::filesystem::path& requested) {
  std::filesystem::path current = without_trailing_separator(requested);
  for (int links = 0; links <= kMaxLinks; ++links) {
    long pid = -1;
    int descriptor = -1;
    if (descriptor_entry(current, pid, descriptor)) {
      // Our own: used as it is open (its offset, O_APPEND, even a socket); another process's
      // is opened by its name like a device.
      if (pid == static_cast<long>(::getpid()))
        return {current, TargetKind::descriptor, descriptor};
      return {current, TargetKind::device_or_pipe};
    }
    struct stat status {};
    if (::lstat(current.c_str(), &status) != 0) return {current, TargetKind::absent};
    if (S_ISLNK(status.st_mode)) {
      std::array<char, PATH_MAX> buffer{};
      const ssize_t n = ::readlink(current.c_str(), buffer.data(), buffer.size() - 1);
      if (n <= 0) return {current, TargetKind::absent};
      const std::filesystem::path link(std::string(buffer.data(), static_cast<std::size_t>(n)));
      current =
          link.is_absolute() || !current.has_parent_path() ? link : current.parent_path() / link;
      continue;
    }
    if (S_ISREG(status.st_mode)) return {current, TargetKind::regular};
    if (S_ISDIR(status.st_mode)) return {current, TargetKind::directory};
    if (S_ISCHR(status.st_mode) || S_ISFIFO(status.st_mode)) {
      return {current, TargetKind::device_or_pipe};
    }
    if (S_ISSOCK(status.st_mode)) return {current, TargetKind::socket};
    return {current, TargetKind::block_device};
  }
  throw Error("cannot write " + requested.string() + ": Too many levels of symbolic links");
}

std::string describe(const std::filesystem::path& requested, const Target& target) {
  if (target.path == without_trailing_separator(requested)) return requested.string();
  return requested.string() + " (-> " + target.path.string() + ")";
}

void check_can_create_in(const std::filesystem::path& path, const std::string& shown) {
  std::error_code ec;
  std::filesystem::path directory = directory_of(without_trailing_separator(path));
  while (!std::filesystem::exists(directory, ec) && directory != directory_of(directory)) {
    directory = directory_of(directory);
  }
  if (!std::filesystem::exists(directory, ec)) return;  // left to the write to report
  if (!std::filesystem::is_directory(directory, ec)) {
    // The wording of create_directories' own failure, which this only brings forward.
    throw Error("cannot create directory " + directory.string() + ": Not a directory");
  }
  if (::access(directory.c_str(), W_OK | X_OK) != 0) {
    throw Error("cannot write " + shown + ": " + errno_text() + " (directory " +
                directory.string() + ")");
  }
}

}  // namespace detail

void check_can_create_in(const std::filesystem::path& path) {
  detail::check_can_create_in(path, path.string());
}

namespace {

// check_can_write on a target already resolved (the constructor below resolves it once).
void check_can_write_target(const std::filesystem::path& path, const Target& target,
                            bool overwrite) {
  refuse_unwritable_kinds(path, target);
  detail::refuse_input_target(path, target);  // before "use --force", which would not help
  switch (target.kind) {
    case TargetKind::descriptor:
    case TargetKind::device_or_pipe:
      check_direct_target(path, target);
      return;
    case TargetKind::directory:
      throw Error(describe(path, target) + " is a directory; expected a file name");
    case TargetKind::regular:
      if (!overwrite) throw Error(describe(path, target) + " exists; use --force to overwrite it");
      break;
    default:
      break;
  }
  detail::check_can_create_in(target.path, describe(path, target));
}

bool written_straight_into(TargetKind kind) {
  return kind == TargetKind::descriptor || kind == TargetKind::device_or_pipe;
}

}  // namespace

void check_can_write(const std::filesystem::path& path, bool overwrite) {
  check_can_write_target(path, resolve_target(path), overwrite);
}

bool is_stream_output(const std::filesystem::path& path) {
  return written_straight_into(resolve_target(path).kind);
}

AtomicOutputFile::AtomicOutputFile(std::filesystem::path path, bool overwrite)
    : path_(std::move(path)), overwrite_(overwrite) {
  const Target target = resolve_target(path_);
  check_can_write_target(path_, target, overwrite_);
  target_ = target.path;
  if (written_straight_into(target.kind)) {
    // Straight in: writing to a device or pipe replaces nothing, and renaming over one would
    // destroy it (as root, /dev/null became a regular file).
    fd_ = target.kind == TargetKind::descriptor
              ? ::fcntl(target.descriptor, F_DUPFD_CLOEXEC, 0)
              : ::open(target_.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
    if (fd_ < 0) throw Error("cannot write " + describe(path_, target) + ": " + errno_text());
    return;
  }
  const std::filesystem::path directory = directory_of(target_);
  std::error_code ec;
  std::filesystem::create_directories(directory, ec);
  if (ec) throw Error("cannot create directory " + directory.string() + ": " + ec.message());
  // What a run killed outright (kill -9, a power cut) left beside this target goes; a live
  // run's temporary file is locked and kept.
  detail::remove_abandoned_leftovers(directory, target_.filename().native());
  // A new name when the lock finds the file gone (taken for abandoned between its creation and
  // the lock, by another run's tidying): at most this many tries.
  constexpr int kTries = 4;
  for (int attempt = 0; attempt < kTries && fd_ < 0; ++attempt) {
    temporary_ = temporary_name(target_);
    // Tracked before the file exists, so an interrupt never finds it created but unknown.
    pending_slot_ = detail::track_pending_path(temporary_);
    fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd_ < 0) {
      const std::string reason = errno_text();
      detail::untrack_pending_path(pending_slot_);
      throw Error("cannot write " + path_.string() + ": " + reason);
    }
    if (detail::lock_as_live(fd_, temporary_)) break;
    ::close(fd_);
    fd_ = -1;
    detail::untrack_pending_path(pending_slot_);
    pending_slot_ = -1;
  }
  if (fd_ < 0) {
    throw Error("cannot write " + path_.string() + ": its temporary file kept vanishing");
  }
}

AtomicOutputFile::~AtomicOutputFile() {
  detail::untrack_pending_path(pending_slot_);
  if (committed_) return;
  if (fd_ >= 0) ::close(fd_);
  if (!temporary_.empty()) ::unlink(temporary_.c_str());
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
  if (temporary_.empty()) {  // a device, pipe or descriptor: nothing to flush or rename
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) throw Error("cannot write " + path_.string() + ": " + errno_text());
    committed_ = true;
    return;
  }
  if (::fsync(fd_) != 0) throw Error("cannot flush " + path_.string() + ": " + errno_text());
  // The target may have become an input (a link changed) since the constructor looked.
  detail::refuse_input_target(path_, resolve_target(path_));
  detail::hold_commit_for_tests(target_);
  if (overwrite_) {
    if (::rename(temporary_.c_str(), target_.c_str()) != 0) {
      throw Error("cannot rename into " + path_.string() + ": " + errno_text());
    }
  } else {
    // Claimed atomically: of two runs writing the same new name, one gets it, the other is told.
    const int failure = detail::rename_without_replacing(temporary_, target_);
    if (failure == EEXIST) throw Error(path_.string() + " exists; use --force to overwrite it");
    if (failure != 0) {
      throw Error("cannot rename into " + path_.string() + ": " + std::strerror(failure));
    }
  }
  // Untracked at once: the temporary name is gone, and a later interrupt must not unlink a
  // file of that name that something else might create.
  detail::untrack_pending_path(pending_slot_);
  pending_slot_ = -1;
  committed_ = true;
  // Closed after the rename: the lock marks the temporary name live until it is gone.
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) throw Error("cannot write " + path_.string() + ": " + errno_text());
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content,
                           bool overwrite) {
  AtomicOutputFile file(path, overwrite);
  file.write(content);
  file.commit();
}

}  // namespace sigmatau
