// Warm-up transient detection from block means (rule and constants in warmup.hpp).
#include "sigmatau/warmup.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sigmatau {

WarmupBlockSums::WarmupBlockSums(std::int64_t samples) {
  const std::int64_t block = samples / kWarmupBlocks;
  if (block < kMinBlockSamples) return;  // too short: no blocks, no detection
  blocks_.block_samples = block;
  blocks_.means.assign(kWarmupBlocks, 0.0);
}

void WarmupBlockSums::add(std::span<const double> values) {
  const std::int64_t block = blocks_.block_samples;
  if (block == 0) return;
  const std::int64_t end = block * kWarmupBlocks;  // samples past the last block are not used
  // A block's piece at a time (the additions those of one value after another, in order).
  std::size_t i = 0;
  while (i < values.size() && seen_ < end) {
    const std::int64_t left_in_block = block - seen_ % block;
    const std::size_t n =
        static_cast<std::size_t>(std::min<std::int64_t>(left_in_block, static_cast<std::int64_t>(values.size() - i)));
    double sum = sum_;
    for (std::size_t k = 0; k < n; ++k) sum += values[i + k];
    sum_ = sum;
    i += n;
    seen_ += static_cast<std::int64_t>(n);
    if (seen_ % block == 0) {
      blocks_.means[static_cast<std::size_t>(seen_ / block - 1)] = sum_ / static_cast<double>(block);
      sum_ = 0;
    }
  }
}

WarmupBlocks WarmupBlockSums::blocks() const { return blocks_; }

WarmupDecision decide_warmup(const std::vector<WarmupBlocks>& channels, double rate_hz) {
  WarmupDecision decision;
  decision.reason = "no warm-up transient found";
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const std::vector<double>& means = channels[c].means;
    if (means.size() != static_cast<std::size_t>(kWarmupBlocks)) continue;
    std::vector<double> late(means.begin() + kWarmupBlocks / 2, means.end());
    const auto [lo, hi] = std::minmax_element(late.begin(), late.end());
    const double range = *hi - *lo;
    std::nth_element(late.begin(), late.begin() + late.size() / 2, late.end());
    const double level = late[late.size() / 2];
    if (!(std::abs(means[0] - level) > kTransientFactor * range)) continue;
    int settled = 0;
    while (settled < kWarmupBlocks && std::abs(means[settled] - level) > range) ++settled;
    const auto limit = static_cast<int>(kMaxTrimFraction * kWarmupBlocks);
    if (settled > limit) continue;  // longer than any warm-up: drift, keep it
    const std::int64_t samples = settled * channels[c].block_samples;
    if (samples > decision.trim_samples) {
      decision.trim_samples = samples;
      decision.trim_s = static_cast<double>(samples) / rate_hz;
      decision.channel = static_cast<int>(c);
      char text[200];
      std::snprintf(text, sizeof text,
                    "warm-up transient: the first block mean was %.3g x the settled range away "
                    "from the settled level; trimmed %.6g s until it settled",
                    std::abs(means[0] - level) / range, decision.trim_s);
      decision.reason = text;
    }
  }
  return decision;
}

WarmupBlocks warmup_blocks(std::span<const double> channel) {
  WarmupBlockSums sums(static_cast<std::int64_t>(channel.size()));
  sums.add(channel);
  return sums.blocks();
}

WarmupDecision detect_warmup(const std::vector<std::span<const double>>& channels, double rate_hz) {
  std::vector<WarmupBlocks> blocks;
  for (const auto& x : channels) blocks.push_back(warmup_blocks(x));
  return decide_warmup(blocks, rate_hz);
}

}  // namespace sigmatau
