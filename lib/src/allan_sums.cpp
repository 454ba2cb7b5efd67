// Sums of squared phase differences for the Allan family (see allan_sums.hpp for the glossary):
// the strided (ADEV, HDEV), modified (MDEV, TDEV) and TOTDEV boundary sums. The overlapping
// sweep (OADEV, OHDEV, the TOTDEV interior) is in allan_sweep.cpp.
//
// Speed: the inner loops are written with kLanes explicit, independent accumulators over separate
// hi / lo streams, which GCC and Clang vectorise for any x86-64 level without changing the order
// of the floating-point operations (results are identical for SSE2, AVX2 and AVX-512 builds).
// The modified sums of several factors run in lock step, one factor per vector lane
// (modified_sums): each factor's running sum is a chain of dependent additions, so one factor
// alone leaves the floating-point units waiting on latency. Floating-point contraction is off in
// this file, so the AVX-512 clones cannot fuse a multiplication and an addition (every clone
// gives the same bits).
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include "allan_sums.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "allan_dd.hpp"
#include "parallel_items.hpp"
#include "sigmatau/error.hpp"
#include "simd_clones.hpp"

namespace sigmatau::detail {
namespace {

/// Independent accumulators per inner loop: enough for two AVX-512 registers, and it bounds the
/// length of each plain-double partial sum to (block length) / kLanes terms.
constexpr int kLanes = 8;
/// Terms per plain-double block in the strided, modified and boundary sums (same reason).
constexpr std::int64_t kBlock = 1024;

double lane_total(const double (&acc)[kLanes]) {
  // Pairwise: ((0+1)+(2+3)) + ((4+5)+(6+7)).
  return ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]));
}

/// W(k, m) from raw hi/lo pointers: (hi[k+m] - hi[k]) + (lo[k+m] - lo[k]).
inline double window(const double* h, const double* l, std::int64_t a, std::int64_t b) {
  return (h[b] - h[a]) + (l[b] - l[a]);
}

/// out[t] = D2(n0 + t) for t < len (not squared): the terms the modified sum runs over.
SIGMATAU_AVX2_CLONES void fill_d2(const double* h, const double* l, std::int64_t m, std::int64_t n0, std::int64_t len,
             double* out) {
  const double* h0 = h + n0;
  const double* l0 = l + n0;
  const double* h1 = h0 + m;
  const double* l1 = l0 + m;
  const double* h2 = h1 + m;
  const double* l2 = l1 + m;
  for (std::int64_t i = 0; i < len; ++i) {
    out[i] = ((h2[i] - h1[i]) + (l2[i] - l1[i])) - ((h1[i] - h0[i]) + (l1[i] - l0[i]));
  }
}

/// out[t] = D2(n0 + t) from the compact phase: ((o2 + o0) - 2 o1) + c, c the base part.
SIGMATAU_AVX2_CLONES void fill_d2_compact(const double* o, std::int64_t m, std::int64_t n0,
                                          std::int64_t len, double c, double* out) {
  const double* o0 = o + n0;
  const double* o1 = o0 + m;
  const double* o2 = o1 + m;
  for (std::int64_t i = 0; i < len; ++i) out[i] = ((o2[i] + o0[i]) - 2.0 * o1[i]) + c;
}

/// Where the modified sums' D2 come from. Factors from kCompactBlock that are multiples of
/// kBlock read the compact phase (one double a point: half the memory traffic, which is what
/// bounds the far-apart points of large factors): every fill of the modified sums covers start
/// points within one aligned run of kBlock, so for such m the points n, n + m and n + 2m of a
/// fill each stay in one base block and the base part is one constant per fill. D2(n) is then
/// the same value whichever fill computes it (as lead or as trail), so V still telescopes
/// exactly. Smaller factors read the double-double phase: their D2 can be smaller than the
/// phase excursion within a base block, which bounds the offsets' accuracy (as in the sweep).
struct D2Source {
  const double* h = nullptr;
  const double* l = nullptr;
  const CompactPhase* compact = nullptr;

  static bool compact_suits(std::int64_t m) { return m >= kCompactBlock && m % kBlock == 0; }

  void fill(std::int64_t m, std::int64_t n0, std::int64_t len, double* out) const {
    if (compact != nullptr && compact_suits(m)) {
      SIGMATAU_ASSERT(n0 % kBlock + len <= kBlock, "a compact fill stays in one aligned run");
      fill_d2_compact(compact->offset.data(), m, n0, len, compact_base_d2(*compact, n0, m), out);
    } else {
      fill_d2(h, l, m, n0, len, out);
    }
  }
};

}  // namespace

double strided_sum(const PhaseSeries& series, int order, std::int64_t m, std::int64_t count) {
  SIGMATAU_ASSERT(order == 2 || order == 3, "difference order must be 2 or 3");
  const double* h = series.hi().data();
  const double* l = series.lo().data();
  DoubleDouble total;
  for (std::int64_t k0 = 0; k0 < count; k0 += kBlock) {
    const std::int64_t k1 = std::min(count, k0 + kBlock);
    double acc[kLanes] = {};
    for (std::int64_t k = k0; k < k1; ++k) {
      const std::int64_t n = k * m;
      const double w0 = window(h, l, n, n + m);
      const double w1 = window(h, l, n + m, n + 2 * m);
      double d = w1 - w0;
      if (order == 3) d = (window(h, l, n + 2 * m, n + 3 * m) - w1) - d;
      acc[(k - k0) % kLanes] += d * d;
    }
    total.add(lane_total(acc));
  }
  return total.value();
}

namespace {

/// The running state of one factor's modified sum: V(j) = s + c, and the total of the blocks
/// done so far.
struct ModifiedState {
  double s = 0.0;
  double c = 0.0;
  DoubleDouble total;
};

/// ring[(n mod ring.size())] = D2(n) for the n in [n0, n0 + len); the ring's size is a power of
/// two at least len.
void put_in_ring(std::span<double> ring, std::int64_t n0, std::int64_t len, const double* d2) {
  const auto size = static_cast<std::int64_t>(ring.size());
  const std::int64_t at = n0 & (size - 1);
  const std::int64_t first = std::min(len, size - at);
  std::copy_n(d2, first, ring.begin() + at);
  std::copy_n(d2 + first, len - first, ring.begin());
}

/// V(j0) = sum of D2(j0..j0+m-1), accurately; `buffer` holds kBlock doubles. With a ring, the
/// D2 also go into it (put_in_ring).
ModifiedState modified_start(const D2Source& phase, std::int64_t m, std::int64_t j0,
                             double* buffer, std::span<double> ring = {}) {
  DoubleDouble v0;
  for (std::int64_t i0 = 0; i0 < m; i0 += kBlock) {
    const std::int64_t len = std::min(kBlock, m - i0);
    phase.fill(m, j0 + i0, len, buffer);
    if (!ring.empty()) put_in_ring(ring, j0 + i0, len, buffer);
    double acc[kLanes] = {};
    for (std::int64_t t = 0; t < len; ++t) acc[t % kLanes] += buffer[t];
    v0.add(lane_total(acc));
  }
  return {v0.hi, v0.lo, {}};
}

/// The blocks of one factor's modified sum from start point j_begin (a multiple of kBlock) up
/// to j_end (a multiple of kBlock, or count), one factor at a time, added to state.total.
/// `lead`, `trail` hold kBlock doubles.
void modified_finish(const D2Source& phase, std::int64_t m, std::int64_t count,
                     ModifiedState& state, std::int64_t j_begin, std::int64_t j_end,
                     double* lead, double* trail) {
  // V(j+1) = V(j) + D2(j+m) - D2(j): each of the two additions is error-free transformed (the
  // running value is s + c), so V carries no drift however long the series; (s, c) is
  // renormalised after every block.
  double s = state.s;
  double c = state.c;
  const std::int64_t transitions = count - 1;  // D2(j+m) exists for j <= count - 2
  for (std::int64_t j0 = j_begin; j0 < j_end; j0 += kBlock) {
    const std::int64_t len = std::min(kBlock, j_end - j0);
    const std::int64_t steps = std::min(len, transitions - j0);
    if (steps > 0) {
      phase.fill(m, j0 + m, steps, lead);
      phase.fill(m, j0, steps, trail);
    }
    double acc[kLanes] = {};
    for (std::int64_t t = 0; t < len; ++t) {
      const double v = s + c;
      acc[t % kLanes] += v * v;
      if (t < steps) {
        const SumAndError a = two_sum(s, lead[t]);
        const SumAndError b = two_sum(a.sum, -trail[t]);
        s = b.sum;
        c += a.err + b.err;
      }
    }
    const SumAndError r = two_sum(s, c);
    s = r.sum;
    c = r.err;
    state.total.add(lane_total(acc));
  }
  state.s = s;
  state.c = c;
}

/// Factors run in lock step by modified_sums: one per lane of a vector of kLanes doubles
/// (GCC/Clang vector extension; element-wise operations, so each lane computes exactly what
/// modified_finish computes for its factor).
constexpr int kFactorLanes = kLanes;
using Lanes = double __attribute__((vector_size(kFactorLanes * sizeof(double))));

/// Steps per lock-step chunk: the D2 rows of a chunk (2 x kChunk x kFactorLanes doubles,
/// 32 KiB) stay in the first-level cache between their filling and their use.
constexpr std::int64_t kChunk = 256;
/// Factors up to this keep their D2 in a ring (modified_piece): at most 8 x 32 KiB.
constexpr std::int64_t kRingMost = 2048;
static_assert(kBlock % kChunk == 0 && kChunk % kLanes == 0, "blocks are made of chunks");

/// One row of kChunk D2 values per factor.
using Rows = const double* [kFactorLanes];

/// Rows row[g][t] (factor g, step t) at steps t..t+kFactorLanes-1 as kFactorLanes vectors,
/// vector k holding step t + k of every factor: an 8 x 8 transpose in three rounds of shuffles
/// (pairs, then quads, then halves), data movement only.
[[gnu::always_inline]] inline void transpose_rows(const Rows& row, std::int64_t t, Lanes (&out)[kFactorLanes]) {
  static_assert(kFactorLanes == 8, "the shuffles are written for 8 x 8");
  Lanes r[8];
  for (int g = 0; g < 8; ++g) __builtin_memcpy(&r[g], row[g] + t, sizeof(Lanes));
  Lanes p[8];
  for (int g = 0; g < 8; g += 2) {
    p[g] = __builtin_shufflevector(r[g], r[g + 1], 0, 8, 2, 10, 4, 12, 6, 14);
    p[g + 1] = __builtin_shufflevector(r[g], r[g + 1], 1, 9, 3, 11, 5, 13, 7, 15);
  }
  Lanes q[8];
  for (int g = 0; g < 8; g += 4) {
    q[g] = __builtin_shufflevector(p[g], p[g + 2], 0, 1, 8, 9, 4, 5, 12, 13);
    q[g + 2] = __builtin_shufflevector(p[g], p[g + 2], 2, 3, 10, 11, 6, 7, 14, 15);
    q[g + 1] = __builtin_shufflevector(p[g + 1], p[g + 3], 0, 1, 8, 9, 4, 5, 12, 13);
    q[g + 3] = __builtin_shufflevector(p[g + 1], p[g + 3], 2, 3, 10, 11, 6, 7, 14, 15);
  }
  for (int k = 0; k < 4; ++k) {
    out[k] = __builtin_shufflevector(q[k], q[k + 4], 0, 1, 2, 3, 8, 9, 10, 11);
    out[k + 4] = __builtin_shufflevector(q[k], q[k + 4], 4, 5, 6, 7, 12, 13, 14, 15);
  }
}

/// The running values and lanes of kFactorLanes factors in lock step.
struct LockStep {
  Lanes s, c;
  Lanes acc[kLanes];
};

/// One chunk (kChunk steps) of modified_finish for kFactorLanes factors at once: lead[g] and
/// trail[g] hold D2(j + m + t) and D2(j + t) of factor g at [t] (one row per factor, as the
/// fills write them; turned into one vector per step by transpose_rows). Steps within a block
/// go to the block's lanes acc[t mod kLanes], as in modified_finish.
SIGMATAU_SIMD_CLONES void modified_chunk_lanes(const Rows& lead, const Rows& trail,
                                                LockStep& state) {
  Lanes s = state.s;
  Lanes c = state.c;
  Lanes acc[kLanes];
  for (int k = 0; k < kLanes; ++k) acc[k] = state.acc[k];
  static_assert(kLanes == kFactorLanes, "a transposed block is one block of lanes");
  for (std::int64_t t = 0; t < kChunk; t += kLanes) {
    Lanes ups[kFactorLanes], downs[kFactorLanes];
    transpose_rows(lead, t, ups);
    transpose_rows(trail, t, downs);
    for (int k = 0; k < kLanes; ++k) {
      const Lanes up = ups[k];
      const Lanes down = -downs[k];
      const Lanes v = s + c;
      acc[k] += v * v;
      // two_sum(s, up), then two_sum(that, -down), as in modified_finish.
      const Lanes as = s + up;
      const Lanes ab = as - s;
      const Lanes ae = (s - (as - ab)) + (up - ab);
      const Lanes bs = as + down;
      const Lanes bb = bs - as;
      const Lanes be = (as - (bs - bb)) + (down - bb);
      s = bs;
      c += ae + be;
    }
  }
  state.s = s;
  state.c = c;
  for (int k = 0; k < kLanes; ++k) state.acc[k] = acc[k];
}

/// The end of a block in lock step: (s, c) renormalised as in modified_finish, block_total[g]
/// the block's lane total of factor g, and the lanes cleared for the next block.
void modified_block_end(LockStep& state, double* block_total) {
  const Lanes rs = state.s + state.c;
  const Lanes rb = rs - state.s;
  state.c = (state.s - (rs - rb)) + (state.c - rb);
  state.s = rs;
  const Lanes* a = state.acc;
  const Lanes total = ((a[0] + a[1]) + (a[2] + a[3])) + ((a[4] + a[5]) + (a[6] + a[7]));
  __builtin_memcpy(block_total, &total, sizeof total);
  for (int k = 0; k < kLanes; ++k) state.acc[k] = Lanes{};
}

}  // namespace

namespace {

/// Each factor's start points are cut in kPieces pieces at block boundaries that depend on the
/// series' length and the factor's term count alone (not on the threads or on the other
/// factors), so that threads can share even a single factor, and the last pieces to be taken
/// are short: piece p is [cut(p), cut(p + 1)), and each piece starts from its V(cut(p))
/// computed afresh. The factor's sum is the pieces' totals added in order. A cut is at the same
/// point (p / kPieces of the series) for every factor that reaches it, so the factors of a group
/// still read shared phase points in every piece (n + 2m of factor m is n + m' of m' = 2m).
constexpr int kPieces = 4;
std::int64_t modified_cut(std::int64_t points, std::int64_t count, int p) {
  if (p == 0) return 0;
  if (p == kPieces) return count;
  return std::min(points / kPieces * p, count - 1) / kBlock * kBlock;
}

/// One piece (0 <= piece < kPieces) of modified_sums for the factors m (at most kFactorLanes,
/// ascending): the piece's sum of V^2 of each factor, into totals.
void modified_piece(const D2Source& phase, std::int64_t points, std::span<const std::int64_t> m,
                    std::span<const std::int64_t> counts, int piece,
                    std::span<DoubleDouble> totals) {
  // modified_start and modified_finish use kBlock doubles of lead and trail; the lock step one
  // row of kChunk per factor of each.
  std::vector<double> lead(static_cast<std::size_t>(std::max(kBlock, kChunk * kFactorLanes)));
  std::vector<double> trail(static_cast<std::size_t>(std::max(kBlock, kChunk * kFactorLanes)));
  const std::size_t G = m.size();
  SIGMATAU_ASSERT(G <= kFactorLanes, "a group has at most kFactorLanes factors");
  ModifiedState state[kFactorLanes];
  std::int64_t first[kFactorLanes] = {};  // the piece's first block
  std::int64_t locked[kFactorLanes] = {};  // its blocks with kBlock steps, done in lock step
  std::int64_t end[kFactorLanes] = {};     // the piece's end (start point)
  std::int64_t most = 0;
  LockStep lanes{};
  double block_total[kFactorLanes];
  // Small factors keep the D2 they compute as lead in a ring of the last >= m + kChunk values
  // (a power of two, so a chunk's trail row, aligned to kChunk, is contiguous in it): their
  // trail is then read, not computed again from the double-double phase. The ring starts with
  // the D2 that modified_start sums. Large factors' rings would not stay in cache; they compute
  // their trail row as they compute their lead row.
  std::vector<double> rings[kFactorLanes];
  for (std::size_t g = 0; g < G; ++g) {
    if (m[g] <= kRingMost) {
      rings[g].resize(std::bit_ceil(static_cast<std::uint64_t>(m[g] + kChunk)));
    }
  }
  for (std::size_t g = 0; g < G; ++g) {
    const std::int64_t begin = modified_cut(points, counts[g], piece);
    end[g] = modified_cut(points, counts[g], piece + 1);
    first[g] = begin / kBlock;
    // Block b has kBlock steps when (b + 1) kBlock <= count - 1 (modified_finish's steps).
    const std::int64_t full = G > 1 ? (counts[g] - 1) / kBlock : 0;
    locked[g] = std::max<std::int64_t>(0, std::min(full, end[g] / kBlock) - first[g]);
    most = std::max(most, locked[g]);
    state[g] = begin < end[g] ? modified_start(phase, m[g], begin, lead.data(), rings[g])
                              : ModifiedState{};
    lanes.s[g] = state[g].s;
    lanes.c[g] = state[g].c;
  }
  // A finished factor's lane (and an unused one) idles on zeros (and is not read again).
  std::fill(lead.begin(), lead.end(), 0.0);
  std::fill(trail.begin(), trail.end(), 0.0);
  Rows lead_rows, trail_rows;
  for (int g = 0; g < kFactorLanes; ++g) {
    lead_rows[g] = lead.data() + g * kChunk;
    trail_rows[g] = trail.data() + g * kChunk;
  }
  for (std::int64_t b = 0; b < most; ++b) {
    for (std::int64_t t = 0; t < kBlock; t += kChunk) {
      for (std::size_t g = 0; g < G; ++g) {
        if (b >= locked[g]) continue;
        const std::int64_t mg = m[g];
        const std::int64_t j = (first[g] + b) * kBlock + t;
        double* lead_row = lead.data() + g * kChunk;
        phase.fill(mg, j + mg, kChunk, lead_row);
        if (rings[g].empty()) {
          phase.fill(mg, j, kChunk, trail.data() + g * kChunk);
        } else {
          // D2(j..j+kChunk) went in as lead (or at the start) and are still there: the ring
          // holds >= m + kChunk values, and those written since are D2(j+kChunk..j+m+kChunk).
          put_in_ring(rings[g], j + mg, kChunk, lead_row);
          const auto size = static_cast<std::int64_t>(rings[g].size());
          trail_rows[g] = rings[g].data() + (j & (size - 1));
        }
      }
      modified_chunk_lanes(lead_rows, trail_rows, lanes);
    }
    modified_block_end(lanes, block_total);
    for (std::size_t g = 0; g < G; ++g) {
      if (b >= locked[g]) continue;
      state[g].s = lanes.s[g];
      state[g].c = lanes.c[g];
      state[g].total.add(block_total[g]);
      if (b + 1 == locked[g]) {
        std::fill_n(lead.begin() + static_cast<std::ptrdiff_t>(g * kChunk), kChunk, 0.0);
        std::fill_n(trail.begin() + static_cast<std::ptrdiff_t>(g * kChunk), kChunk, 0.0);
        trail_rows[g] = trail.data() + g * kChunk;
      }
    }
  }
  for (std::size_t g = 0; g < G; ++g) {
    modified_finish(phase, m[g], counts[g], state[g], (first[g] + locked[g]) * kBlock, end[g],
                    lead.data(), trail.data());
    totals[g] = state[g].total;
  }
}

}  // namespace

std::vector<double> modified_sums(const PhaseSeries& series, std::span<const std::int64_t> m,
                                  std::span<const std::int64_t> counts, unsigned threads) {
  SIGMATAU_ASSERT(m.size() == counts.size(), "one count per factor");
  D2Source phase{series.hi().data(), series.lo().data(), nullptr};
  std::shared_ptr<const CompactPhase> compact;
  if (std::any_of(m.begin(), m.end(), D2Source::compact_suits)) {
    compact = compact_phase(series);
    phase.compact = compact.get();
  }
  // Groups of kFactorLanes factors (the last one fewer), consecutive in the order given
  // (ascending factors have similar term counts, so few lanes idle; full groups leave no lane
  // idle where the work is, among the many steps of the small factors); each group's pieces
  // are tasks that threads take in turn, the group of the largest factors first (the factors
  // whose phase points lie far apart take the longest per term).
  const std::size_t groups = (m.size() + kFactorLanes - 1) / kFactorLanes;
  std::vector<DoubleDouble> piece_totals[kPieces];
  for (auto& p : piece_totals) p.resize(m.size());
  for_each_item_parallel(kPieces * groups, std::max(1u, threads), [&](std::size_t task) {
    const std::size_t k = groups - 1 - task / kPieces;
    const int piece = static_cast<int>(task % kPieces);
    const std::size_t a = k * kFactorLanes;
    const std::size_t b = std::min(m.size(), a + kFactorLanes);
    modified_piece(phase, series.size(), m.subspan(a, b - a), counts.subspan(a, b - a), piece,
                   std::span(piece_totals[piece]).subspan(a, b - a));
  });
  std::vector<double> sums(m.size(), 0.0);
  for (std::size_t t = 0; t < m.size(); ++t) {
    DoubleDouble total = piece_totals[0][t];
    for (int p = 1; p < kPieces; ++p) total.add(piece_totals[p][t].hi, piece_totals[p][t].lo);
    sums[t] = total.value();
  }
  return sums;
}

double total_boundary_sum(const PhaseSeries& series, std::int64_t m) {
  const double* h = series.hi().data();
  const double* l = series.lo().data();
  const std::int64_t L = series.size() - 1;
  SIGMATAU_ASSERT(2 * m <= L + 1, "total variance needs 2m <= N");
  DoubleDouble total;
  // Lower end, i = 1..m-1: x*[i-m] = -x[m-i] (x[0] = 0), so
  // x*[i-m] - 2x*[i] + x*[i+m] = W(i, m) - (x[i] + x[m-i]).
  // Upper end, i = L-m+1..L-1: x*[i+m] = 2x[L] - x[2L-i-m], so
  // x*[i+m] - x[i] = W(2L-i-m, i+m-L) + W(i, L-i) and the term is that minus W(i-m, m).
  for (int end = 0; end < 2; ++end) {
    for (std::int64_t k0 = 1; k0 < m; k0 += kBlock) {
      const std::int64_t k1 = std::min(m, k0 + kBlock);
      double acc[kLanes] = {};
      for (std::int64_t k = k0; k < k1; ++k) {
        double d;
        if (end == 0) {
          const std::int64_t i = k;
          const double reflected = (h[i] + h[m - i]) + (l[i] + l[m - i]);
          d = window(h, l, i, i + m) - reflected;
        } else {
          const std::int64_t i = L - m + k;
          const double up = window(h, l, 2 * L - i - m, L) + window(h, l, i, L);
          d = up - window(h, l, i - m, i);
        }
        acc[k % kLanes] += d * d;
      }
      total.add(lane_total(acc));
    }
  }
  return total.value();
}

}  // namespace sigmatau::detail
