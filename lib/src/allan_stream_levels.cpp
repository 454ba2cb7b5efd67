// The decimated phase of the stream mode (see allan_stream_levels.hpp).
#include "allan_stream_levels.hpp"

#include <algorithm>
#include <cstddef>

#include "simd_clones.hpp"

namespace sigmatau::detail {
namespace {

/// dst[c] = src[2 c] for c < n.
SIGMATAU_SIMD_CLONES void every_second(const double* src, std::size_t n, double* dst) {
  for (std::size_t c = 0; c < n; ++c) dst[c] = src[2 * c];
}

}  // namespace

void distribute_points(std::vector<Level>& levels, std::int64_t points, std::int64_t count,
                       bool with_p) {
  const std::int64_t first = points - count;  // index of the first new point
  auto take = [](Doubles& to, const Doubles& from, std::int64_t at, std::size_t n) {
    const std::size_t old = to.size();
    to.resize(old + n);
    every_second(from.data() + at, n, to.data() + old);
  };
  for (std::size_t j = 1; j < levels.size(); ++j) {
    const Level& below = levels[j - 1];
    Level& level = levels[j];
    const std::int64_t s = level.stride;
    const std::int64_t k0 = (first + s - 1) / s * s;  // first new point of this level
    if (k0 >= points) continue;
    const auto n = static_cast<std::size_t>((points - 1 - k0) / s + 1);
    // Every new point of this level is a new point of the level below (a multiple of its
    // stride, at or after `first`), so it is still there.
    const std::int64_t at = k0 / below.stride - below.begin;
    take(level.xh, below.xh, at, n);
    take(level.xl, below.xl, at, n);
    if (with_p) {
      take(level.ph, below.ph, at, n);
      take(level.pl, below.pl, at, n);
    }
  }
}

void trim_levels(std::vector<Level>& levels, const std::vector<std::int64_t>& keep_from) {
  for (std::size_t j = 0; j < levels.size(); ++j) {
    Level& level = levels[j];
    const std::int64_t drop = std::min(keep_from[j], level.x_end()) - level.begin;
    if (drop <= 0 || drop * 2 < static_cast<std::int64_t>(level.xh.size())) continue;
    auto erase = [drop](Doubles& v) {
      const auto n = std::min<std::size_t>(static_cast<std::size_t>(drop), v.size());
      v.erase(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n));
    };
    erase(level.xh);
    erase(level.xl);
    erase(level.ph);
    erase(level.pl);
    level.begin += drop;
  }
}

}  // namespace sigmatau::detail
