// The overlapping sweep (OADEV, OHDEV and the interior of TOTDEV): sums of squared second or
// third differences at every start point, for many averaging factors at once (see
// allan_sums.hpp for the glossary).
//
// Speed: the inner loops are written with kLanes explicit, independent accumulators over separate
// streams, which GCC and Clang vectorise for any x86-64 level without changing the order of the
// floating-point operations. The hot loops are compiled for AVX-512, AVX2 and the baseline
// (function multi-versioning; the loader picks one), and floating-point contraction is off in
// this file: an AVX-512 build may not fuse a multiplication and an addition into one FMA (one
// rounding instead of two), so every build gives the same results, bit for bit.
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include <algorithm>
#include <cstdint>
#include <future>
#include <memory>
#include <mutex>
#include <system_error>

#include "allan_dd.hpp"
#include "allan_sums.hpp"
#include "allan_sweep_kernels.hpp"
#include "phase_spill.hpp"
#include "phase_store.hpp"
#include "sigmatau/error.hpp"
#include "simd_clones.hpp"

namespace sigmatau::detail {
namespace {

using namespace sweep;

/// Start points per block of the sweep over the compact phase (factors >= kCompactMin). Within a
/// block every factor reads its three or four phase segments of kSweepBlock points (8 bytes a
/// point). Octave factors share segments (offset n + 2m of factor m is offset n + m' of factor
/// m' = 2m), so a block's ~15 distinct segments stay in cache while the factors of a group use
/// them, and each segment streams from memory once per block in long runs that the hardware
/// prefetchers follow.
constexpr std::int64_t kSweepBlock = 65536;
constexpr std::size_t kSweepGroup = 32;
/// Most octave factors swept together by chains (chain_sweep): the window of phase segments a
/// chain keeps, (order 2^(G-1) + 1) x kTermBlock points, stays within 1 MiB.
constexpr std::size_t kChainGroup2 = 6;
constexpr std::size_t kChainGroup3 = 5;
static_assert(kChainGroup2 <= kFusedMax && kChainGroup3 <= kFusedMax, "groups fit the kernels");
/// Points per base block of the compact phase (CompactPhase): offsets are measured from a base
/// point at most this far back, so they hold the phase excursion over at most 4096 samples and
/// are accurate to ~1 ulp of it. A divisor of kSweepBlock.
constexpr std::int64_t kBaseBlock = kCompactBlock;
static_assert(kSweepBlock % kBaseBlock == 0 && kBaseBlock % kTermBlock == 0,
              "sweep blocks are made of base blocks, base blocks of term blocks");
/// Factors from which the compact phase is used. Below, the in-block excursion of the phase that
/// limits the offsets' accuracy (up to kBaseBlock samples of local drift) could exceed the window
/// sums of the factor itself by a factor kBaseBlock / m, so small factors read the double-double
/// phase.
constexpr std::int64_t kCompactMin = kBaseBlock;
/// With spilled (file-backed) storage, the loops check the process's resident budget after about
/// this many bytes of phase read or written (enforce_spill_budget), so that a starved watchdog
/// thread cannot let the resident set grow with the length of the log.
constexpr std::int64_t kBudgetCheckBytes = std::int64_t{8} << 20;

SIGMATAU_SIMD_CLONES double sum_squares_d2(const double* h, const double* l, std::int64_t m,
                                            std::int64_t n0, std::int64_t len) {
  return block_sum_squares<2>(h, l, m, n0, len);
}
SIGMATAU_SIMD_CLONES double sum_squares_d3(const double* h, const double* l, std::int64_t m,
                                            std::int64_t n0, std::int64_t len) {
  return block_sum_squares<3>(h, l, m, n0, len);
}

SIGMATAU_SIMD_CLONES void compact_d2(const double* o0, std::int64_t m, std::int64_t r0,
                                      std::int64_t r1, double c, double (&acc)[kLanes]) {
  // c == 0 (all three points in one base block, the common case for m much smaller than the
  // block) saves one addition per term; adding an exact 0 would not change any term.
  if (c == 0.0) {
    compact_segment<2, false>(o0, m, r0, r1, c, acc);
  } else {
    compact_segment<2, true>(o0, m, r0, r1, c, acc);
  }
}
SIGMATAU_SIMD_CLONES void compact_d3(const double* o0, std::int64_t m, std::int64_t r0,
                                      std::int64_t r1, double c, double (&acc)[kLanes]) {
  compact_segment<3, true>(o0, m, r0, r1, c, acc);
}

/// Calls Kernel<G>::run(args...) for G = 2..kFusedMax.
template <template <int> class Kernel, class... Args>
SIGMATAU_ALWAYS_INLINE void with_group_size(int G, Args... args) {
  switch (G) {
    case 2: Kernel<2>::run(args...); break;
    case 3: Kernel<3>::run(args...); break;
    case 4: Kernel<4>::run(args...); break;
    case 5: Kernel<5>::run(args...); break;
    case 6: Kernel<6>::run(args...); break;
    default: SIGMATAU_ASSERT(false, "fused kernels take 2 to kFusedMax factors");
  }
}
static_assert(kFusedMax == 6, "with_group_size covers 2..6");

template <int Order>
struct FusedCompact {
  template <int G>
  struct Kernel {
    SIGMATAU_ALWAYS_INLINE static void run(const double* o, std::int64_t m0, const double* c, double* out,
                    const double* prefetch) {
      fused_compact_block<Order, G>(o, m0, c, out, prefetch);
    }
  };
};
template <int Order>
struct FusedDd {
  template <int G>
  struct Kernel {
    SIGMATAU_ALWAYS_INLINE static void run(const double* h, const double* l, std::int64_t m0,
                                           double* out) {
      fused_dd_block<Order, G>(h, l, m0, out);
    }
  };
};

SIGMATAU_SIMD_CLONES void fused_compact(int order, int G, const double* o, std::int64_t m0,
                                         const double* c, double* out, const double* prefetch) {
  if (order == 2) {
    with_group_size<FusedCompact<2>::Kernel>(G, o, m0, c, out, prefetch);
  } else {
    with_group_size<FusedCompact<3>::Kernel>(G, o, m0, c, out, prefetch);
  }
}
SIGMATAU_SIMD_CLONES void fused_dd(int order, int G, const double* h, const double* l,
                                    std::int64_t m0, double* out) {
  if (order == 2) {
    with_group_size<FusedDd<2>::Kernel>(G, h, l, m0, out);
  } else {
    with_group_size<FusedDd<3>::Kernel>(G, h, l, m0, out);
  }
}

/// Splits o[k] = x[k] - base[k / kBaseBlock] (see CompactPhase) from the double-double phase,
/// one base block at a time.
SIGMATAU_SIMD_CLONES void split_block(const double* h, const double* l, std::int64_t len,
                                       double bh, double bl, double* o) {
  for (std::int64_t i = 0; i < len; ++i) o[i] = (h[i] - bh) + (l[i] - bl);
}

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

/// A run of factors computed together: m[first], 2 m[first], ..., 2^(size-1) m[first].
struct FactorGroup {
  std::size_t first = 0;
  std::size_t size = 1;
};

/// Splits m into groups: runs of consecutive entries that double (and, with `base_multiples`,
/// are multiples of kBaseBlock), each run cut into near-equal groups of at most max_group;
/// every other factor is a group of one.
std::vector<FactorGroup> octave_groups(std::span<const std::int64_t> m, bool base_multiples,
                                       std::size_t max_group) {
  std::vector<FactorGroup> groups;
  std::size_t t = 0;
  while (t < m.size()) {
    std::size_t end = t + 1;
    if (!base_multiples || m[t] % kBaseBlock == 0) {
      while (end < m.size() && m[end] == 2 * m[end - 1]) ++end;
    }
    const std::size_t run = end - t;
    const std::size_t parts = (run + max_group - 1) / max_group;
    for (std::size_t g = 0; g < parts; ++g) {
      const std::size_t a = t + run * g / parts;
      const std::size_t b = t + run * (g + 1) / parts;
      groups.push_back({a, b - a});
    }
    t = end;
  }
  return groups;
}

/// Whether every factor of the group has a full term block at start point n0.
bool full_block(const FactorGroup& group, std::span<const std::int64_t> counts, std::int64_t n0) {
  for (std::size_t t = group.first; t < group.first + group.size; ++t) {
    if (n0 + kTermBlock > counts[t]) return false;
  }
  return true;
}

/// Factors below kCompactMin, on the double-double phase: term blocks in the outer loop and
/// factors in the inner one, so the few kilobytes of phase a term block reads stay in cache for
/// every factor, and octave runs go through the fused kernel. Each factor's block totals are
/// added in ascending order, as in a sweep of that factor alone.
void small_factor_sweep(const double* h, const double* l, bool spilled, int order,
                        std::span<const std::int64_t> m, std::span<const std::int64_t> counts,
                        std::span<DoubleDouble> acc) {
  if (m.empty()) return;
  const std::vector<FactorGroup> groups = octave_groups(m, false, kFusedMax);
  const std::int64_t max_count = *std::max_element(counts.begin(), counts.end());
  constexpr std::int64_t kCheckEvery = kBudgetCheckBytes / (16 * kTermBlock);  // term blocks
  for (std::int64_t b0 = 0; b0 < max_count; b0 += kTermBlock) {
    if (spilled && (b0 / kTermBlock) % kCheckEvery == 0) enforce_spill_budget();
    for (const FactorGroup& group : groups) {
      if (group.size > 1 && full_block(group, counts, b0)) {
        double out[kFusedMax];
        fused_dd(order, static_cast<int>(group.size), h + b0, l + b0, m[group.first], out);
        for (std::size_t g = 0; g < group.size; ++g) acc[group.first + g].add(out[g]);
        continue;
      }
      for (std::size_t t = group.first; t < group.first + group.size; ++t) {
        if (b0 >= counts[t]) continue;
        const std::int64_t len = std::min(kTermBlock, counts[t] - b0);
        acc[t].add(order == 2 ? sum_squares_d2(h, l, m[t], b0, len)
                              : sum_squares_d3(h, l, m[t], b0, len));
      }
    }
  }
}

/// Factors from kCompactMin on, on the compact phase, kSweepBlock start points at a time.
void compact_sweep(const CompactPhase& phase, int order, std::span<const std::int64_t> m,
                   std::span<const std::int64_t> counts, std::span<DoubleDouble> acc) {
  if (m.empty()) return;
  const double* o = phase.offset.data();
  std::vector<std::int64_t> cuts;
  const std::int64_t max_count = *std::max_element(counts.begin(), counts.end());
  for (std::int64_t n0 = 0; n0 < max_count; n0 += kSweepBlock) {
    if (phase.offset.spilled()) enforce_spill_budget();  // ~15 segments of 512 KiB a block
    for (std::size_t t = 0; t < m.size(); ++t) {
      const std::int64_t end = std::min(n0 + kSweepBlock, counts[t]);
      for (std::int64_t b0 = n0; b0 < end; b0 += kTermBlock) {
        const std::int64_t len = std::min(kTermBlock, end - b0);
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
          const double c = base_difference(phase.base, blocks, order);
          if (order == 2) {
            compact_d2(o + b0, m[t], r0, r1, c, lanes);
          } else {
            compact_d3(o + b0, m[t], r0, r1, c, lanes);
          }
        }
        acc[t].add(lane_total(lanes));
      }
    }
  }
}

/// A group of octave factors m0, 2 m0, ... (m0 a multiple of kBaseBlock) on the compact phase,
/// by chains: for each residue r0 (a multiple of kTermBlock below m0), the term blocks at
/// n0 = r0, r0 + m0, r0 + 2 m0, ... in turn. Every point a step reads lies a multiple of m0
/// after n0, so consecutive steps read the same phase segments but one (a window of
/// order 2^(G-1) + 1 segments of kTermBlock points, which stays in the second-level cache):
/// each phase point comes from memory once per group instead of about once per factor.
/// A term block lies within one base block at each of its points (m0 and n0 are multiples of
/// kTermBlock, and kBaseBlock = 2 kTermBlock divides m0), so its base part is one constant.
/// Blocks are summed as compact_sweep sums them (same lanes, same order within a block); their
/// totals are kept and added in ascending order at the end, so the result is the same bit for
/// bit.
void chain_sweep(const CompactPhase& phase, int order, std::span<const std::int64_t> m,
                 std::span<const std::int64_t> counts, std::span<DoubleDouble> acc) {
  const std::size_t G = m.size();
  SIGMATAU_ASSERT(G >= 2 && G <= static_cast<std::size_t>(kFusedMax) && m[0] % kBaseBlock == 0,
                  "chain groups hold 2 to kFusedMax octave factors, multiples of the base block");
  const FactorGroup group{0, G};
  const std::int64_t m0 = m[0];
  const double* o = phase.offset.data();
  const std::int64_t size = static_cast<std::int64_t>(phase.offset.size());
  std::vector<std::vector<double>> totals(G);
  for (std::size_t i = 0; i < G; ++i) {
    totals[i].resize(static_cast<std::size_t>((counts[i] + kTermBlock - 1) / kTermBlock));
  }
  const std::int64_t max_count = *std::max_element(counts.begin(), counts.end());
  // The farthest point of a step, relative to n0: the last point of the largest factor.
  const std::int64_t reach = order * m[G - 1];
  const bool spilled = phase.offset.spilled();
  constexpr std::int64_t kCheckEvery = kBudgetCheckBytes / (8 * kTermBlock);  // steps
  std::int64_t steps = 0;
  for (std::int64_t r0 = 0; r0 < m0; r0 += kTermBlock) {
    for (std::int64_t n0 = r0; n0 < max_count; n0 += m0) {
      if (spilled && steps++ % kCheckEvery == 0) enforce_spill_budget();  // a segment a step
      double c[kFusedMax] = {};
      for (std::size_t i = 0; i < G; ++i) {
        if (n0 >= counts[i]) continue;
        std::int64_t blocks[4];
        for (int j = 0; j <= order; ++j) blocks[j] = (n0 + j * m[i]) / kBaseBlock;
        c[i] = base_difference(phase.base, blocks, order);
      }
      const auto block = static_cast<std::size_t>(n0 / kTermBlock);
      if (full_block(group, counts, n0)) {
        // The segment new to the window two steps from now goes to the cache meanwhile.
        const std::int64_t ahead = n0 + 2 * m0 + reach;
        const double* prefetch = ahead + kTermBlock <= size ? o + ahead : o + n0;
        double out[kFusedMax];
        fused_compact(order, static_cast<int>(G), o + n0, m0, c, out, prefetch);
        for (std::size_t i = 0; i < G; ++i) totals[i][block] = out[i];
        continue;
      }
      for (std::size_t i = 0; i < G; ++i) {
        if (n0 >= counts[i]) continue;
        const std::int64_t len = std::min(kTermBlock, counts[i] - n0);
        double lanes[kLanes] = {};
        if (order == 2) {
          compact_d2(o + n0, m[i], 0, len, c[i], lanes);
        } else {
          compact_d3(o + n0, m[i], 0, len, c[i], lanes);
        }
        totals[i][block] = lane_total(lanes);
      }
    }
  }
  for (std::size_t i = 0; i < G; ++i) {
    for (const double total : totals[i]) acc[i].add(total);
  }
}

}  // namespace

namespace {
DoubleBuffer compact_storage(const PhaseSeries& series, std::vector<double>&& memory) {
  const auto n = static_cast<std::size_t>(series.size());
  if (!series.spilled() && memory.capacity() >= n) return DoubleBuffer(std::move(memory), n);
  return DoubleBuffer(n, series.store().storage);
}
}  // namespace

CompactPhase::CompactPhase(const PhaseSeries& series, std::vector<double> memory)
    : offset(compact_storage(series, std::move(memory))) {
  // The buffer asks for 2 MiB pages where Linux allows them (phase_spill.cpp): the sweep
  // touches ~15 distant places of the array per block, and with 4 KiB pages each costs TLB misses.
  const double* h = series.hi().data();
  const double* l = series.lo().data();
  const std::int64_t N = series.size();
  base.resize(static_cast<std::size_t>((N + kBaseBlock - 1) / kBaseBlock));
  constexpr std::int64_t kCheckEvery = kBudgetCheckBytes / (24 * kBaseBlock);  // base blocks
  for (std::int64_t b = 0; b * kBaseBlock < N; ++b) {
    if (offset.spilled() && b % kCheckEvery == 0) enforce_spill_budget();
    const std::int64_t k0 = b * kBaseBlock;
    base[static_cast<std::size_t>(b)] = {h[k0], l[k0]};
    split_block(h + k0, l + k0, std::min(kBaseBlock, N - k0), h[k0], l[k0],
                offset.data() + k0);
  }
}

double compact_base_d2(const CompactPhase& phase, std::int64_t n, std::int64_t m) {
  const std::int64_t b[3] = {n / kBaseBlock, (n + m) / kBaseBlock, (n + 2 * m) / kBaseBlock};
  return base_difference(phase.base, b, 2);
}

std::shared_ptr<const CompactPhase> compact_phase(const PhaseSeries& series) {
  PhaseStore& store = series.store();
  std::lock_guard lock(store.mutex);
  if (!store.compact) {
    store.compact = std::make_shared<const CompactPhase>(series, std::move(store.recycled));
    std::vector<double>().swap(store.recycled);
  }
  return store.compact;
}

double sum_squares(const double* h, const double* l, int order, std::int64_t m, std::int64_t n0,
                   std::int64_t len) {
  return order == 2 ? sum_squares_d2(h, l, m, n0, len) : sum_squares_d3(h, l, m, n0, len);
}

std::vector<double> overlapping_sums(const PhaseSeries& series, int order,
                                     std::span<const std::int64_t> m,
                                     std::span<const std::int64_t> counts, unsigned threads) {
  SIGMATAU_ASSERT(order == 2 || order == 3, "difference order must be 2 or 3");
  SIGMATAU_ASSERT(m.size() == counts.size(), "one count per factor");
  std::vector<double> sums(m.size(), 0.0);
  // Factors below kCompactMin read the double-double phase, the others the compact phase.
  std::vector<std::int64_t> small_m, small_counts, large_m, large_counts;
  for (std::size_t t = 0; t < m.size(); ++t) {
    (m[t] < kCompactMin ? small_m : large_m).push_back(m[t]);
    (m[t] < kCompactMin ? small_counts : large_counts).push_back(counts[t]);
  }
  std::vector<DoubleDouble> small_acc(small_m.size()), large_acc(large_m.size());
  const auto small_sweep = [&] {
    small_factor_sweep(series.hi().data(), series.lo().data(), series.spilled(), order, small_m,
                       small_counts, small_acc);
  };
  // The two sets share nothing but the (read-only) phase: with a second thread the small
  // factors are swept beside the large ones (each accumulator is the same either way). Not
  // for spilled storage, where two sweeps would compete for the resident budget.
  std::future<void> beside;
  if (threads > 1 && !small_m.empty() && !large_m.empty() && !series.spilled()) {
    try {
      beside = std::async(std::launch::async, small_sweep);
    } catch (const std::system_error&) {
      // no thread to be had (a resource limit): below, on this one
    }
  }
  if (!beside.valid()) small_sweep();
  // Should the large sweep throw (std::bad_alloc), `beside` waits for the small one as it is
  // destroyed (a std::async future does), before small_acc goes.
  if (!large_m.empty()) {
    const std::shared_ptr<const CompactPhase> phase = compact_phase(series);
    // Octave runs (multiples of kBaseBlock) by chains; every other factor by blocks.
    std::vector<std::int64_t> other_m, other_counts;
    std::vector<std::size_t> other_index;
    for (const FactorGroup& group :
         octave_groups(large_m, true, order == 2 ? kChainGroup2 : kChainGroup3)) {
      if (group.size > 1) {
        chain_sweep(*phase, order, std::span(large_m).subspan(group.first, group.size),
                    std::span(large_counts).subspan(group.first, group.size),
                    std::span(large_acc).subspan(group.first, group.size));
        continue;
      }
      other_m.push_back(large_m[group.first]);
      other_counts.push_back(large_counts[group.first]);
      other_index.push_back(group.first);
    }
    std::vector<DoubleDouble> other_acc(other_m.size());
    for (std::size_t g0 = 0; g0 < other_m.size(); g0 += kSweepGroup) {
      const std::size_t g = std::min(other_m.size() - g0, kSweepGroup);
      compact_sweep(*phase, order, std::span(other_m).subspan(g0, g),
                    std::span(other_counts).subspan(g0, g), std::span(other_acc).subspan(g0, g));
    }
    for (std::size_t k = 0; k < other_m.size(); ++k) large_acc[other_index[k]] = other_acc[k];
  }
  if (beside.valid()) beside.get();
  std::size_t next_small = 0, next_large = 0;
  for (std::size_t t = 0; t < m.size(); ++t) {
    sums[t] = (m[t] < kCompactMin ? small_acc[next_small++] : large_acc[next_large++]).value();
  }
  return sums;
}

}  // namespace sigmatau::detail
