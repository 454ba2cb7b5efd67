#pragma once
// Internal: the sums of squared phase differences behind every Allan-family estimator
// (allan_sweep.cpp: the overlapping sweep; allan_sums.cpp: the others).
// Every difference is formed from window sums W(k, m) = x[k+m] - x[k] of the double-double phase
// (PhaseSeries::window_sum), never from absolute phase values, and every sum of squares is taken
// in blocks (kLanes plain-double lanes per block, block totals carried in double-double).
//
// Glossary (0-based phase points x_0..x_{N-1}, L = N - 1, m = averaging factor):
//   D2(n) = W(n+m, m) - W(n, m)                 = x[n+2m] - 2x[n+m] + x[n]   (Allan)
//   D3(n) = D2(n+m) - D2(n)                     = x[n+3m] - 3x[n+2m] + 3x[n+m] - x[n] (Hadamard)
//   V(j)  = sum_{i=j}^{j+m-1} D2(i)                                          (modified Allan)
//   x*    the phase reflected at both ends (SP 1065 eq. 25): x*[-j] = 2x[0] - x[j],
//         x*[L+j] = 2x[L] - x[L-j]                                            (total)

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "allan_dd.hpp"
#include "phase_spill.hpp"
#include "sigmatau/phase_series.hpp"

namespace sigmatau::detail {

/// Points per base block of the compact phase.
inline constexpr std::int64_t kCompactBlock = 4096;

/// The phase in the form the overlapping sweep reads: one double per point measured from a base
/// point per block of kCompactBlock points, x[k] = base[k / kCompactBlock] + offset[k], with the
/// bases in double-double. Half the memory traffic of the double-double phase, and a difference
/// needs three or four loads instead of six or eight. offset[k] is W(b B, k - b B) rounded once,
/// so it is accurate to ~1 ulp of the phase excursion within its block; every difference adds the
/// exact (double-double) difference of the bases, rounded once.
/// The offsets live where the series does (memory, or a spilled file: PhaseStorage).
struct CompactPhase {
  /// Built in `memory` when it holds series.size() doubles and the series is not spilled,
  /// else in fresh storage of the series' kind.
  explicit CompactPhase(const PhaseSeries& series, std::vector<double> memory = {});
  DoubleBuffer offset;
  std::vector<DoubleDouble> base;
};

/// The base part (B2 - B1) - (B1 - B0) of D2(n) for lag m, rounded once: D2(n) is
/// ((o[n+2m] + o[n]) - 2 o[n+m]) + this, with B_j the base of the block of n + j m.
double compact_base_d2(const CompactPhase& phase, std::int64_t n, std::int64_t m);

/// The series' compact phase, built on first use and kept with the series (shared by every
/// statistic, factor and call, and by copies of the series) until drop_sweep_cache().
/// Thread-safe: concurrent first uses build it once.
std::shared_ptr<const CompactPhase> compact_phase(const PhaseSeries& series);

/// For each m (ascending, each with counts[t] >= 1 terms), sum_{n < counts[t]} D(n)^2 with
/// D = D2 (order 2, OADEV) or D3 (order 3, OHDEV) and n = 0, 1, 2, ... (every start point).
/// All factors are swept together, block by block, so the phase is read from memory about once
/// per group of factors instead of once per factor.
/// Factors below 4096 read the double-double phase itself (see kCompactMin in allan_sweep.cpp).
/// With threads > 1 the factors below kCompactMin are swept on a second thread (same sums).
std::vector<double> overlapping_sums(const PhaseSeries& series, int order,
                                     std::span<const std::int64_t> m,
                                     std::span<const std::int64_t> counts, unsigned threads = 1);

/// sum_{i < len} D(n0 + i)^2 on raw double-double arrays h, l (D = D2 for order 2, D3 for
/// order 3, lag m), summed in kLanes lanes: the kernel of the overlapping sums, for other
/// accumulators (allan_stream.cpp) that hold their own phase buffers. len <= 2048 keeps each
/// plain-double lane sum as short as in the exact sums.
double sum_squares(const double* h, const double* l, int order, std::int64_t m, std::int64_t n0,
                   std::int64_t len);

/// sum_{k < count} D(k m)^2 with D = D2 (order 2, ADEV) or D3 (order 3, HDEV): stride m.
double strided_sum(const PhaseSeries& series, int order, std::int64_t m, std::int64_t count);

/// For each m (counts[t] >= 1 terms), sum_{j < counts[t]} V(j)^2 (MDEV, TDEV), V carried by a
/// compensated running sum. Factors from 4096 that are multiples of 1024 form their D2 from the
/// compact phase (as the overlapping sweep does), the others from the double-double phase.
/// Up to eight factors run at once, one per vector lane (each factor's running sum is a serial
/// chain of additions, so several chains keep the floating-point units busy), and each factor's
/// start points are cut into four pieces at fixed points of the series; every factor's result is
/// the same bit for bit as when it is computed alone, and with any number of threads (which
/// take the pieces of the groups in turn).
std::vector<double> modified_sums(const PhaseSeries& series, std::span<const std::int64_t> m,
                                  std::span<const std::int64_t> counts, unsigned threads = 1);

/// The 2(m-1) terms of the total variance whose 2m-point window reaches past either end of the
/// phase (i = 1..m-1 and i = L-m+1..L-1): sum of (x*[i-m] - 2x*[i] + x*[i+m])^2. The other
/// N - 2m terms are exactly the OADEV terms. Requires 2m <= L.
double total_boundary_sum(const PhaseSeries& series, std::int64_t m);

}  // namespace sigmatau::detail
