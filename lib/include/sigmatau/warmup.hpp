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

/// Number of blocks the log is split into; fewer than kMinBlockSamples per block: no detection.
inline constexpr int kWarmupBlocks = 200;
inline constexpr std::int64_t kMinBlockSamples = 10;
/// How far outside the settled range the first block must be to call it a transient.
inline constexpr double kTransientFactor = 2.0;
/// Longest trim, as a fraction of the log (a "transient" longer than this is drift: keep it).
inline constexpr double kMaxTrimFraction = 0.25;

}  // namespace sigmatau
