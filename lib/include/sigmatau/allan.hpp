#pragma once
/// \file allan.hpp
/// Exact Allan-family deviations (NIST SP 1065, W. J. Riley, "Handbook of Frequency Stability
/// Analysis", 2008): ADEV (eqs. 6-7), OADEV (eq. 11), MDEV (eq. 14), TDEV (eq. 15), HDEV
/// (eqs. 17-18), OHDEV (eq. 20), TOTDEV (eq. 25), with Stable32's term counts and TOTDEV
/// reflection (no bias correction). Input: a PhaseSeries; output in the series' rate unit
/// (TDEV in its phase unit: s for clock data, input-unit x s otherwise).

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include "sigmatau/phase_series.hpp"

namespace sigmatau {

enum class Statistic { adev, oadev, mdev, tdev, hdev, ohdev, totdev };

/// "adev" | "oadev" | "mdev" | "tdev" | "hdev" | "ohdev" | "totdev"; throws Error otherwise.
Statistic parse_statistic(std::string_view text);
std::string_view to_string(Statistic statistic);

/// One point of a deviation curve.
struct DeviationPoint {
  double tau_s = 0;          ///< averaging time m * tau0 [s]
  std::int64_t m = 0;        ///< averaging factor (cluster size)
  std::int64_t n_terms = 0;  ///< number of terms summed (Stable32's "#")
  double dev = 0;            ///< the deviation, in the series' rate unit (TDEV: phase unit)
};

/// Number of terms the estimator sums at averaging factor m for N phase points (0 when the
/// statistic is undefined there). ADEV floor((N-1)/m)-1, OADEV N-2m, MDEV/TDEV N-3m+1,
/// HDEV floor((N-1)/m)-2, OHDEV N-3m, TOTDEV N-2 (defined for 2m <= N-1, where Stable32 stops;
/// the reflected series would allow more, but those windows would be mostly reflected data).
std::int64_t term_count(Statistic statistic, std::int64_t m, std::int64_t n_phase_points);

/// The statistic at each averaging factor in `m`. A factor with no terms (too few samples) is
/// omitted from the result, never an exception; the result keeps the order of `m` (repeated
/// factors are repeated). A constant input gives exactly 0. Throws Error if a factor is < 1.
/// Accuracy: every difference is formed from window sums of the double-double phase, and sums of
/// squares are blocked, so the result is within ~1e-15 relative of the exact statistic of the
/// input (tests/test_allan_precision.cpp), whatever the offset or length of the data.
/// `threads` (>= 1) is how many threads the sums may use (MDEV and TDEV share their factors
/// among them; OADEV, OHDEV and TOTDEV sweep their factors below 4096 on a second thread); the
/// results are the same bit for bit whatever it is.
std::vector<DeviationPoint> compute_deviation(const PhaseSeries& series, Statistic statistic,
                                              std::span<const std::int64_t> m,
                                              unsigned threads = 1);

}  // namespace sigmatau
