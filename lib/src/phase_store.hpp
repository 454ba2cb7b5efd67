#pragma once
// Internal: what a PhaseSeries holds, shared by its copies. The double-double phase (hi, lo) is
// written once by the builder and never changed; derived forms of it are built on first use and
// kept, so that repeated estimates (several statistics, several calls) do not rebuild them.

#include <memory>
#include <map>
#include <mutex>
#include <vector>

#include "phase_spill.hpp"
#include "sigmatau/phase_series.hpp"

namespace sigmatau::detail {

/// Logs whose largest |value| lies in [kUnscaledMin, kUnscaledMax] (about 1.1e-100 to 8.7e99)
/// are held as given: their squares, sums of squares over any log length and the double-double
/// phase's low parts are far from overflow and from subnormal numbers. Others are divided by
/// value_scale_for(largest |value|), a power of two, which is exact.
inline constexpr double kUnscaledMin = 0x1p-332;
inline constexpr double kUnscaledMax = 0x1p332;

/// 1 for a largest |value| in [unscaled_min, unscaled_max] (or 0), else the power of two
/// 2^floor(log2 largest) that brings it to [1, 2). The noise fit, whose covariances are fourth
/// powers of the deviations, gives a narrower range (fit.cpp).
double value_scale_for(double largest, double unscaled_min = kUnscaledMin,
                       double unscaled_max = kUnscaledMax);

struct CompactPhase;  // allan_sums.hpp (built in allan_sweep.cpp)

struct PhaseStore {
  PhaseStorage storage;
  DoubleBuffer hi;
  DoubleBuffer lo;
  /// A power of two: the phase held is the input's divided by it (phase_series.cpp, "Scale"),
  /// 1 for every log whose largest |value| is within kUnscaledMin..kUnscaledMax. Estimators
  /// multiply each deviation by it.
  double value_scale = 1.0;
  /// The sweep copy (allan_sweep.cpp: compact_phase()), guarded by `mutex` while it is built or
  /// dropped; estimators hold a shared_ptr to it while they use it.
  std::mutex mutex;
  std::shared_ptr<const CompactPhase> compact;
  /// Memory handed back by the caller (PhaseSeries::recycle, under `mutex`): the sweep copy is
  /// built in it when it holds the series' points, instead of in fresh pages.
  std::vector<double> recycled;
  /// The OADEV sums (squared second differences at every start point) by factor, under `mutex`:
  /// computed once for the OADEV and TOTDEV curves of the series (allan.cpp).
  std::map<std::int64_t, double> allan_sums;
};

}  // namespace sigmatau::detail
