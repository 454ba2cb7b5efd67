#pragma once
// Internal: a small work-sharing loop for the channel-parallel estimators.

#include <cstddef>
#include <functional>
#include <type_traits>
#include <vector>

namespace sigmatau::detail {

/// Calls work(i) once for every i in [0, items) on min(threads, items) threads (threads 0: one
/// per core; 1: on the calling thread), items taken in order as threads free up. An exception
/// from work(i) does not stop the other items; after all have run, the first one caught is
/// rethrown.
void for_each_item_parallel(std::size_t items, unsigned threads,
                            const std::function<void(std::size_t)>& work);

/// result[c][s] = curve(c, s) for every channel c < channels and statistic s < statistics.
/// The work items are the (channel, statistic) pairs, spread by for_each_item_parallel over
/// `threads`, so that a few channels with several statistics still keep every core busy.
/// Throws like for_each_item_parallel.
template <class Curve>
auto curves_per_channel_and_statistic(std::size_t channels, std::size_t statistics,
                                      unsigned threads, Curve&& curve) {
  using Result = std::invoke_result_t<Curve&, std::size_t, std::size_t>;
  std::vector<std::vector<Result>> result(channels, std::vector<Result>(statistics));
  for_each_item_parallel(channels * statistics, threads, [&](std::size_t i) {
    result[i / statistics][i % statistics] = curve(i / statistics, i % statistics);
  });
  return result;
}

}  // namespace sigmatau::detail
