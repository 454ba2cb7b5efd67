#pragma once
// Internal (allan_stream*.cpp): the sum of squared differences of one strided estimator of the
// stream mode (one statistic at one averaging factor m), fed from its level of the decimated
// phase as the points arrive.
//
// Glossary: s the stride (a power of two dividing m), q = m / s the lag in level points, step
// the distance between start points in level points (1 for the overlapping estimators, q for
// ADEV and HDEV).

#include <cstdint>
#include <span>

#include "allan_dd.hpp"
#include "allan_stream_levels.hpp"
#include "sigmatau/allan.hpp"

namespace sigmatau::detail {

struct StridedTerms {
  Statistic statistic = Statistic::oadev;
  std::int64_t m = 0, stride = 1, lag = 1, step = 1;
  int level = 0;             ///< log2(stride): the level the terms read
  int order = 2;             ///< 2: D2 (Allan, and MDEV on P), 3: D3 (Hadamard)
  bool running_sum = false;  ///< MDEV, TDEV: third differences of P
  std::int64_t next = 0;     ///< start of the next term, level index
  std::int64_t terms = 0;    ///< terms summed so far
  DoubleDouble sum;          ///< their sum of squares

  /// Sums every term whose points are all in `source` (the level at index `level`).
  void run(const Level& source);
  /// MDEV, TDEV: the terms that also need P[N] = `p_total` (N = `points`), which arrives with
  /// the next point; sums them into *this without changing the level.
  void finish_running_sum(const Level& source, DoubleDouble p_total, std::int64_t points);
};

/// Runs the full term blocks that the overlapping Allan estimators (order 2, step 1, not on P)
/// among `taus`, all on level `source`, have in common: taus whose next terms end at the same
/// point and whose lags are q, 2q, 4q, ... are summed together, each phase point loaded once
/// for all of them (a term block of each tau is summed exactly as StridedTerms::run sums it, so
/// the sums are the same bit for bit). Every tau's remaining terms are left to run().
void run_octave_blocks(std::span<StridedTerms* const> taus, const Level& source);

}  // namespace sigmatau::detail
