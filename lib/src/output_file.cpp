// Atomic output: temp file in the target directory + fsync + rename(2).
#include "sigmatau/output_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <array>
#include <atomic>
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

InterruptCleanup::InterruptCleanup(const std::filesystem::path& path) : slot_(track_pending(path)) {}

InterruptCleanup::~InterruptCleanup() { untrack_pending(slot_); }

void check_can_create_in(const std::filesystem::path& path) {
  std::error_code ec;
  const auto up = [](const std::filesystem::path& p) {
    return p.has_parent_path() ? p.parent_path() : std::filesystem::path(".");
  };
  std::filesystem::path directory = up(path);
  while (!std::filesystem::exists(directory, ec) && directory != "." &&
         directory != directory.root_path()) {
    directory = up(directory);
  }
  if (!std::filesystem::exists(directory, ec)) return;  // left to the write to report
  if (!std::filesystem::is_directory(directory, ec)) {
    // The wording of create_directories' own failure, which this only brings forward.
    throw Error("cannot create directory " + directory.string() + ": Not a directory");
  }
  if (::access(directory.c_str(), W_OK | X_OK) != 0) {
    throw Error("cannot write " + path.string() + ": " + errno_text() + " (directory " +
                directory.string() + ")");
  }
}

void check_can_write(const std::filesystem::path& path, bool overwrite) {
  std::error_code ec;
  if (!overwrite && std::filesystem::exists(path, ec)) {
    throw Error(path.string() + " exists; use --force to overwrite it");
  }
  if (std::filesystem::is_directory(path, ec)) {
    throw Error(path.string() + " is a directory; expected a file name");
  }
  check_can_create_in(path);
}

AtomicOutputFile::AtomicOutputFile(std::filesystem::path path, bool overwrite)
    : path_(std::move(path)), overwrite_(overwrite) {
  check_can_write(path_, overwrite_);
  const auto parent = path_.has_parent_path() ? path_.parent_path() : std::filesystem::path(".");
  std::error_code ec;
  std::filesystem::create_directories(parent, ec);
  if (ec) throw Error("cannot create directory " + parent.string() + ": " + ec.message());
  temporary_ = temporary_name(path_);
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
