#pragma once
// Internal: the inner loops of the overlapping sweep (allan_sweep.cpp, which compiles them for
// several instruction sets with floating-point contraction off). Included only there.
//
// Every kernel sums the squares of kTermBlock or fewer terms in kLanes lanes: term r of a block
// goes to lane r mod kLanes, each lane is summed in plain double in ascending r, and the lanes
// are added pairwise at the end (lane_total). Kernels that compute several factors at once
// (fused_*) keep one set of lanes per factor and do, per lane, exactly what the one-factor
// kernels do, so a factor's block total is the same bit for bit whichever kernel computes it.

#include <cstdint>

#if defined(__GNUC__) || defined(__clang__)
#define SIGMATAU_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define SIGMATAU_ALWAYS_INLINE inline
#endif

namespace sigmatau::detail::sweep {

/// Independent accumulators per inner loop (one AVX-512 register, two AVX2 registers); it also
/// bounds the length of each plain-double partial sum to kTermBlock / kLanes terms.
constexpr int kLanes = 8;
/// Start points per plain-double partial sum (then carried in double-double): each lane sums
/// kTermBlock / kLanes = 256 squares, as in the other sums (allan_sums.cpp).
constexpr std::int64_t kTermBlock = 2048;
/// Most factors a fused kernel computes together (registers: one accumulator per factor).
constexpr int kFusedMax = 6;

SIGMATAU_ALWAYS_INLINE double lane_total(const double (&acc)[kLanes]) {
  // Pairwise: ((0+1)+(2+3)) + ((4+5)+(6+7)).
  return ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]));
}

/// D2 or D3 at start points n0 .. n0 + len - 1 of the double-double phase, squared and summed.
template <int Order>
SIGMATAU_ALWAYS_INLINE double block_sum_squares(const double* h, const double* l, std::int64_t m,
                                                std::int64_t n0, std::int64_t len) {
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
    // so its own rounding (~2^-106 of the phase) is negligible and it may take the cheaper form.
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

/// Sum over r in [r0, r1) of (D(r) + c)^2, where D is the offset part of the Order-th difference
/// at start point r: D2 = (o2 + o0) - 2 o1, D3 = (o3 - o0) + 3 (o1 - o2) (o_j = the offset
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

/// Eight doubles, one per lane (GCC/Clang vector extension: one AVX-512 register, two AVX2 or
/// four SSE2 registers; element-wise operations, so each lane computes exactly what the scalar
/// code computes).
using Lanes = double __attribute__((vector_size(kLanes * sizeof(double))));
SIGMATAU_ALWAYS_INLINE void load_lanes(Lanes& v, const double* p) { __builtin_memcpy(&v, p, sizeof v); }
SIGMATAU_ALWAYS_INLINE double lane_total(const Lanes& a) {
  return ((a[0] + a[1]) + (a[2] + a[3])) + ((a[4] + a[5]) + (a[6] + a[7]));
}

/// One full term block (kTermBlock start points from o) of G octave factors m0, 2 m0, ...,
/// 2^(G-1) m0 together on the compact phase: the phase point factors share (n + 2^g m0 is the
/// middle point of factor g and the last of factor g - 1) is loaded once. Each factor's term is
/// that of compact_segment with base part c[g] (adding an exact zero does not change a square),
/// in the same lane; out[g] is its lane total. The kTermBlock points from `prefetch` are
/// requested into the second-level cache on the way.
template <int Order, int G>
SIGMATAU_ALWAYS_INLINE void fused_compact_block(const double* o, std::int64_t m0, const double* c,
                                                double* out, const double* prefetch) {
  Lanes acc[G];
  Lanes base[G];
  for (int g = 0; g < G; ++g) {
    acc[g] = Lanes{};
    base[g] = Lanes{} + c[g];
  }
  for (std::int64_t i = 0; i < kTermBlock; i += kLanes) {
    // One cache line of a segment a later block will need, spread over the loop.
    __builtin_prefetch(prefetch + i, 0, 2);
    Lanes x0, x1;
    load_lanes(x0, o + i);
    load_lanes(x1, o + m0 + i);
    for (int g = 0; g < G; ++g) {
      Lanes x2, e;
      load_lanes(x2, o + (m0 << (g + 1)) + i);
      if constexpr (Order == 2) {
        e = ((x2 + x0) - 2.0 * x1) + base[g];
      } else {
        Lanes x3;
        load_lanes(x3, o + 3 * (m0 << g) + i);
        e = ((x3 - x0) + 3.0 * (x1 - x2)) + base[g];
      }
      acc[g] += e * e;
      x1 = x2;
    }
  }
  for (int g = 0; g < G; ++g) out[g] = lane_total(acc[g]);
}


/// One full term block of G octave factors m0, ..., 2^(G-1) m0 together on the double-double
/// phase (h, l point at the first start point): the terms of block_sum_squares, per lane, with
/// the points factors share loaded once. out[g] is factor g's lane total.
template <int Order, int G>
SIGMATAU_ALWAYS_INLINE void fused_dd_block(const double* h, const double* l, std::int64_t m0,
                                           double* out) {
  Lanes acc[G];
  for (int g = 0; g < G; ++g) acc[g] = Lanes{};
  for (std::int64_t i = 0; i < kTermBlock; i += kLanes) {
    Lanes h0, l0, h1, l1;
    load_lanes(h0, h + i);
    load_lanes(l0, l + i);
    load_lanes(h1, h + m0 + i);
    load_lanes(l1, l + m0 + i);
    for (int g = 0; g < G; ++g) {
      const std::int64_t m2 = m0 << (g + 1);
      Lanes h2, l2, d;
      load_lanes(h2, h + m2 + i);
      load_lanes(l2, l + m2 + i);
      if constexpr (Order == 2) {
        const Lanes dh = (h2 - h1) - (h1 - h0);
        const Lanes dl = (l2 + l0) - 2.0 * l1;
        d = dh + dl;
      } else {
        const std::int64_t m3 = 3 * (m0 << g);
        Lanes h3, l3;
        load_lanes(h3, h + m3 + i);
        load_lanes(l3, l + m3 + i);
        const Lanes w0 = (h1 - h0) + (l1 - l0);
        const Lanes w1 = (h2 - h1) + (l2 - l1);
        const Lanes w2 = (h3 - h2) + (l3 - l2);
        d = (w2 - w1) - (w1 - w0);
      }
      acc[g] += d * d;
      h1 = h2;
      l1 = l2;
    }
  }
  for (int g = 0; g < G; ++g) out[g] = lane_total(acc[g]);
}

}  // namespace sigmatau::detail::sweep
