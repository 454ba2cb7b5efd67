#pragma once
// Internal (allan_stream*.cpp): the running phase of the stream mode. Each chunk of samples
// becomes phase points in double-double, x_0 = 0, x_k = sum_{i<=k} (y_i - y0bar), with the same
// operations in the same order as PhaseSeries::from_rate (phase_series.cpp), so the points are
// the same bit for bit; for phase input x_k = value_k - value_0 exactly. For MDEV and TDEV also
// the running sum P of the phase (P[0] = 0, P[k+1] = P[k] + x[k]).

#include <cstddef>
#include <cstdint>
#include <span>

#include "allan_dd.hpp"
#include "sigmatau/phase_series.hpp"

namespace sigmatau::detail {

/// The state that carries the phase (and its running sum) from one chunk to the next.
class StreamPhase {
 public:
  explicit StreamPhase(DataKind kind) : kind_(kind) {}

  /// Phase points the next chunk of `samples` values yields (one more than the values for the
  /// first rate or increment chunk: it adds x_0 = 0).
  std::size_t points_for(std::size_t samples) const {
    return samples + (!started_ && kind_ != DataKind::phase ? 1 : 0);
  }
  /// Writes the phase points of chunk y (points_for(y.size()) of them) to nh, nl (high and low
  /// parts). `samples_before` is the number of values of earlier chunks (the double-double phase
  /// is renormalised every kRenormalise values of the whole stream). Returns false if a value is
  /// not finite or the phase overflowed (nothing is then usable).
  bool integrate(std::span<const double> y, std::int64_t samples_before, double* nh, double* nl);
  /// Writes P before each of the `count` points nh, nl to ph, pl and advances P past them.
  void running_sum(const double* nh, const double* nl, std::size_t count, double* ph, double* pl);
  /// P after the last point written (P[N] for N points).
  DoubleDouble running_total() const { return p_run_; }

  /// Renormalise the running double-double phase this often [values] (as phase_series.cpp).
  static constexpr std::int64_t kRenormalise = 4096;

 private:
  DataKind kind_;
  bool started_ = false;
  double offset_ = 0;     // y0bar (rate, increment: mean of the first chunk) or x_0 (phase)
  double h_ = 0, l_ = 0;  // the running phase, not renormalised
  DoubleDouble p_run_;
};

}  // namespace sigmatau::detail
