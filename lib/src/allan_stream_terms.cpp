// The sum of one strided estimator of the stream mode (see allan_stream_terms.hpp).
//
// A term block is summed as allan_sums' sum_squares sums it: term r of the block in lane
// r mod kLanes, each lane in ascending r, the lanes added pairwise at the end; the octave
// kernel does the same per tau (compiled for several instruction sets, contraction off: the
// same bits in every build).
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include "allan_stream_terms.hpp"

#include <algorithm>
#include <vector>

#include "allan_sums.hpp"
#include "simd_clones.hpp"

namespace sigmatau::detail {
namespace {

/// Terms per call of the lane kernel (each lane's plain-double sum stays short, as in
/// allan_sums).
constexpr std::int64_t kKernelTerms = 2048;
constexpr int kLanes = 8;
/// Most taus the octave kernel sums together.
constexpr int kOctaveMax = 6;

using Lanes = double __attribute__((vector_size(kLanes * sizeof(double))));

/// One full block of kKernelTerms terms of G taus with lags q0, 2 q0, ..., 2^(G-1) q0 whose
/// terms end at the same points: h, l point at the last point of the first term (the term of
/// lag q ending at e is D2 = x[e] - 2 x[e - q] + x[e - 2q]). out[g] is the block total of tau g.
template <int G>
inline __attribute__((always_inline)) void octave_block(const double* h, const double* l,
                                                        std::int64_t q0, double* out) {
  Lanes acc[G];
  for (int g = 0; g < G; ++g) acc[g] = Lanes{};
  for (std::int64_t i = 0; i < kKernelTerms; i += kLanes) {
    Lanes h2, l2, h1, l1;
    __builtin_memcpy(&h2, h + i, sizeof h2);
    __builtin_memcpy(&l2, l + i, sizeof l2);
    __builtin_memcpy(&h1, h + i - q0, sizeof h1);
    __builtin_memcpy(&l1, l + i - q0, sizeof l1);
    for (int g = 0; g < G; ++g) {
      // The first point of lag 2^g q0 is the middle point of lag 2^(g+1) q0.
      const std::int64_t first = q0 << (g + 1);
      Lanes h0, l0;
      __builtin_memcpy(&h0, h + i - first, sizeof h0);
      __builtin_memcpy(&l0, l + i - first, sizeof l0);
      const Lanes dh = (h2 - h1) - (h1 - h0);
      const Lanes dl = (l2 + l0) - 2.0 * l1;
      const Lanes d = dh + dl;
      acc[g] += d * d;
      h1 = h0;
      l1 = l0;
    }
  }
  for (int g = 0; g < G; ++g) {
    const Lanes& a = acc[g];
    out[g] = ((a[0] + a[1]) + (a[2] + a[3])) + ((a[4] + a[5]) + (a[6] + a[7]));
  }
}

SIGMATAU_SIMD_CLONES void octave_blocks(int G, const double* h, const double* l, std::int64_t q0,
                                        double* out) {
  switch (G) {
    case 2:
      octave_block<2>(h, l, q0, out);
      break;
    case 3:
      octave_block<3>(h, l, q0, out);
      break;
    case 4:
      octave_block<4>(h, l, q0, out);
      break;
    case 5:
      octave_block<5>(h, l, q0, out);
      break;
    default:
      octave_block<6>(h, l, q0, out);
      break;
  }
}

}  // namespace

void StridedTerms::run(const Level& source) {
  // P[k] is known for k < points too (it lags x by one; P[points] follows with the next point,
  // so MDEV terms end one point later than they could: finish_running_sum() adds the last).
  const std::int64_t end = running_sum ? source.p_end() : source.x_end();
  const std::int64_t span = static_cast<std::int64_t>(order) * lag;
  const double* hh = running_sum ? source.ph.data() : source.xh.data();
  const double* ll = running_sum ? source.pl.data() : source.xl.data();
  if (step == 1) {
    while (next + span < end) {
      const std::int64_t len = std::min(kKernelTerms, end - span - next);
      sum.add(sum_squares(hh, ll, order, lag, next - source.begin, len));
      terms += len;
      next += len;
    }
  } else {
    double acc = 0.0;
    for (; next + span < end; next += step) {
      acc += sum_squares(hh, ll, order, lag, next - source.begin, 1);
      ++terms;
    }
    sum.add(acc);
  }
}

void StridedTerms::finish_running_sum(const Level& source, DoubleDouble p_total,
                                      std::int64_t points) {
  // Levels whose stride divides N hold P[N] as their next entry.
  if (!running_sum || points % source.stride != 0) return;
  Level extended = source;
  extended.ph.push_back(p_total.hi);
  extended.pl.push_back(p_total.lo);
  const std::int64_t span = 3 * lag;
  const std::int64_t end = extended.p_end();
  for (; next + span < end; next += step) {
    sum.add(sum_squares(extended.ph.data(), extended.pl.data(), 3, lag, next - extended.begin, 1));
    ++terms;
  }
}

void run_octave_blocks(std::span<StridedTerms* const> taus, const Level& source) {
  std::vector<StridedTerms*> eligible;
  for (StridedTerms* tau : taus) {
    if (tau->order == 2 && tau->step == 1 && !tau->running_sum) eligible.push_back(tau);
  }
  std::sort(eligible.begin(), eligible.end(),
            [](const StridedTerms* a, const StridedTerms* b) { return a->lag < b->lag; });
  const std::int64_t end = source.x_end();
  std::size_t a = 0;
  while (a < eligible.size()) {
    // The longest run from a: lags doubling, the next terms ending at the same point.
    const std::int64_t e = eligible[a]->next + 2 * eligible[a]->lag;
    std::size_t b = a + 1;
    while (b < eligible.size() && b - a < static_cast<std::size_t>(kOctaveMax) &&
           eligible[b]->lag == 2 * eligible[b - 1]->lag &&
           eligible[b]->next + 2 * eligible[b]->lag == e) {
      ++b;
    }
    const int G = static_cast<int>(b - a);
    if (G >= 2) {
      double out[kOctaveMax];
      // Blocks whose last term ends before `end` (run() sums a term once its last point is in).
      for (std::int64_t first_end = e; first_end + kKernelTerms <= end; first_end += kKernelTerms) {
        octave_blocks(G, source.xh.data() + (first_end - source.begin),
                      source.xl.data() + (first_end - source.begin), eligible[a]->lag, out);
        for (int g = 0; g < G; ++g) {
          StridedTerms& tau = *eligible[a + static_cast<std::size_t>(g)];
          tau.sum.add(out[g]);
          tau.terms += kKernelTerms;
          tau.next += kKernelTerms;
        }
      }
    }
    a = b;
  }
}

}  // namespace sigmatau::detail
