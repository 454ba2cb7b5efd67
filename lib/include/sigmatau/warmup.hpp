#pragma once
/// \file warmup.hpp
/// Warm-up transient detection: a sensor's bias often settles for minutes after power-on, and
/// that settling is not noise. Left in, it inflates the long-tau end of the Allan curve.
///
/// Rule (per channel, then the longest over the channels): split the log into blocks of
/// 1/kBlocks of its length; the settled level is the median of the block means of the second
/// half, and its spread the full range (max - min) of those block means. The start is a
/// transient when the first block mean lies more than kTransientFactor x that range from the
/// level; it is trimmed up to the first block whose mean is back within the range. Stationary
/// noise (white, flicker, random walk) keeps its early block means inside twice the late range in
/// all but rare cases, so an untouched log is the usual outcome. The trim never exceeds
/// kMaxTrimFraction of the log.

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sigmatau {

struct WarmupDecision {
  std::int64_t trim_samples = 0;  ///< samples to drop at the start (0: none)
  double trim_s = 0;              ///< the same in seconds
  int channel = -1;               ///< the channel that set the trim (-1: none)
  std::string reason;             ///< one sentence for the report
};

/// Looks for a settling transient at the start of each channel sampled at rate_hz.
WarmupDecision detect_warmup(const std::vector<std::span<const double>>& channels, double rate_hz);

/// The block means of one channel, what the rule looks at (empty `means`: the channel is shorter
/// than kWarmupBlocks x kMinBlockSamples and is not examined).
struct WarmupBlocks {
  std::int64_t block_samples = 0;  ///< samples per block = samples / kWarmupBlocks (rounded down)
  std::vector<double> means;       ///< kWarmupBlocks block means [unit of the samples]
};

/// The block means of a channel whose samples arrive in pieces (a log read in blocks): give the
/// channel's total length first, then add() every sample in order. means() equals what
/// detect_warmup computes on the whole channel, bit for bit (the same sums in the same order).
class WarmupBlockSums {
 public:
  /// `samples`: the channel's total length (known from an earlier pass).
  explicit WarmupBlockSums(std::int64_t samples);
  void add(std::span<const double> values);
  /// The block means once every sample was added.
  WarmupBlocks blocks() const;

 private:
  WarmupBlocks blocks_;
  double sum_ = 0;
  std::int64_t seen_ = 0;
};

/// The block means of one whole channel (WarmupBlockSums fed it at once): what detect_warmup
/// computes per channel, for callers that compute the channels apart (in parallel).
WarmupBlocks warmup_blocks(std::span<const double> channel);

/// detect_warmup's decision from every channel's block means (channel order kept: the reason
/// names the first channel with the longest trim).
WarmupDecision decide_warmup(const std::vector<WarmupBlocks>& channels, double rate_hz);

/// Number of blocks the log is split into; fewer than kMinBlockSamples per block: no detection.
inline constexpr int kWarmupBlocks = 200;
inline constexpr std::int64_t kMinBlockSamples = 10;
/// How far outside the settled range the first block must be to call it a transient.
inline constexpr double kTransientFactor = 2.0;
/// Longest trim, as a fraction of the log (a "transient" longer than this is drift: keep it).
inline constexpr double kMaxTrimFraction = 0.25;

}  // namespace sigmatau
