#pragma once
/// \file allan_stream.hpp
/// Allan-family deviations of a log read once (a pipe, stdin, a live logger) in memory independent
/// of its length: the bounded-memory single-pass mode (`sigmatau adev --mode stream`).
///
/// Method. At tau = m tau0 the overlapping estimators (OADEV, OHDEV, MDEV/TDEV) sum their terms
/// only at start points that are multiples of a stride s = max(1, m/K), rounded down to a power
/// of two that divides m, instead of at every start point (K = `density`, overlap density: start
/// points per tau). Every term is still an exact term of the exact estimator, so the estimate is
/// unbiased; only its variance grows, and each point reports the equivalent degrees of freedom of
/// the strided estimator (Greenhall & Riley 2003 with stride factor S = m/s), lower than the exact
/// estimator's. For m <= K the stride is 1 and the point equals the exact one up to rounding.
/// ADEV and HDEV (stride m by definition) are exact. The phase at multiples of each stride is
/// kept in double-double over the last 3 m / s points only, so memory is O(K log N).
/// MDEV's inner sum V(j) = sum_{i=j}^{j+m-1} D2(i) is a third difference, at lag m, of the
/// running sum P of the phase (P[k] = x_0 + ... + x_{k-1}), so MDEV costs the same as OHDEV.
/// Noise identification (for the EDF and the intervals) uses the lag-1 autocorrelation of the
/// series at each m, accumulated in one pass; below 30 averages the B1 ratio of the few m-sample
/// means kept (as compute_allan_curve, with the B1 term count of that short series).
/// TOTDEV needs the whole record reflected at both ends and is not available in this mode.
///
/// References: NIST SP 1065 (Riley 2008) eqs. 11, 14, 20; C. A. Greenhall, W. J. Riley,
/// "Uncertainty of stability variances based on finite differences", 35th PTTI, 2003.

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "sigmatau/allan_curve.hpp"
#include "sigmatau/phase_series.hpp"
#include "sigmatau/taus.hpp"

namespace sigmatau {

/// Default overlap density K (start points per tau): chosen from the speed-against-error table
/// (bench/bench_long_logs.cpp): on 1e8 samples K = 8 keeps the median EDF within 0.5% of the
/// exact estimator's (K = 4: 1.4%, K = 2: 5%) and the median deviation within 1e-4 of the exact
/// one, while the time per sample is still set mostly by the per-sample work, not by K (1e8
/// samples, CPU time on a shared 2-core Xeon VM: 6.3 ns/sample at K = 1, 7.1 at K = 8, 7.5 at
/// K = 32; K = 16 and 32 buy < 0.5% of EDF for 2-6% more time).
constexpr int kDefaultStreamDensity = 8;

struct StreamSettings {
  /// oadev, ohdev, mdev, tdev (strided) and adev, hdev (exact); totdev is an Error.
  std::vector<Statistic> statistics = {Statistic::oadev};
  /// octave, decade or explicit seconds (the length of the log is not known in advance, so
  /// `many` and `all` are an Error).
  TauSpec taus;
  /// Overlap density K >= 1; Error otherwise.
  int density = kDefaultStreamDensity;
};

/// One pass over a channel. Feed samples with add() in order; curves() can be called at any time
/// and describes everything added so far.
class AllanStream {
 public:
  /// kind and tau0_s [s] as for PhaseSeries::from_samples. Throws Error on bad settings.
  AllanStream(DataKind kind, double tau0_s, const StreamSettings& settings);
  ~AllanStream();
  AllanStream(AllanStream&&) noexcept;
  AllanStream& operator=(AllanStream&&) noexcept;

  /// Appends samples (rate, increment or phase values, in the unit the curves are wanted in).
  /// Throws Error naming the 0-based index of a non-finite sample (counted from the first add).
  void add(std::span<const double> values);
  /// Number of phase points so far (samples + 1 for rate and increment input).
  std::int64_t size() const;
  /// The curves of the statistics in the order of the settings, at `confidence_level` in (0, 1).
  /// Points: taus up to the Stable32 stop ratio for the current length (as the exact curves).
  std::vector<AllanCurve> curves(double confidence_level) const;
  /// The stride s used at averaging factor m for `statistic` (1 <= s <= m, s divides m).
  std::int64_t stride(Statistic statistic, std::int64_t m) const;
  /// Averaging factors of a decade run that the current length reaches (up to the stop ratio of
  /// one of the statistics) but that the stream does not compute: their stride lag (the odd
  /// part 5^k of 10^k) would need memory beyond its bound, from m = 10^7 on. Ascending; empty
  /// for octave and explicit taus, and for logs too short to reach them.
  std::vector<std::int64_t> factors_left_out() const;
  /// Bytes of state held (independent of the number of samples added).
  std::size_t memory_bytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// EDF of the strided estimator: the overlapping `statistic` (oadev, ohdev, mdev, tdev) at
/// averaging factor m with start points every s samples (s divides m) on N phase points, for
/// power-law noise alpha. Equals equivalent_dof() for s = 1. NaN outside Greenhall's domain.
double strided_equivalent_dof(Statistic statistic, int alpha, std::int64_t m, std::int64_t s,
                              std::int64_t n_phase_points);

}  // namespace sigmatau
