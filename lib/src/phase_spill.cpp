// Phase storage in memory or in an unlinked, memory-mapped temporary file (see phase_spill.hpp).
#include "phase_spill.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#include "page_populate.hpp"
#include "sigmatau/error.hpp"

#include <fcntl.h>
#include <unistd.h>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace sigmatau::detail {

std::string temporary_directory(const std::string& directory) {
  if (!directory.empty()) return directory;
  const char* tmp = std::getenv("TMPDIR");
  return tmp && *tmp ? tmp : "/tmp";
}

int open_unlinked_temporary(const std::string& directory, const std::string& what) {
  int fd = -1;
#if defined(O_TMPFILE)
  fd = open(directory.c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0600);
#endif
  if (fd < 0) {
    std::string name = directory + "/sigmatau-" + what + "-XXXXXX";
    fd = mkostemp(name.data(), O_CLOEXEC);
    if (fd < 0) {
      throw Error("cannot create a temporary file in " + directory + " for the " + what + ": " +
                  std::strerror(errno) + " (choose another directory with TMPDIR)");
    }
    unlink(name.c_str());
  }
  return fd;
}

namespace {

#if defined(__linux__)

/// Watchdog that keeps the file-backed resident set of the process under a budget by dropping
/// the page mappings of every spilled buffer (see the file comment of phase_spill.hpp). It runs
/// while at least one spilled buffer exists and checks every kPeriod: at the ~1-2 GB/s a sweep
/// touches pages, the resident set can overshoot the budget by a few tens of MiB at most.
class PageReleaser {
 public:
  static PageReleaser& instance() {
    static PageReleaser releaser;
    return releaser;
  }

  void add(void* address, std::size_t bytes, std::int64_t budget) {
    std::lock_guard lock(mutex_);
    mappings_.push_back({address, bytes});
    budget_ = budget;
    if (!thread_.joinable()) {
      stop_ = false;
      try {
        thread_ = std::thread([this] { run(); });
      } catch (const std::system_error&) {
        // No thread to be had (a process at its thread limit): the loops that stream through
        // spilled buffers call enforce_spill_budget() every few MiB, which keeps the budget
        // alone, a little less promptly. Throwing here would leave this mapping listed after
        // its buffer's constructor failed.
      }
    }
  }

  /// Called before `address` is unmapped: afterwards the watchdog never touches it.
  void remove(void* address) {
    std::thread finished;
    {
      std::lock_guard lock(mutex_);
      std::erase_if(mappings_, [&](const Mapping& m) { return m.address == address; });
      if (mappings_.empty() && thread_.joinable()) {
        stop_ = true;
        finished = std::move(thread_);
      }
    }
    wake_.notify_all();
    if (finished.joinable()) finished.join();
  }

  ~PageReleaser() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
  }

 private:
  struct Mapping {
    void* address;
    std::size_t bytes;
  };
  static constexpr std::chrono::milliseconds kPeriod{5};

 public:
  /// The watchdog's check, now, from the calling thread.
  void check_now() {
    std::lock_guard lock(mutex_);
    release_if_over_budget();
  }

 private:
  void release_if_over_budget() {
    if (mappings_.empty()) return;
    const std::int64_t resident = file_resident_bytes();
    if (resident > budget_) {
      // Under the lock: remove() cannot unmap a buffer while it is being released.
      for (const Mapping& m : mappings_) madvise(m.address, m.bytes, MADV_DONTNEED);
    }
  }

  void run() {
    std::unique_lock lock(mutex_);
    while (!stop_) {
      wake_.wait_for(lock, kPeriod, [this] { return stop_; });
      if (stop_) break;
      release_if_over_budget();
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_;
  std::vector<Mapping> mappings_;
  std::int64_t budget_ = 0;
  bool stop_ = false;
  std::thread thread_;
};

std::string spill_directory(const PhaseStorage& storage) {
  return temporary_directory(storage.directory);
}

/// An unlinked file of `bytes` bytes in `dir`, with its blocks reserved.
int open_spill_file(const std::string& dir, std::size_t bytes) {
  const int fd = open_unlinked_temporary(dir, "phase");
  const int rc = posix_fallocate(fd, 0, static_cast<off_t>(bytes));
  if (rc != 0) {
    close(fd);
    throw Error("cannot reserve " + std::to_string(bytes >> 20) + " MiB in " + dir +
                " for the phase: " + std::strerror(rc) +
                " (free some space or choose another directory with TMPDIR)");
  }
  return fd;
}

#endif  // __linux__

}  // namespace

void enforce_spill_budget() {
#if defined(__linux__)
  PageReleaser::instance().check_now();
#endif
}

std::int64_t file_resident_bytes() {
#if defined(__linux__)
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return -1;
  long long size = 0, resident = 0, shared = 0;
  const int got = std::fscanf(f, "%lld %lld %lld", &size, &resident, &shared);
  std::fclose(f);
  if (got != 3) return -1;
  return shared * static_cast<std::int64_t>(sysconf(_SC_PAGESIZE));
#else
  return -1;
#endif
}

DoubleBuffer::DoubleBuffer(std::size_t n, const PhaseStorage& storage) : size_(n) {
  if (n == 0) return;
  const std::size_t bytes = n * sizeof(double);
#if defined(__linux__)
  if (storage.spill) {
    const std::string dir = spill_directory(storage);
    const int fd = open_spill_file(dir, bytes);
    void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
    const int map_errno = errno;
    close(fd);  // the mapping keeps the (unlinked) file alive
    if (p == MAP_FAILED) {
      throw Error("cannot map a " + std::to_string(bytes >> 20) + " MiB temporary file in " + dir +
                  ": " + std::strerror(map_errno));
    }
    data_ = static_cast<double*>(p);
    mapped_bytes_ = bytes;
    spilled_ = true;
    PageReleaser::instance().add(p, bytes, storage.resident_bytes);
    return;
  }
  // Anonymous pages: no zero-fill pass (fresh pages read as 0). In 4 KiB pages: MADV_HUGEPAGE
  // was measured slower end to end on the 2-core VM (adev at 1e8 samples: 4.2 s of system time
  // against 1.5 s without it, bench/results_speed.md).
  void* p = mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) throw std::bad_alloc();
  data_ = static_cast<double*>(p);
  mapped_bytes_ = bytes;
  populate_in_background(p, bytes);
#else
  if (storage.spill) throw Error("spilling the phase to a file needs Linux");
  data_ = static_cast<double*>(std::calloc(n, sizeof(double)));
  if (!data_) throw std::bad_alloc();
#endif
}

DoubleBuffer::DoubleBuffer(std::vector<double>&& memory, std::size_t n) : size_(n) {
  SIGMATAU_ASSERT(memory.capacity() >= n, "the adopted memory holds n doubles");
  adopted_ = std::move(memory);
  data_ = n > 0 ? adopted_.data() : nullptr;
}

void DoubleBuffer::reset() noexcept {
  if (!data_) return;
  if (!adopted_.empty() || adopted_.capacity() > 0) {
    std::vector<double>().swap(adopted_);
    data_ = nullptr;
    size_ = 0;
    return;
  }
#if defined(__linux__)
  if (spilled_) PageReleaser::instance().remove(data_);
  munmap(data_, mapped_bytes_);
#else
  std::free(data_);
#endif
  data_ = nullptr;
  size_ = 0;
  mapped_bytes_ = 0;
  spilled_ = false;
}

DoubleBuffer::~DoubleBuffer() { reset(); }

DoubleBuffer::DoubleBuffer(DoubleBuffer&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)),
      size_(std::exchange(other.size_, 0)),
      mapped_bytes_(std::exchange(other.mapped_bytes_, 0)),
      spilled_(std::exchange(other.spilled_, false)),
      adopted_(std::move(other.adopted_)) {}

DoubleBuffer& DoubleBuffer::operator=(DoubleBuffer&& other) noexcept {
  if (this != &other) {
    reset();
    data_ = std::exchange(other.data_, nullptr);
    size_ = std::exchange(other.size_, 0);
    mapped_bytes_ = std::exchange(other.mapped_bytes_, 0);
    spilled_ = std::exchange(other.spilled_, false);
    adopted_ = std::move(other.adopted_);
  }
  return *this;
}

}  // namespace sigmatau::detail
