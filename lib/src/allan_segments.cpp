// Allan-family curves pooled over the contiguous segments of a split log.
//
// Glossary (see allan_segments.hpp for the pooling rules):
//   k      segment index; N_k its phase points, n_k its term count at m
//   v_k    its variance at m (dev_k^2); TOTDEV: divided by its own bias B_k
//   m      averaging factor, tau = m tau0
//   ref    the reference segment at m: the one with the most terms there (noise type from it)
#include "sigmatau/allan_segments.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "allan_curve_assembly.hpp"
#include "parallel_items.hpp"
#include "phase_store.hpp"
#include "sigmatau/confidence.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void check_segments(std::span<const PhaseSeries> segments) {
  if (segments.empty()) throw Error("no segment to analyse");
  for (const auto& s : segments) {
    if (s.tau0_s() != segments.front().tau0_s() || s.kind() != segments.front().kind()) {
      throw Error("segments of one channel must share tau0 and data kind");
    }
  }
}

/// Each segment's points at the factors `m`, aligned with `m`: n_terms 0 where the segment has
/// none. [segment][factor index].
std::vector<std::vector<DeviationPoint>> per_segment(std::span<const PhaseSeries> segments,
                                                     Statistic statistic,
                                                     std::span<const std::int64_t> m) {
  std::vector<std::vector<DeviationPoint>> result;
  result.reserve(segments.size());
  for (const auto& segment : segments) {
    std::vector<DeviationPoint> aligned(m.size());
    // Only the factors this segment has terms at are computed (compute_deviation would omit the
    // others anyway); their order follows `m`.
    std::vector<std::int64_t> defined;
    std::vector<std::size_t> where;
    for (std::size_t i = 0; i < m.size(); ++i) {
      if (m[i] < 1) throw Error("averaging factor must be >= 1, got " + std::to_string(m[i]));
      if (term_count(statistic, m[i], segment.size()) > 0) {
        defined.push_back(m[i]);
        where.push_back(i);
      }
    }
    if (!defined.empty()) {
      const auto points = compute_deviation(segment, statistic, defined);
      SIGMATAU_ASSERT(points.size() == defined.size(), "compute_deviation omitted a defined factor");
      for (std::size_t j = 0; j < points.size() && j < where.size(); ++j) aligned[where[j]] = points[j];
    }
    result.push_back(std::move(aligned));
  }
  return result;
}

/// sum(n_k v_k scale_k) / sum(n_k) as a deviation; scale_k multiplies segment k's variance
/// (TOTDEV bias correction; 1 otherwise).
DeviationPoint pool(const std::vector<std::vector<DeviationPoint>>& points, std::size_t i,
                    std::int64_t m, double tau0_s, const std::vector<double>& scale) {
  DeviationPoint pooled;
  pooled.m = m;
  pooled.tau_s = static_cast<double>(m) * tau0_s;
  // The deviations are pooled divided by a power of two (1 for ordinary values), so that their
  // squares neither overflow nor underflow for extreme logs (phase_store.hpp).
  double largest = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (points[k][i].n_terms > 0) largest = std::max(largest, points[k][i].dev);
  }
  const double unit = detail::value_scale_for(largest);
  double weighted = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const DeviationPoint& p = points[k][i];
    if (p.n_terms <= 0) continue;
    pooled.n_terms += p.n_terms;
    const double dev = p.dev / unit;
    weighted += static_cast<double>(p.n_terms) * (dev * dev) * scale[k];
  }
  pooled.dev = pooled.n_terms > 0
                   ? std::sqrt(weighted / static_cast<double>(pooled.n_terms)) * unit
                   : kNaN;
  return pooled;
}

std::size_t longest(std::span<const PhaseSeries> segments) {
  std::size_t best = 0;
  for (std::size_t k = 1; k < segments.size(); ++k) {
    if (segments[k].size() > segments[best].size()) best = k;
  }
  return best;
}

}  // namespace

std::vector<SegmentRange> segment_ranges(std::span<const std::int64_t> segment_starts,
                                         std::int64_t samples, std::int64_t skip) {
  if (!(samples >= 0) || !(skip >= 0 && (skip < samples || samples == 0))) {
    throw Error("segment_ranges: skip " + std::to_string(skip) + " outside a log of " +
                std::to_string(samples) + " samples");
  }
  std::vector<SegmentRange> ranges;
  const std::int64_t starts_size = static_cast<std::int64_t>(segment_starts.size());
  for (std::int64_t k = 0; k < std::max<std::int64_t>(starts_size, 1); ++k) {
    const std::int64_t begin = starts_size == 0 ? 0 : segment_starts[k];
    const std::int64_t end = k + 1 < starts_size ? segment_starts[k + 1] : samples;
    if (!(begin >= 0 && begin < end && end <= samples) && samples > 0) {
      throw Error("segment starts must ascend within the log's " + std::to_string(samples) +
                  " samples (segment " + std::to_string(k) + " starts at row " +
                  std::to_string(begin) + ")");
    }
    const SegmentRange kept{std::max(begin, skip) - skip, end - skip};
    if (kept.size() > 0) ranges.push_back(kept);
  }
  return ranges;
}

std::vector<PhaseSeries> segment_series(std::span<const double> values,
                                        std::span<const SegmentRange> segments, DataKind kind,
                                        double tau0_s) {
  std::vector<PhaseSeries> series;
  series.reserve(segments.size());
  for (const auto& s : segments) {
    if (!(s.begin >= 0 && s.begin < s.end && s.end <= static_cast<std::int64_t>(values.size()))) {
      throw Error("segment rows [" + std::to_string(s.begin) + ", " + std::to_string(s.end) +
                  ") lie outside the channel's " + std::to_string(values.size()) + " samples");
    }
    series.push_back(PhaseSeries::from_samples(
        values.subspan(static_cast<std::size_t>(s.begin), static_cast<std::size_t>(s.size())),
        kind, tau0_s));
  }
  return series;
}

std::vector<DeviationPoint> compute_segmented_deviation(std::span<const PhaseSeries> segments,
                                                        Statistic statistic,
                                                        std::span<const std::int64_t> m) {
  check_segments(segments);
  const auto points = per_segment(segments, statistic, m);
  const std::vector<double> unit_scale(segments.size(), 1.0);
  std::vector<DeviationPoint> result;
  for (std::size_t i = 0; i < m.size(); ++i) {
    const DeviationPoint p = pool(points, i, m[i], segments.front().tau0_s(), unit_scale);
    if (p.n_terms > 0) result.push_back(p);
  }
  return result;
}

AllanCurve compute_segmented_allan_curve(std::span<const PhaseSeries> segments,
                                         Statistic statistic, const TauSpec& taus,
                                         double confidence_level, EdfModel edf_model) {
  if (!(confidence_level > 0.0 && confidence_level < 1.0)) {
    throw Error("confidence level must be between 0 and 1 (e.g. 0.683), got " +
                std::to_string(confidence_level));
  }
  check_segments(segments);
  const PhaseSeries& longest_segment = segments[longest(segments)];
  const auto factors = averaging_factors(taus, statistic, longest_segment.size(),
                                         longest_segment.tau0_s(), longest_segment.kind());
  if (factors.empty()) {
    throw Error("the longest contiguous segment (" + std::to_string(longest_segment.size() - 1) +
                " samples) is too short for " + std::string(to_string(statistic)) +
                " at any tau");
  }
  const auto points = per_segment(segments, statistic, factors);
  AllanCurve curve;
  curve.statistic = statistic;
  curve.confidence_level = confidence_level;
  for (std::size_t i = 0; i < factors.size(); ++i) {
    const std::int64_t m = factors[i];
    // The reference segment: the most terms at m (ties: the first).
    std::size_t ref = segments.size();
    for (std::size_t k = 0; k < segments.size(); ++k) {
      if (points[k][i].n_terms > 0 && (ref == segments.size() || points[k][i].n_terms > points[ref][i].n_terms)) {
        ref = k;
      }
    }
    if (ref == segments.size()) continue;  // no segment has terms at m
    ConfidencePoint confidence;
    const std::int64_t averages = (segments[ref].size() - 1) / m;
    const std::int64_t kept_m = kept_noise_factor(statistic, segments[ref].size(), m);
    if (m != kept_m && averages <= kept_noise_threshold(statistic)) {
      confidence.noise.alpha = identify_noise(segments[ref], statistic, kept_m).alpha;
      confidence.noise.method = NoiseIdentification::Method::kept;
    } else {
      confidence.noise = identify_noise(segments[ref], statistic, m);
    }
    std::vector<double> scale(segments.size(), 1.0);
    if (statistic == Statistic::totdev) {
      for (std::size_t k = 0; k < segments.size(); ++k) {
        scale[k] = 1.0 / totvar_bias(confidence.noise.alpha, m, segments[k]);
      }
    }
    const DeviationPoint pooled = pool(points, i, m, segments.front().tau0_s(), scale);
    detail::check_representable(statistic, pooled);
    // Independent segments: their degrees of freedom add. A segment outside the EDF algorithm's
    // domain (NaN) adds nothing; if none is inside, the EDF and interval stay NaN.
    double edf = 0.0;
    bool any_edf = false;
    for (std::size_t k = 0; k < segments.size(); ++k) {
      if (points[k][i].n_terms <= 0) continue;
      const std::int64_t edf_points =
          statistic == Statistic::totdev ? record_points(segments[k]) : segments[k].size();
      const double e = equivalent_dof(statistic, confidence.noise.alpha, m, edf_points, edf_model);
      if (std::isfinite(e)) {
        edf += e;
        any_edf = true;
      }
    }
    confidence.edf = any_edf ? edf : kNaN;
    confidence.interval = chi_squared_interval(pooled.dev, confidence.edf, confidence_level);
    curve.points.push_back({pooled, confidence});
  }
  return curve;
}

std::vector<std::vector<AllanCurve>> compute_segmented_allan_curves(
    const std::vector<std::vector<PhaseSeries>>& channels,
    const std::vector<Statistic>& statistics, const TauSpec& taus, double confidence_level,
    unsigned threads, EdfModel edf_model) {
  return detail::curves_per_channel_and_statistic(
      channels.size(), statistics.size(), threads, [&](std::size_t c, std::size_t s) {
        return compute_segmented_allan_curve(channels[c], statistics[s], taus, confidence_level,
                                             edf_model);
      });
}

}  // namespace sigmatau
