// Sums of squared phase differences for the Allan family (see allan_sums.hpp for the glossary):
// the strided (ADEV, HDEV), modified (MDEV, TDEV) and TOTDEV boundary sums. The overlapping
// sweep (OADEV, OHDEV, the TOTDEV interior) is in allan_sweep.cpp.
//
// Speed: the inner loops are written with kLanes explicit, independent accumulators over separate
// hi / lo streams, which GCC and Clang vectorise for any x86-64 level without changing the order
// of the floating-point operations (results are identical for SSE2, AVX2 and AVX-512 builds).
#include "allan_sums.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "allan_dd.hpp"
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
