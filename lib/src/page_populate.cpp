// Background page population (see page_populate.hpp).
#include "page_populate.hpp"

#include <algorithm>
#include <cerrno>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <system_error>
#include <thread>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace sigmatau::detail {
namespace {

#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
/// Smaller ranges fault in quickly enough on their own.
constexpr std::size_t kMinBytes = std::size_t{64} << 20;
/// Bytes per madvise call: the worker looks at its stop flag between calls.
constexpr std::size_t kStepBytes = std::size_t{8} << 20;

struct Range {
  std::uintptr_t begin;
  std::uintptr_t end;
};

/// One thread, a queue of ranges, populated in order, each from its start.
class Populator {
 public:
  static Populator& instance() {
    static Populator p;
    return p;
  }

  void add(void* address, std::size_t bytes) {
    const auto page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
    // Whole pages inside the range only: the pages at its edges may belong to other objects,
    // which populating would not harm, but they are not ours to touch.
    const auto first = (reinterpret_cast<std::uintptr_t>(address) + page - 1) / page * page;
    const auto last = (reinterpret_cast<std::uintptr_t>(address) + bytes) / page * page;
    if (last <= first) return;
    std::lock_guard lock(mutex_);
    if (failed_ || stop_) return;
    if (!worker_.joinable()) {
      // No thread to be had (a process or address-space limit): the pages fault in as they
      // are written, as without this file.
      try {
        worker_ = std::thread([this] { run(); });
      } catch (const std::system_error&) {
        failed_ = true;
        return;
      }
    }
    queue_.push_back({first, last});
    wake_.notify_one();
  }

  ~Populator() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_one();
    if (worker_.joinable()) worker_.join();
  }

 private:
  void run() {
    std::unique_lock lock(mutex_);
    for (;;) {
      wake_.wait(lock, [this] { return stop_ || !queue_.empty(); });
      if (stop_) return;
      Range& r = queue_.front();
      const std::uintptr_t begin = r.begin;
      const std::uintptr_t end = std::min(r.end, begin + kStepBytes);
      r.begin = end;
      if (r.begin >= r.end) queue_.pop_front();
      lock.unlock();
      const int rc = madvise(reinterpret_cast<void*>(begin), end - begin, MADV_POPULATE_WRITE);
      lock.lock();
      // EINVAL: the kernel has no MADV_POPULATE_WRITE; give up for good. Other errors (the
      // range was unmapped meanwhile, memory is short): drop that range.
      if (rc != 0) {
        if (errno == EINVAL) {
          failed_ = true;
          queue_.clear();
        } else if (!queue_.empty() && queue_.front().begin == end) {
          queue_.pop_front();
        }
      }
    }
  }

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<Range> queue_;
  std::thread worker_;
  bool stop_ = false;
  bool failed_ = false;
};
#endif

}  // namespace

void populate_in_background(void* address, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_POPULATE_WRITE)
  if (address == nullptr || bytes < kMinBytes) return;
  Populator::instance().add(address, bytes);
#else
  (void)address;
  (void)bytes;
#endif
}

}  // namespace sigmatau::detail
