// Warm-up transient detection from block means (rule and constants in warmup.hpp).
#include "sigmatau/warmup.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sigmatau {

WarmupDecision detect_warmup(const std::vector<std::span<const double>>& channels, double rate_hz) {
  WarmupDecision decision;
  decision.reason = "no warm-up transient found";
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const auto& x = channels[c];
    const auto n = static_cast<std::int64_t>(x.size());
    const std::int64_t block = n / kWarmupBlocks;
    if (block < kMinBlockSamples) continue;
    std::vector<double> means(kWarmupBlocks);
    for (int b = 0; b < kWarmupBlocks; ++b) {
      double sum = 0;
      for (std::int64_t i = b * block; i < (b + 1) * block; ++i) sum += x[i];
      means[b] = sum / static_cast<double>(block);
    }
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
    const std::int64_t samples = settled * block;
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

}  // namespace sigmatau
