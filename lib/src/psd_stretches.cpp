// Welch PSD over the contiguous stretches of a split log (psd.hpp, welch_psd_stretches): each
// stretch's Welch average, weighted by its number of Welch segments.
#include <algorithm>
#include <string>

#include "sigmatau/error.hpp"
#include "sigmatau/psd.hpp"

namespace sigmatau {

PsdCurve welch_psd_stretches(std::span<const std::span<const double>> stretches, double rate_hz,
                             const WelchOptions& options) {
  std::size_t longest_size = 0;
  for (const auto& s : stretches) longest_size = std::max(longest_size, s.size());
  WelchOptions fixed = options;
  if (fixed.segment_length == 0) {
    fixed.segment_length = default_segment_length(static_cast<std::int64_t>(longest_size));
  }
  PsdCurve combined;
  for (const auto& s : stretches) {
    if (static_cast<std::int64_t>(s.size()) < fixed.segment_length) continue;
    const PsdCurve part = welch_psd(s, rate_hz, fixed);
    if (combined.segments == 0) {
      combined = part;
      for (double& v : combined.psd) v *= static_cast<double>(part.segments);
      continue;
    }
    SIGMATAU_ASSERT(part.psd.size() == combined.psd.size(), "Welch grids differ");
    for (std::size_t j = 0; j < part.psd.size(); ++j) {
      combined.psd[j] += static_cast<double>(part.segments) * part.psd[j];
      combined.edf[j] += part.edf[j];
    }
    combined.segments += part.segments;
  }
  if (combined.segments == 0) {
    throw Error("no contiguous stretch holds one PSD segment of " +
                std::to_string(fixed.segment_length) + " samples (the longest has " +
                std::to_string(longest_size) + ")");
  }
  for (double& v : combined.psd) v /= static_cast<double>(combined.segments);
  return combined;
}

}  // namespace sigmatau
