#pragma once
// Fresh memory faulted in ahead of its first write, on a background thread.
//
// A large array the process is about to fill (a log's samples, a phase's hi and lo arrays)
// costs one page fault per 4 KiB page on first write: about a third of `adev`'s time at 1e8
// samples on the 2-core VM (bench/results_speed.md). populate_in_background() hands a range
// to one worker thread that asks the kernel to map it writable (madvise MADV_POPULATE_WRITE,
// Linux 5.14+), a few MiB at a time from its start, while the caller goes on: the writer then
// mostly finds its pages present, and the page clearing runs on the other core.
//
// Safe whatever the caller does meanwhile: populating never changes a byte (a page already
// present is left as it is, a new one reads as zero as it would have), and a range unmapped
// or reused before the worker reaches it only makes the madvise call fail or fault in pages
// that the new owner would have faulted in anyway. Without MADV_POPULATE_WRITE (another OS, an
// older kernel) or when no thread can be started (a resource limit) it does nothing.
#include <cstddef>

namespace sigmatau::detail {

/// Queues [address, address + bytes) for the worker (ranges below 64 MiB are not worth it and
/// are ignored). Returns at once.
void populate_in_background(void* address, std::size_t bytes);

}  // namespace sigmatau::detail
