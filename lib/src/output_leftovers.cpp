// Nothing left behind: the interrupt clean-up table (temporary files, scratch trees, child
// processes, all undone from a signal handler), the locks that mark a temporary name as live,
// the removal of abandoned ones (kill -9, a power cut), and the claim of an output name by a
// rename that never replaces.
#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <thread>
#include <vector>

#include "output_internal.hpp"
#include "sigmatau/output_file.hpp"

namespace sigmatau {
namespace {

// Paths of the open temporary files and scratch trees, readable from a signal handler: a slot is
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

// Child processes (gnuplot) that write into a scratch tree: killed and reaped first, so that
// none writes a file after the tree was emptied. 0 is a free slot.
constexpr std::size_t kChildSlots = 8;  // one gnuplot at a time per plotting thread
std::array<std::atomic<pid_t>, kChildSlots> child_slots{};
static_assert(std::atomic<pid_t>::is_always_lock_free);

// A scratch tree is flat (plot data and gnuplot's files) or nearly so (a report directory whose
// file names hold a '/'); deeper levels are left, and the tree with them.
constexpr int kTreeDepth = 8;
// Passes over a directory until one removes nothing: entries removed while getdents64 reads
// may be skipped by it, and a thread of the dying process may still add one.
constexpr int kTreePasses = 4;

/// Removes everything inside the directory open at `fd`, subdirectories to `depth` levels.
/// Async-signal-safe: getdents64, unlinkat, openat and close are system calls.
void empty_directory_at(int fd, int depth) noexcept {
  alignas(struct dirent64) char buffer[2048];
  for (int pass = 0; pass < kTreePasses; ++pass) {
    bool removed = false;
    if (::lseek(fd, 0, SEEK_SET) != 0) return;
    for (;;) {
      const ssize_t n = ::getdents64(fd, buffer, sizeof buffer);
      if (n <= 0) break;
      for (ssize_t offset = 0; offset < n;) {
        const auto* entry = reinterpret_cast<const struct dirent64*>(buffer + offset);
        offset += entry->d_reclen;
        const char* name = entry->d_name;
        if (name[0] == '.' && (name[1] == '\0' || (name[1] == '.' && name[2] == '\0'))) continue;
        if (::unlinkat(fd, name, 0) == 0) {
          removed = true;
          continue;
        }
        if (errno != EISDIR && errno != EPERM) continue;  // Linux says EISDIR, POSIX EPERM
        if (depth > 0) {
          const int sub = ::openat(fd, name, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
          if (sub >= 0) {
            empty_directory_at(sub, depth - 1);
            ::close(sub);
          }
        }
        if (::unlinkat(fd, name, AT_REMOVEDIR) == 0) removed = true;
      }
    }
    if (!removed) return;
  }
}

/// Removes the tree at `path` if it is a directory (a symbolic link is never followed).
void remove_tree(const char* path) noexcept {
  const int fd = ::open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return;
  empty_directory_at(fd, kTreeDepth);
  ::close(fd);
  ::rmdir(path);
}

bool same_file(const struct stat& a, const struct stat& b) {
  return a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

/// flock(2) with LOCK_EX and `extra` flags, retried when a signal interrupts it. 0 or an errno.
int exclusive_lock(int fd, int extra) {
  while (::flock(fd, LOCK_EX | extra) != 0) {
    if (errno != EINTR) return errno;
  }
  return 0;
}

/// Removes the file or directory at `path` when nothing holds its lock (its writer is gone).
void remove_if_abandoned(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) return;
  struct stat opened {
  }, named{};
  const bool ours =
      ::fstat(fd, &opened) == 0 && (S_ISREG(opened.st_mode) || S_ISDIR(opened.st_mode));
  // Taken: the writer is gone. Held (EWOULDBLOCK): a live run's. No locks on this file system:
  // cannot tell, so kept.
  if (ours && exclusive_lock(fd, LOCK_NB) == 0 && ::lstat(path.c_str(), &named) == 0 &&
      same_file(opened, named)) {
    if (S_ISDIR(opened.st_mode)) {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    } else {
      ::unlink(path.c_str());
    }
  }
  ::close(fd);
}

bool all_of(std::string_view text, int (*test)(int)) {
  for (const char c : text) {
    if (!test(static_cast<unsigned char>(c))) return false;
  }
  return true;
}

}  // namespace

int detail::track_pending_path(const std::filesystem::path& path) {
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

void detail::untrack_pending_path(int slot) {
  if (slot >= 0) pending_slots[static_cast<std::size_t>(slot)].state.store(kFree);
}

void remove_pending_temporaries() noexcept {
  // Writers first: a child killed and reaped adds no file to a tree after it was emptied.
  for (auto& slot : child_slots) {
    const pid_t pid = slot.load(std::memory_order_acquire);
    if (pid <= 0) continue;
    ::kill(pid, SIGKILL);
    while (::waitpid(pid, nullptr, 0) < 0 && errno == EINTR) {
    }
  }
  for (auto& slot : pending_slots) {
    if (slot.state.load(std::memory_order_acquire) == kArmed) ::unlink(slot.path.data());
  }
  // Directories last, with everything in them (a finished plot, gnuplot's log: whatever was
  // made there, tracked by name or not).
  for (auto& slot : pending_slots) {
    if (slot.state.load(std::memory_order_acquire) == kArmed) remove_tree(slot.path.data());
  }
}

InterruptCleanup::InterruptCleanup(const std::filesystem::path& path)
    : slot_(detail::track_pending_path(path)) {}

InterruptCleanup::~InterruptCleanup() { detail::untrack_pending_path(slot_); }

KillOnInterrupt::KillOnInterrupt(int pid) {
  if (pid <= 0) return;
  for (std::size_t i = 0; i < kChildSlots; ++i) {
    pid_t expected = 0;
    if (child_slots[i].compare_exchange_strong(expected, static_cast<pid_t>(pid))) {
      slot_ = static_cast<int>(i);
      return;
    }
  }
}

KillOnInterrupt::~KillOnInterrupt() {
  if (slot_ >= 0) child_slots[static_cast<std::size_t>(slot_)].store(0);
}

namespace detail {

int rename_without_replacing(const std::filesystem::path& from, const std::filesystem::path& to) {
  if (::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE) == 0) return 0;
  if (errno != EINVAL && errno != ENOSYS && errno != EOPNOTSUPP) return errno;
  // No RENAME_NOREPLACE on this file system: link(2) fails on an existing name too.
  if (::link(from.c_str(), to.c_str()) == 0) {
    ::unlink(from.c_str());
    return 0;
  }
  if (errno == EEXIST) return EEXIST;
  // Nor hard links (a directory, or a file system without them): checked, then renamed.
  struct stat existing {};
  if (::lstat(to.c_str(), &existing) == 0) return EEXIST;
  return ::rename(from.c_str(), to.c_str()) == 0 ? 0 : errno;
}

bool lock_as_live(int fd, const std::filesystem::path& path) {
  const int failure = exclusive_lock(fd, 0);
  if (failure != 0) return true;  // no locks here (ENOLCK, EOPNOTSUPP): kept unlocked
  struct stat opened {
  }, named{};
  return ::fstat(fd, &opened) == 0 && ::lstat(path.c_str(), &named) == 0 &&
         same_file(opened, named);
}

bool is_leftover_name(std::string_view name, std::string_view base) {
  if (!name.starts_with(base)) return false;
  name.remove_prefix(base.size());
  constexpr std::string_view kTmp = ".tmp-", kPartial = ".partial-", kOld = ".old";
  constexpr std::size_t kRandom = 6;  // the random part: "%06x", or mkdtemp's XXXXXX
  if (name.starts_with(kTmp)) {
    name.remove_prefix(kTmp.size());
    return name.size() == kRandom && all_of(name, isxdigit);
  }
  if (!name.starts_with(kPartial)) return false;
  name.remove_prefix(kPartial.size());
  if (name.size() == kRandom + kOld.size() && name.ends_with(kOld)) name.remove_suffix(kOld.size());
  return name.size() == kRandom && all_of(name, isalnum);
}

void remove_abandoned_leftovers(const std::filesystem::path& directory, std::string_view base) {
  std::error_code ec;
  std::filesystem::directory_iterator it(directory, ec);
  if (ec) return;
  std::vector<std::filesystem::path> leftovers;  // collected first: removing while iterating
  for (const auto end = std::filesystem::directory_iterator(); it != end; it.increment(ec)) {
    if (ec) break;
    if (is_leftover_name(it->path().filename().native(), base)) leftovers.push_back(it->path());
  }
  for (const auto& path : leftovers) remove_if_abandoned(path);
}

void hold_commit_for_tests(const std::filesystem::path& target) {
  const char* text = std::getenv("SIGMATAU_TEST_HOLD_COMMIT");
  if (text == nullptr) return;
  const std::string_view hook(text);
  const std::size_t colon = hook.find(':');
  if (colon == std::string_view::npos || target.filename() != hook.substr(0, colon)) return;
  const std::string file(hook.substr(colon + 1));
  constexpr auto kPoll = std::chrono::milliseconds(10);
  constexpr int kPolls = 6000;  // 60 s: a test that forgot to release it still ends
  for (int i = 0; i < kPolls && ::access(file.c_str(), F_OK) != 0; ++i) {
    std::this_thread::sleep_for(kPoll);
  }
}

}  // namespace detail
}  // namespace sigmatau
