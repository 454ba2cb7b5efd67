#pragma once
// Internal: a small work-sharing loop for the channel-parallel estimators.

#include <cstddef>
#include <functional>

namespace sigmatau::detail {

/// Calls work(i) once for every i in [0, items) on min(threads, items) threads (threads 0: one
/// per core; 1: on the calling thread), items taken in order as threads free up. An exception
/// from work(i) does not stop the other items; after all have run, the first one caught is
/// rethrown.
void for_each_item_parallel(std::size_t items, unsigned threads,
                            const std::function<void(std::size_t)>& work);

}  // namespace sigmatau::detail
