#pragma once
/// \file allan_segments.hpp
/// Allan-family curves of a log broken into contiguous segments (a logger
/// restart, a dropped stretch: GapPolicy::split). Every segment becomes its own PhaseSeries, so
/// no difference spans a gap, and the segments' results are pooled through the public
/// estimators (allan.hpp, confidence.hpp); no estimator is re-implemented here. The Welch PSD
/// over such segments is welch_psd_stretches (psd.hpp).
///
/// Pooling at averaging factor m (segment k: n_k terms, variance v_k = dev_k^2):
///  - ADEV, OADEV, MDEV, TDEV, HDEV, OHDEV: each variance is S_k / (c n_k), where S_k is the
///    segment's sum of squared differences and the normalisation c depends only on m and tau0,
///    the same for every segment. The variance over all terms of all segments is therefore
///    sum(S_k) / (c sum(n_k)) = sum(n_k v_k) / sum(n_k): the n-weighted mean of the segment
///    variances, exactly the statistic of the log with the cross-gap terms left out.
///  - TOTDEV: each segment's TOTVAR reflects that segment at its own ends (so the reflection
///    never reaches across a gap) and is divided by its own bias B_k = 1 - a tau / T_k (T_k the
///    segment's record length, allan_curve.hpp totvar_bias); the corrected variances are then
///    n-weighted like the others. This is an approximation: TOTVAR is not a plain mean of
///    squared differences (its reflected terms depend on where the record ends), so the pooled
///    value is not the TOTVAR of any single series; it is the natural unbiased combination.
///  - Noise type (for the EDF and the TOTDEV bias): identified with identify_noise on the
///    segment with the most terms at m (the longest); where that segment has few averages at m
///    (kept_noise_threshold), the type identified on it at its kept_noise_factor.
///  - EDF: segments are independent, so their EDFs add: sum over the segments with terms at m
///    of equivalent_dof(statistic, alpha, m, N_k) (TOTDEV: record_points of the segment, as
///    compute_allan_curve does). The interval is chi_squared_interval on the pooled deviation.
///  - A segment too short for m (no terms there) contributes nothing at that m. The averaging
///    factors are those the spec gives for the longest segment.

#include <cstdint>
#include <span>
#include <vector>

#include "sigmatau/allan.hpp"
#include "sigmatau/allan_curve.hpp"
#include "sigmatau/phase_series.hpp"
#include "sigmatau/taus.hpp"

namespace sigmatau {

/// Rows [begin, end) of one contiguous segment of a log (0-based sample indices).
struct SegmentRange {
  std::int64_t begin = 0;
  std::int64_t end = 0;
  std::int64_t size() const { return end - begin; }
};

/// The segments of a log of `samples` rows from TimingReport::segment_starts (ascending, first
/// 0), after the first `skip` rows are removed (a warm-up trim): row indices are then relative
/// to row `skip`, and segments left empty are dropped. An empty `segment_starts` means one
/// segment. Throws Error when the starts are not ascending or lie outside [0, samples), or when
/// skip is outside [0, samples).
std::vector<SegmentRange> segment_ranges(std::span<const std::int64_t> segment_starts,
                                         std::int64_t samples, std::int64_t skip = 0);

/// One PhaseSeries per segment of `values` (samples of `kind` taken every tau0_s seconds); each
/// is built by PhaseSeries::from_samples and throws like it. Throws Error when a segment lies
/// outside `values`.
std::vector<PhaseSeries> segment_series(std::span<const double> values,
                                        std::span<const SegmentRange> segments, DataKind kind,
                                        double tau0_s);

/// The statistic at each averaging factor in `m`, pooled over the segments (see the file
/// comment): dev in the series' rate unit (TDEV: phase unit), n_terms the sum of the segments'
/// term counts. TOTDEV is returned without bias correction, like compute_deviation. Factors no
/// segment has terms at are omitted; the order of `m` is kept. Throws Error when `segments` is
/// empty, when the segments' tau0 or kind differ, or when a factor is < 1.
std::vector<DeviationPoint> compute_segmented_deviation(std::span<const PhaseSeries> segments,
                                                        Statistic statistic,
                                                        std::span<const std::int64_t> m);

/// compute_allan_curve over segments: pooled deviation, noise type from the longest segment,
/// summed EDF, chi-squared interval at `confidence_level` (in (0, 1)). Throws Error like
/// compute_segmented_deviation, and when the longest segment is too short for any tau.
AllanCurve compute_segmented_allan_curve(std::span<const PhaseSeries> segments,
                                         Statistic statistic, const TauSpec& taus,
                                         double confidence_level,
                                         EdfModel edf_model = EdfModel::greenhall);

/// Several statistics for several channels, each channel given as its segments; (channel,
/// statistic) pairs are spread over `threads` worker threads (0: one per hardware core).
/// Result: [channel][statistic].
std::vector<std::vector<AllanCurve>> compute_segmented_allan_curves(
    const std::vector<std::vector<PhaseSeries>>& channels,
    const std::vector<Statistic>& statistics, const TauSpec& taus, double confidence_level,
    unsigned threads = 0, EdfModel edf_model = EdfModel::greenhall);

}  // namespace sigmatau
