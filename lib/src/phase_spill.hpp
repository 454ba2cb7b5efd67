#pragma once
// Internal: the storage of a phase series (and of the arrays derived from it), either in
// anonymous memory or "spilled" to an unlinked temporary file that is memory-mapped.
//
// A spilled buffer costs no anonymous memory: its pages live in the kernel's page cache, which
// the kernel writes back and evicts as it needs. Pages of a shared file mapping that a process
// has touched still count in its resident set (RssFile), so a watchdog thread drops the mappings
// of every spilled buffer (madvise MADV_DONTNEED: the data stays in the file / page cache, the
// next access faults it back in) whenever the process's file-backed resident set exceeds a
// budget. The estimators read spilled and in-memory buffers through the same pointers, so their
// results are the same to the last bit.

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "sigmatau/phase_series.hpp"

namespace sigmatau::detail {

/// n doubles, uninitialised (anonymous pages read as 0 until written), in memory or spilled to
/// an unlinked temporary file in storage.directory (see PhaseStorage). Move-only.
class DoubleBuffer {
 public:
  DoubleBuffer() = default;
  /// Throws Error (with the directory and strerror) when the file cannot be created or the
  /// space cannot be reserved (posix_fallocate: a full disk is an error here, never a SIGBUS
  /// later), or when the mapping fails.
  DoubleBuffer(std::size_t n, const PhaseStorage& storage);
  /// n doubles in the memory of `memory` (capacity >= n; its contents are left as they are),
  /// which the buffer keeps: memory already faulted in is reused instead of fresh pages.
  DoubleBuffer(std::vector<double>&& memory, std::size_t n);
  ~DoubleBuffer();
  DoubleBuffer(DoubleBuffer&& other) noexcept;
  DoubleBuffer& operator=(DoubleBuffer&& other) noexcept;
  DoubleBuffer(const DoubleBuffer&) = delete;
  DoubleBuffer& operator=(const DoubleBuffer&) = delete;

  double* data() const { return data_; }
  std::size_t size() const { return size_; }
  bool spilled() const { return spilled_; }

 private:
  void reset() noexcept;
  double* data_ = nullptr;
  std::size_t size_ = 0;
  std::size_t mapped_bytes_ = 0;
  bool spilled_ = false;
  std::vector<double> adopted_;  // the memory of the second constructor, else empty
};

/// Does the watchdog's check now, in the calling thread: drops the mappings of every spilled
/// buffer if the file-backed resident set exceeds the budget. Loops that stream through spilled
/// buffers call it every few MiB, so the resident set stays bounded even when the watchdog
/// thread is not scheduled for a while (a loaded machine). Costs one read of /proc/self/statm.
void enforce_spill_budget();

/// The directory for temporary files: `directory` when given, else $TMPDIR, else /tmp.
std::string temporary_directory(const std::string& directory);

/// A read-write file in `directory` that has no name (O_TMPFILE, else mkostemp and unlink), so
/// the kernel frees it when the descriptor is closed, whatever way the process ends. `what`
/// names its content in the Error thrown when it cannot be created ("phase", "values").
int open_unlinked_temporary(const std::string& directory, const std::string& what);

/// File-backed resident bytes of this process (RssFile + RssShmem from /proc/self/statm), or -1
/// where that is not available.
std::int64_t file_resident_bytes();

}  // namespace sigmatau::detail
