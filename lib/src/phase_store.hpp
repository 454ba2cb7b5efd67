#pragma once
// Internal: what a PhaseSeries holds, shared by its copies. The double-double phase (hi, lo) is
// written once by the builder and never changed; derived forms of it are built on first use and
// kept, so that repeated estimates (several statistics, several calls) do not rebuild them.

#include <memory>
#include <mutex>
#include <vector>

#include "phase_spill.hpp"
#include "sigmatau/phase_series.hpp"

namespace sigmatau::detail {

struct CompactPhase;  // allan_sums.hpp (built in allan_sweep.cpp)

struct PhaseStore {
  PhaseStorage storage;
  DoubleBuffer hi;
  DoubleBuffer lo;
  /// The sweep copy (allan_sweep.cpp: compact_phase()), guarded by `mutex` while it is built or
  /// dropped; estimators hold a shared_ptr to it while they use it.
  std::mutex mutex;
  std::shared_ptr<const CompactPhase> compact;
  /// Memory handed back by the caller (PhaseSeries::recycle, under `mutex`): the sweep copy is
  /// built in it when it holds the series' points, instead of in fresh pages.
  std::vector<double> recycled;
};

}  // namespace sigmatau::detail
