// Atomic output: temp file in the target's directory + fsync + rename(2); devices, FIFOs and
// open descriptors written straight into; symbolic links followed, never replaced.
#include "sigmatau/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <string_view>

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

// Temporary names of the open AtomicOutputFiles, readable from a signal handler: a slot is
// claimed (free -> busy) with a compare-exchange, its name copied, then published (armed);
// remove_pending_temporaries() only reads armed slots. Lock-free atomics are async-signal-safe.
constexpr std::size_t kPendingSlots = 32;        // far more outputs than any verb has open at once
constexpr std::size_t kPendingPathBytes = 4096;  // PATH_MAX on Linux, with its NUL
enum SlotState : int { kFree = 0, kBusy = 1, kArmed = 2 };
struct PendingSlot {
  std::atomic<int> state{kFree};
  std::array<char, kPendingPathBytes> path{};
};
std::array<PendingSlot, kPendingSlots> pending_slots;
static_assert(std::atomic<int>::is_always_lock_free);

/// Slot index holding `path`, or -1 when the name is too long or every slot is taken.
int track_pending(const std::filesystem::path& path) {
  const std::string& name = path.native();
  if (name.size() >= kPendingPathBytes) return -1;
  for (std::size_t i = 0; i < kPendingSlots; ++i) {
    int expected = kFree;
    if (!pending_slots[i].state.compare_exchange_strong(expected, kBusy)) continue;
    std::memcpy(pending_slots[i].path.data(), name.c_str(), name.size() + 1);
    pending_slots[i].state.store(kArmed, std::memory_order_release);
    return static_cast<int>(i);
  }
  return -1;
}

void untrack_pending(int slot) {
  if (slot >= 0) pending_slots[static_cast<std::size_t>(slot)].state.store(kFree);
}

// What an output path names, after following the symbolic links of its last component.
enum class TargetKind {
  absent,          // nothing there yet (or unreachable: the directory checks report why)
  regular,         // a regular file: replaced atomically with --force
  directory,       // refused
  device_or_pipe,  // a character device or FIFO (or another process's descriptor): opened
  descriptor,      // one of this process's open descriptors (/dev/stdout, /dev/fd/N): dup'ed
  socket,          // refused: open(2) cannot write one
  block_device,    // refused: a disk is never an output
};

struct Target {
  std::filesystem::path path;  // the path with the links of its last component followed
  TargetKind kind = TargetKind::absent;
  int descriptor = -1;  // for TargetKind::descriptor
};

// Symbolic links followed before giving up (Linux's own limit, MAXSYMLINKS, is 40).
constexpr int kMaxLinks = 40;

std::filesystem::path directory_of(const std::filesystem::path& path) {
  return path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
}

// "a/b/" names "a/b" (shell completion types directories with the slash).
std::filesystem::path without_trailing_separator(std::filesystem::path path) {
  if (!path.has_filename() && path.has_relative_path()) path = path.parent_path();
  return path;
}

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

// "PATH" or, when links led elsewhere, "PATH (-> TARGET)", for messages.
std::string describe(const std::filesystem::path& requested, const Target& target) {
  if (target.path == without_trailing_separator(requested)) return requested.string();
  return requested.string() + " (-> " + target.path.string() + ")";
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

// check_can_create_in naming `shown` (the path as the user gave it, with where its links led).
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

}  // namespace

void remove_pending_temporaries() noexcept {
  for (auto& slot : pending_slots) {
    if (slot.state.load(std::memory_order_acquire) == kArmed) ::unlink(slot.path.data());
  }
  // Directories last, once their tracked files are gone (rmdir fails on a file or a directory
  // that is not empty, and leaves it).
  for (auto& slot : pending_slots) {
    if (slot.state.load(std::memory_order_acquire) == kArmed) ::rmdir(slot.path.data());
  }
}

InterruptCleanup::InterruptCleanup(const std::filesystem::path& path)
    : slot_(track_pending(path)) {}

InterruptCleanup::~InterruptCleanup() { untrack_pending(slot_); }

void check_can_create_in(const std::filesystem::path& path) {
  check_can_create_in(path, path.string());
}

namespace {

// check_can_write on a target already resolved (the constructor below resolves it once).
void check_can_write_target(const std::filesystem::path& path, const Target& target,
                            bool overwrite) {
  refuse_unwritable_kinds(path, target);
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
  check_can_create_in(target.path, describe(path, target));
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

std::filesystem::path check_output_directory(const std::filesystem::path& dir, bool overwrite) {
  const Target target = resolve_target(dir);
  switch (target.kind) {
    case TargetKind::absent:
      break;
    case TargetKind::directory:
    case TargetKind::regular:  // replaced by the directory with --force, as before
      if (!overwrite) throw Error(describe(dir, target) + " exists; use --force to replace it");
      break;
    default:
      throw Error("cannot write " + describe(dir, target) +
                  ": it is a device, pipe or socket; expected a directory name");
  }
  check_can_create_in(target.path, describe(dir, target));
  return target.path;
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
  temporary_ = temporary_name(target_);
  // Tracked before the file exists, so an interrupt never finds it created but unknown.
  pending_slot_ = track_pending(temporary_);
  fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    const std::string reason = errno_text();
    untrack_pending(pending_slot_);
    throw Error("cannot write " + path_.string() + ": " + reason);
  }
}

AtomicOutputFile::~AtomicOutputFile() {
  untrack_pending(pending_slot_);
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
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) throw Error("cannot write " + path_.string() + ": " + errno_text());
  // Re-check just before the rename so a file created meanwhile is not replaced silently.
  std::error_code ec;
  if (!overwrite_ && std::filesystem::exists(target_, ec)) {
    throw Error(path_.string() + " exists; use --force to overwrite it");
  }
  if (::rename(temporary_.c_str(), target_.c_str()) != 0) {
    throw Error("cannot rename into " + path_.string() + ": " + errno_text());
  }
  // Untracked at once: the temporary name is gone, and a later interrupt must not unlink a
  // file of that name that something else might create.
  untrack_pending(pending_slot_);
  pending_slot_ = -1;
  committed_ = true;
}

void write_file_atomically(const std::filesystem::path& path, std::string_view content,
                           bool overwrite) {
  AtomicOutputFile file(path, overwrite);
  file.write(content);
  file.commit();
}

}  // namespace sigmatau
