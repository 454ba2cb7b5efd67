#pragma once
// The outlier (spike) check of every channel of a log for `adev` and `psd`, the check `analyze`
// runs (sigmatau::OutlierChecker, data_checks.hpp: blocks of 4096 rows, 8 robust sigma; phase
// data checked on the differences of consecutive values), with its messages. Fed a whole channel
// or block by block, it gives the same warnings bit for bit.
#include <cstddef>
#include <future>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "log_options.hpp"
#include "sigmatau/data_checks.hpp"

namespace sigmatau::cli {

/// One OutlierChecker per channel, with analyze's options; values fed in row order, in any pieces.
class ChannelOutliers {
 public:
  /// One checker per channel `names[c]`. The values fed are the samples as the verb holds them
  /// (x LoadedChannels::to_si); `units[c]` (one per channel, from channel_units_of or
  /// resolve_channel_units) labels the values in the messages in the channel's declared unit
  /// (held value x result_to_si / to_si), unlabelled when the unit is unknown. Throws Error
  /// when the sizes of `names` and `units` differ.
  ChannelOutliers(const std::vector<std::string>& names, const std::vector<ChannelUnit>& units,
                  DataKind kind);
  /// The next values of channel `channel`, in row order.
  void add(std::size_t channel, std::span<const double> values);
  /// The outlier warnings (the library's messages, e.g. "gx: 3 samples beyond 8 robust sigma
  /// ..."), in channel order; channels without outliers give none. Call once, at the end.
  std::vector<std::string> finish();

 private:
  std::vector<OutlierChecker> checkers_;
};

/// ChannelOutliers for a log read block by block (adev's stream and out-of-core paths, psd): the
/// checkers are made at the first block, once the channel names are known, with the channels'
/// units (channel_units_of, without notes). Each block is copied and checked on a worker thread
/// while the caller goes on (its own sums, the next read); blocks are checked one at a time and
/// in order, so the warnings are ChannelOutliers', bit for bit. Memory: one copy of a block.
class BlockOutliers {
 public:
  /// `background` false: every block is checked on the caller's thread (adev --threads 1).
  BlockOutliers(const LogArguments& args, DataKind kind, bool background = true);
  BlockOutliers(const BlockOutliers&) = delete;
  BlockOutliers& operator=(const BlockOutliers&) = delete;
  ~BlockOutliers();  ///< waits for the block being checked
  /// The next block of every channel `names[c]` (values as held: x LoadedChannels::to_si),
  /// checked on the worker thread, or on the caller's without a copy when not `in_background`
  /// (a large block, e.g. the rows psd holds before its segment length is known).
  void add(const std::vector<std::string>& names, const std::vector<std::vector<double>>& values,
           bool in_background = true);
  /// The warnings (ChannelOutliers::finish); none when no block was added. Call once, at the end.
  std::vector<std::string> finish();

 private:
  void wait();  ///< for the block being checked; rethrows what its check threw
  const LogArguments& args_;
  DataKind kind_;
  bool background_;
  std::optional<ChannelOutliers> outliers_;
  std::vector<std::vector<double>> copy_;  ///< the block being checked
  std::future<void> job_;                  ///< last: destroyed (joined) first
};

/// The outlier warnings of channels held in memory (samples x LoadedChannels::to_si), as
/// ChannelOutliers gives them.
std::vector<std::string> outlier_warnings(const std::vector<std::vector<double>>& channels,
                                          const std::vector<std::string>& names,
                                          const std::vector<ChannelUnit>& units, DataKind kind);

}  // namespace sigmatau::cli
