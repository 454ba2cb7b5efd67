#pragma once
/// \file allan_curve.hpp
/// A deviation curve with confidence intervals: the estimate stage's output, consumed by the
/// fit, the plots and the reports. Composes allan.hpp (values) and confidence.hpp (intervals).

#include <cstdint>
#include <vector>

#include "sigmatau/allan.hpp"
#include "sigmatau/confidence.hpp"
#include "sigmatau/phase_series.hpp"
#include "sigmatau/taus.hpp"

namespace sigmatau {

/// One point: the deviation and its confidence interval (in the series' rate unit; TDEV in its
/// phase unit).
struct CurvePoint {
  DeviationPoint value;
  ConfidencePoint confidence;
};

struct AllanCurve {
  Statistic statistic = Statistic::oadev;
  double confidence_level = 0.683;  ///< two-sided probability of the intervals
  std::vector<CurvePoint> points;
};

/// The statistic at the averaging factors of `taus`, with intervals at `confidence_level`
/// (in (0, 1); Error otherwise). Averaging factors with no terms are left out.
AllanCurve compute_allan_curve(const PhaseSeries& series, Statistic statistic,
                               const TauSpec& taus, double confidence_level);

/// Several statistics for several channels, channels spread over `threads` worker threads
/// (0: one per hardware core). Result: [channel][statistic], in the order given.
std::vector<std::vector<AllanCurve>> compute_allan_curves(
    const std::vector<PhaseSeries>& channels, const std::vector<Statistic>& statistics,
    const TauSpec& taus, double confidence_level, unsigned threads = 0);

}  // namespace sigmatau
