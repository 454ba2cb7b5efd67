#pragma once
// Internal (allan_stream*.cpp): the decimated phase of the stream mode. Level j holds the phase
// points (and, for MDEV and TDEV, the running sum P) whose index is a multiple of 2^j, in
// double-double, from the oldest point still needed to the newest: a strided estimator with
// stride 2^j reads level j contiguously.

#include <cstdint>
#include <vector>

#include "allan_stream_noise.hpp"

namespace sigmatau::detail {

struct Level {
  std::int64_t stride = 1;  ///< 2^j
  std::int64_t begin = 0;   ///< level index (point index / stride) of element 0 of the buffers
  Doubles xh, xl;           ///< phase, high and low parts
  Doubles ph, pl;           ///< running sum P (MDEV, TDEV), high and low parts
  std::int64_t x_end() const { return begin + static_cast<std::int64_t>(xh.size()); }
  std::int64_t p_end() const { return begin + static_cast<std::int64_t>(ph.size()); }
};

/// Appends the newest `count` of `points` phase points, already at the end of levels[0], to the
/// coarser levels (each takes every second new point of the level below it); with_p: P too.
void distribute_points(std::vector<Level>& levels, std::int64_t points, std::int64_t count,
                       bool with_p);

/// Drops the points of level j before level index keep_from[j] (amortised: only once they are
/// at least half of the buffer).
void trim_levels(std::vector<Level>& levels, const std::vector<std::int64_t>& keep_from);

}  // namespace sigmatau::detail
