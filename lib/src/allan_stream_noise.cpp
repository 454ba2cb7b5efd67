// One-pass noise identification sums of the stream mode (see allan_stream_noise.hpp).
//
// The lane loops are compiled for AVX-512, AVX2 and the baseline (the loader picks one); with
// floating-point contraction off, every build does the same operations in the same order and
// the sums are identical bit for bit.
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include "allan_stream_noise.hpp"
#include "simd_clones.hpp"

#include <limits>

namespace sigmatau::detail {
namespace {

constexpr std::size_t kLanes = 8;

/// a[1..len) into the lanes: b = a[i] - shift and p = a[i-1] - shift; element 1 + j of the main
/// loop goes to lane j mod kLanes, the elements after the last full group of kLanes to lanes
/// 0, 1, ... (as the scalar loop always did).
SIGMATAU_SIMD_CLONES void lag1_lanes(const double* a, std::size_t len, double shift,
                                      double (&t1)[kLanes], double (&t2)[kLanes],
                                      double (&t12)[kLanes]) {
  // One vector of kLanes doubles per sum (GCC/Clang vector extension, element-wise).
  using Lanes = double __attribute__((vector_size(kLanes * sizeof(double))));
  Lanes s1, s2, s12;
  __builtin_memcpy(&s1, t1, sizeof s1);
  __builtin_memcpy(&s2, t2, sizeof s2);
  __builtin_memcpy(&s12, t12, sizeof s12);
  std::size_t i = 1;
  for (; i + kLanes <= len; i += kLanes) {
    Lanes b, p;
    __builtin_memcpy(&b, a + i, sizeof b);
    __builtin_memcpy(&p, a + i - 1, sizeof p);
    b = b - shift;
    p = p - shift;
    s1 += b;
    s2 += b * b;
    s12 += p * b;
  }
  __builtin_memcpy(t1, &s1, sizeof s1);
  __builtin_memcpy(t2, &s2, sizeof s2);
  __builtin_memcpy(t12, &s12, sizeof s12);
  for (std::size_t k = 0; i < len; ++i, ++k) {
    const double b = a[i] - shift;
    const double p = a[i - 1] - shift;
    t1[k] += b;
    t2[k] += b * b;
    t12[k] += p * b;
  }
}

/// out[i] = in[i] - in[i-1] for i in [1, len).
SIGMATAU_SIMD_CLONES void first_differences(const double* in, std::size_t len, double* out) {
  for (std::size_t i = 1; i < len; ++i) out[i] = in[i] - in[i - 1];
}

}  // namespace

void AcfSums::add_block(const double* a, std::size_t len) {
  if (len == 0) return;
  if (n == 0) {
    shift = a[0];
    first = 0.0;
  }
  double t1[kLanes] = {}, t2[kLanes] = {}, t12[kLanes] = {};
  const double before = n > 0 ? last : 0.0;  // 0: no lag-1 product for the first value
  const double b = a[0] - shift;
  t1[0] += b;
  t2[0] += b * b;
  t12[0] += before * b;
  lag1_lanes(a, len, shift, t1, t2, t12);
  for (std::size_t k = 0; k < kLanes; ++k) {
    s1.add(t1[k]);
    s2.add(t2[k]);
    s12.add(t12[k]);
  }
  last = a[len - 1] - shift;
  n += static_cast<std::int64_t>(len);
}

double AcfSums::r1() const {
  if (n < 2) return std::numeric_limits<double>::quiet_NaN();
  using ld = long double;
  const ld nn = static_cast<ld>(n);
  const ld S1 = static_cast<ld>(s1.hi) + s1.lo;
  const ld S2 = static_cast<ld>(s2.hi) + s2.lo;
  const ld S12 = static_cast<ld>(s12.hi) + s12.lo;
  const ld mean = S1 / nn;
  const ld den = S2 - nn * mean * mean;
  const ld num = S12 - mean * (S1 - last) - mean * (S1 - first) + (nn - 1) * mean * mean;
  if (!(den > 0)) return std::numeric_limits<double>::quiet_NaN();
  return static_cast<double>(num / den);
}

void NoiseState::flush() {
  // Series d + 1 is series d differenced: its first value is taken against the last value of
  // series d from the previous chunk, or dropped if series d had none yet.
  std::size_t start = 0;
  for (int d = 0; d < 4 && start < batch.size(); ++d) {
    const bool had = sums[d].n > 0;
    const double before = previous[d];
    sums[d].add_block(batch.data() + start, batch.size() - start);
    previous[d] = batch.back();
    if (d == 3) break;  // no series 4
    spare.resize(batch.size());
    first_differences(batch.data() + start, batch.size() - start, spare.data() + start);
    if (had) {
      spare[start] = batch[start] - before;
    } else {
      ++start;
    }
    batch.swap(spare);
  }
  batch.clear();
}

}  // namespace sigmatau::detail
