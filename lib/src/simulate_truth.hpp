#pragma once
// Internal: evaluating a user truth series (simulate.hpp, TruthSeries) at increasing times with a
// remembered position, so a log of n samples costs O(n + rows) instead of O(n log rows).
#include <cstddef>

#include "sigmatau/simulate.hpp"

namespace sigmatau::detail {

class TruthCursor {
 public:
  explicit TruthCursor(const TruthSeries& series) : series_(&series) {}
  /// truth_at(series, t) (any t; fastest when t does not decrease between calls).
  Truth at(double t_s);
  /// truth_mean(series, t0, t1), t0 <= t1.
  Truth mean(double t0_s, double t1_s);

 private:
  /// The row i with t_i <= t < t_{i+1} (0 before the first row, rows - 1 at or after the last).
  std::size_t locate(double t_s);
  const TruthSeries* series_;
  std::size_t hint_ = 0;
};

}  // namespace sigmatau::detail
