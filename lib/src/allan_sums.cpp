// Sums of squared phase differences for the Allan family (see allan_sums.hpp for the glossary).
//
// Speed: the inner loops are written with kLanes explicit, independent accumulators over separate
// hi / lo streams, which GCC and Clang vectorise for any x86-64 level without changing the order
// of the floating-point operations (results are identical for SSE2, AVX2 and AVX-512 builds).
#include "allan_sums.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>

#include "allan_dd.hpp"
#include "phase_store.hpp"
#include "sigmatau/error.hpp"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(SIGMATAU_NO_CLONES)
#define SIGMATAU_TARGET_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define SIGMATAU_TARGET_CLONES
#endif
#if defined(__GNUC__) || defined(__clang__)
#define SIGMATAU_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define SIGMATAU_ALWAYS_INLINE inline
#endif

namespace sigmatau::detail {
namespace {

/// Independent accumulators per inner loop: enough for two AVX-512 registers, and it bounds the
/// length of each plain-double partial sum to (block length) / kLanes terms.
constexpr int kLanes = 8;
/// Start points per block of the overlapping sweep. Within a block every factor reads its three
/// or four phase segments of kSweepBlock points (8 bytes a point in the compact form). Octave
/// factors share segments (offset n + 2m of factor m is offset n + m' of factor m' = 2m), so a
/// block's ~27 distinct segments (14 MiB) stay in the L3 cache while the factors of a group use
/// them, and each segment streams from memory once per block in long runs that the hardware
/// prefetchers follow. Measured on 1e8 samples, 25 octave factors (AMD EPYC, 32 MiB L3): 2048
/// 1.6 s, 8192 1.5 s, 32768 1.3 s, 65536 1.0 s, 131072 1.0-1.2 s.
constexpr std::int64_t kSweepBlock = 65536;
constexpr std::size_t kSweepGroup = 32;
/// Points per base block of the compact phase (CompactPhase): offsets are measured from a base
/// point at most this far back, so they hold the phase excursion over at most 4096 samples and
/// are accurate to ~1 ulp of it. A divisor of kSweepBlock.
constexpr std::int64_t kBaseBlock = 4096;
/// Start points per plain-double partial sum (then carried in double-double): bounds each lane's
/// sum of squares to kTermBlock / kLanes = 256 terms, as in the other sums.
constexpr std::int64_t kTermBlock = 2048;
static_assert(kSweepBlock % kBaseBlock == 0 && kBaseBlock % kTermBlock == 0,
              "sweep blocks are made of base blocks, base blocks of term blocks");
/// Factors from which the compact phase is used. Below, the in-block excursion of the phase that
/// limits the offsets' accuracy (up to kBaseBlock samples of local drift) could exceed the window
/// sums of the factor itself by a factor kBaseBlock / m, so small factors keep the double-double
/// phase (their segments are in cache anyway: they lie within kSweepBlock + 3 kBaseBlock points).
constexpr std::int64_t kCompactMin = kBaseBlock;
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

/// D2 or D3 at start points n0 .. n0 + len - 1, squared and summed.
template <int Order>
SIGMATAU_ALWAYS_INLINE double block_sum_squares(const double* h, const double* l, std::int64_t m, std::int64_t n0,
                         std::int64_t len) {
  const double* h0 = h + n0;
  const double* l0 = l + n0;
  const double* h1 = h0 + m;
  const double* l1 = l0 + m;
  const double* h2 = h1 + m;
  const double* l2 = l1 + m;
  double acc[kLanes] = {};
  std::int64_t i = 0;
  if constexpr (Order == 2) {
    // D2 = [(h2 - h1) - (h1 - h0)] + [(l2 + l0) - 2 l1]: the hi part is formed from window
    // differences (each rounded to ~1 ulp of a window sum); the lo part is ~2^-53 of the phase,
    // so its own rounding (~2^-106 of the phase) is negligible and it may take the cheaper form
    // (one addition fewer, one multiplication on the otherwise idle multiplier).
    for (; i + kLanes <= len; i += kLanes) {
      for (int k = 0; k < kLanes; ++k) {
        const double dh = (h2[i + k] - h1[i + k]) - (h1[i + k] - h0[i + k]);
        const double dl = (l2[i + k] + l0[i + k]) - 2.0 * l1[i + k];
        const double d = dh + dl;
        acc[k] += d * d;
      }
    }
    for (int k = 0; i < len; ++i, ++k) {
      const double d = ((h2[i] - h1[i]) - (h1[i] - h0[i])) + ((l2[i] + l0[i]) - 2.0 * l1[i]);
      acc[k] += d * d;
    }
  } else {
    const double* h3 = h2 + m;
    const double* l3 = l2 + m;
    for (; i + kLanes <= len; i += kLanes) {
      for (int k = 0; k < kLanes; ++k) {
        const double w0 = (h1[i + k] - h0[i + k]) + (l1[i + k] - l0[i + k]);
        const double w1 = (h2[i + k] - h1[i + k]) + (l2[i + k] - l1[i + k]);
        const double w2 = (h3[i + k] - h2[i + k]) + (l3[i + k] - l2[i + k]);
        const double d = (w2 - w1) - (w1 - w0);
        acc[k] += d * d;
      }
    }
    for (int k = 0; i < len; ++i, ++k) {
      const double w0 = (h1[i] - h0[i]) + (l1[i] - l0[i]);
      const double w1 = (h2[i] - h1[i]) + (l2[i] - l1[i]);
      const double w2 = (h3[i] - h2[i]) + (l3[i] - l2[i]);
      const double d = (w2 - w1) - (w1 - w0);
      acc[k] += d * d;
    }
  }
  return lane_total(acc);
}

// The two hot loops are compiled twice, for AVX2 and for the baseline, and the loader picks one
// (GCC/Clang function multi-versioning): a generic x86-64 build still runs 4-wide where it can.
// Without FMA in the AVX2 clone, both do exactly the same operations in the same order, so the
// results are identical bit for bit.
SIGMATAU_TARGET_CLONES double sum_squares_d2(const double* h, const double* l, std::int64_t m,
                                             std::int64_t n0, std::int64_t len) {
  return block_sum_squares<2>(h, l, m, n0, len);
}
SIGMATAU_TARGET_CLONES double sum_squares_d3(const double* h, const double* l, std::int64_t m,
                                             std::int64_t n0, std::int64_t len) {
  return block_sum_squares<3>(h, l, m, n0, len);
}

/// Sum over r in [r0, r1) of (D(r) + c)^2, where D is the offset part of the Order-th difference
/// at start point r: D2 = (o2 - o1) - (o1 - o0), D3 = (o3 - o0) + 3 (o1 - o2) (o_j = the offset
/// phase j m after r), and c is the base part, constant over the segment. Term r goes to lane
/// r mod kLanes of acc, so the split into segments does not change the order of the additions
/// within a lane.
template <int Order, bool WithBase>
SIGMATAU_ALWAYS_INLINE void compact_segment(const double* o0, std::int64_t m, std::int64_t r0,
                                            std::int64_t r1, double c, double (&lanes)[kLanes]) {
  // A local copy: the compiler cannot keep `lanes` in registers, as it may alias the offsets.
  double acc[kLanes];
  for (int k = 0; k < kLanes; ++k) acc[k] = lanes[k];
  const double* o1 = o0 + m;
  const double* o2 = o1 + m;
  const double* o3 = o2 + m;
  auto term = [&](std::int64_t r) {
    if constexpr (Order == 2) {
      const double e = (o2[r] + o0[r]) - 2.0 * o1[r];
      if constexpr (WithBase) {
        return e + c;
      } else {
        return e;
      }
    } else {
      return ((o3[r] - o0[r]) + 3.0 * (o1[r] - o2[r])) + c;
    }
  };
  std::int64_t r = r0;
  for (; r < r1 && r % kLanes != 0; ++r) {
    const double d = term(r);
    acc[r % kLanes] += d * d;
  }
  for (; r + kLanes <= r1; r += kLanes) {
    for (int k = 0; k < kLanes; ++k) {
      const double d = term(r + k);
      acc[k] += d * d;
    }
  }
  for (; r < r1; ++r) {
    const double d = term(r);
    acc[r % kLanes] += d * d;
  }
  for (int k = 0; k < kLanes; ++k) lanes[k] = acc[k];
}

SIGMATAU_TARGET_CLONES void compact_d2(const double* o0, std::int64_t m, std::int64_t r0,
                                       std::int64_t r1, double c, double (&acc)[kLanes]) {
  // c == 0 (all three points in one base block, the common case for m much smaller than the
  // block) saves one addition per term; adding an exact 0 would not change any term.
  if (c == 0.0) {
    compact_segment<2, false>(o0, m, r0, r1, c, acc);
  } else {
    compact_segment<2, true>(o0, m, r0, r1, c, acc);
  }
}
SIGMATAU_TARGET_CLONES void compact_d3(const double* o0, std::int64_t m, std::int64_t r0,
                                       std::int64_t r1, double c, double (&acc)[kLanes]) {
  compact_segment<3, true>(o0, m, r0, r1, c, acc);
}

/// Splits o[k] = x[k] - base[k / kBaseBlock] (see CompactPhase) from the double-double phase,
/// one base block at a time.
SIGMATAU_TARGET_CLONES void split_block(const double* h, const double* l, std::int64_t len,
                                        double bh, double bl, double* o) {
  for (std::int64_t i = 0; i < len; ++i) o[i] = (h[i] - bh) + (l[i] - bl);
}

/// out[t] = D2(n0 + t) for t < len (not squared): the terms the modified sum runs over.
SIGMATAU_TARGET_CLONES void fill_d2(const double* h, const double* l, std::int64_t m, std::int64_t n0, std::int64_t len,
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

}  // namespace

CompactPhase::CompactPhase(const PhaseSeries& series)
    : offset(static_cast<std::size_t>(series.size()), series.store().storage) {
  // The buffer asks for 2 MiB pages where Linux allows them (phase_spill.cpp): the sweep
  // touches ~27 distant places of the array per block, and with 4 KiB pages each costs TLB misses.
  const double* h = series.hi().data();
  const double* l = series.lo().data();
  const std::int64_t N = series.size();
  base.resize(static_cast<std::size_t>((N + kBaseBlock - 1) / kBaseBlock));
  for (std::int64_t b = 0; b * kBaseBlock < N; ++b) {
    const std::int64_t k0 = b * kBaseBlock;
    base[static_cast<std::size_t>(b)] = {h[k0], l[k0]};
    split_block(h + k0, l + k0, std::min(kBaseBlock, N - k0), h[k0], l[k0],
                offset.data() + k0);
  }
}

std::shared_ptr<const CompactPhase> compact_phase(const PhaseSeries& series) {
  PhaseStore& store = series.store();
  std::lock_guard lock(store.mutex);
  if (!store.compact) store.compact = std::make_shared<const CompactPhase>(series);
  return store.compact;
}

namespace {

/// a - b in double-double.
DoubleDouble dd_sub(const DoubleDouble& a, const DoubleDouble& b) {
  DoubleDouble r = a;
  r.add(-b.hi, -b.lo);
  return r;
}

/// The base part of the difference for start points whose Order + 1 phase points lie in blocks
/// b[0..Order]: (B2 - B1) - (B1 - B0), or (B3 - B0) + 3 (B1 - B2) for Order 3.
double base_difference(const std::vector<DoubleDouble>& base, const std::int64_t* b, int order) {
  auto at = [&](int j) { return base[static_cast<std::size_t>(b[j])]; };
  DoubleDouble d;
  if (order == 2) {
    d = dd_sub(dd_sub(at(2), at(1)), dd_sub(at(1), at(0)));
  } else {
    const DoubleDouble outer = dd_sub(at(3), at(0));
    const DoubleDouble inner = dd_sub(at(1), at(2));
    d = outer;
    d.add(inner.hi, inner.lo);
    d.add(inner.hi, inner.lo);
    d.add(inner.hi, inner.lo);
  }
  return d.value();
}

}  // namespace

double sum_squares(const double* h, const double* l, int order, std::int64_t m, std::int64_t n0,
                   std::int64_t len) {
  return order == 2 ? sum_squares_d2(h, l, m, n0, len) : sum_squares_d3(h, l, m, n0, len);
}

std::vector<double> overlapping_sums(const PhaseSeries& series, int order,
                                     std::span<const std::int64_t> m,
                                     std::span<const std::int64_t> counts) {
  SIGMATAU_ASSERT(order == 2 || order == 3, "difference order must be 2 or 3");
  SIGMATAU_ASSERT(m.size() == counts.size(), "one count per factor");
  std::vector<double> sums(m.size(), 0.0);
  if (m.empty()) return sums;
  const double* h = series.hi().data();
  const double* l = series.lo().data();
  std::shared_ptr<const CompactPhase> phase;
  if (*std::max_element(m.begin(), m.end()) >= kCompactMin) phase = compact_phase(series);
  const double* o = phase ? phase->offset.data() : nullptr;
  for (std::size_t g0 = 0; g0 < m.size(); g0 += kSweepGroup) {
    const std::size_t g1 = std::min(m.size(), g0 + kSweepGroup);
    std::vector<DoubleDouble> acc(g1 - g0);
    std::vector<std::int64_t> cuts;
    const std::int64_t max_count = *std::max_element(counts.begin() + g0, counts.begin() + g1);
    for (std::int64_t n0 = 0; n0 < max_count; n0 += kSweepBlock) {
      for (std::size_t t = g0; t < g1; ++t) {
        const std::int64_t end = std::min(n0 + kSweepBlock, counts[t]);
        for (std::int64_t b0 = n0; b0 < end; b0 += kTermBlock) {
          const std::int64_t len = std::min(kTermBlock, end - b0);
          if (m[t] < kCompactMin) {
            acc[t - g0].add(order == 2 ? sum_squares_d2(h, l, m[t], b0, len)
                                       : sum_squares_d3(h, l, m[t], b0, len));
            continue;
          }
          // Start points b0 + r: point j (at b0 + j m + r) enters a new base block where
          // b0 + j m + r is a multiple of kBaseBlock; between such cuts the base part is
          // constant. len <= kBaseBlock, so each point adds at most one cut.
          cuts.assign({0, len});
          for (int j = 0; j <= order; ++j) {
            const std::int64_t r = (kBaseBlock - (b0 + j * m[t]) % kBaseBlock) % kBaseBlock;
            if (r > 0 && r < len) cuts.push_back(r);
          }
          std::sort(cuts.begin(), cuts.end());
          double lanes[kLanes] = {};
          for (std::size_t s = 0; s + 1 < cuts.size(); ++s) {
            const std::int64_t r0 = cuts[s];
            const std::int64_t r1 = cuts[s + 1];
            if (r1 <= r0) continue;
            std::int64_t blocks[4];
            for (int j = 0; j <= order; ++j) blocks[j] = (b0 + j * m[t] + r0) / kBaseBlock;
            const double c = base_difference(phase->base, blocks, order);
            if (order == 2) {
              compact_d2(o + b0, m[t], r0, r1, c, lanes);
            } else {
              compact_d3(o + b0, m[t], r0, r1, c, lanes);
            }
          }
          acc[t - g0].add(lane_total(lanes));
        }
      }
    }
    for (std::size_t t = g0; t < g1; ++t) sums[t] = acc[t - g0].value();
  }
  return sums;
}

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

double modified_sum(const PhaseSeries& series, std::int64_t m, std::int64_t count) {
  const double* h = series.hi().data();
  const double* l = series.lo().data();
  // V(0) = sum of D2(0..m-1), accurately.
  DoubleDouble v0;
  std::vector<double> lead(static_cast<std::size_t>(kBlock));
  std::vector<double> trail(static_cast<std::size_t>(kBlock));
  for (std::int64_t i0 = 0; i0 < m; i0 += kBlock) {
    const std::int64_t len = std::min(kBlock, m - i0);
    fill_d2(h, l, m, i0, len, lead.data());
    double acc[kLanes] = {};
    for (std::int64_t t = 0; t < len; ++t) acc[t % kLanes] += lead[t];
    v0.add(lane_total(acc));
  }
  // V(j+1) = V(j) + D2(j+m) - D2(j): each of the two additions is error-free transformed (the
  // running value is s + c), so V carries no drift however long the series; (s, c) is
  // renormalised after every block.
  double s = v0.hi;
  double c = v0.lo;
  DoubleDouble total;
  const std::int64_t transitions = count - 1;  // D2(j+m) exists for j <= count - 2
  for (std::int64_t j0 = 0; j0 < count; j0 += kBlock) {
    const std::int64_t len = std::min(kBlock, count - j0);
    const std::int64_t steps = std::min(len, transitions - j0);
    if (steps > 0) {
      fill_d2(h, l, m, j0 + m, steps, lead.data());
      fill_d2(h, l, m, j0, steps, trail.data());
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
    total.add(lane_total(acc));
  }
  return total.value();
}

double total_boundary_sum(const PhaseSeries& series, std::int64_t m) {
  const double* h = series.hi().data();
  const double* l = series.lo().data();
  const std::int64_t L = series.size() - 1;
  SIGMATAU_ASSERT(2 * m <= L, "total variance needs 2m <= N - 1");
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
