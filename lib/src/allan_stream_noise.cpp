// One-pass noise identification of the stream mode (see allan_stream_noise.hpp).
//
// Every z value is read once: the differenced series 1..3 are formed in registers from z and
// the kHistory values before it, as d1[i] = z[i] - z[i-1], d2[i] = d1[i] - d1[i-1], d3[i] =
// d2[i] - d2[i-1] (the same operations as differencing the whole series one order at a time,
// so the same values bit for bit), and all sums of all orders are accumulated in the same loop,
// in kLanes plain-double lanes (value i of a call goes to lane i mod kLanes), carried into
// double-double after each chunk. The loop is compiled for AVX-512, AVX2 and the baseline; with
// floating-point contraction off every build gives the same bits.
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include "allan_stream_noise.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "sigmatau/phase_series.hpp"
#include "simd_clones.hpp"

#if defined(__GNUC__) || defined(__clang__)
#define SIGMATAU_NOISE_INLINE inline __attribute__((always_inline))
#else
#define SIGMATAU_NOISE_INLINE inline
#endif

namespace sigmatau::detail {
namespace {

constexpr int kLanes = NoiseSums::kLanes;
/// Differencing stops once r1 / (1 + r1) is below this value (confidence.cpp).
constexpr double kStationaryDelta = 0.25;
using LaneSums = double[4][3][kLanes];

/// z at p differenced d times (d <= 3), as the series would be differenced one order at a time:
/// D0 = z[0], Dd = D(d-1) at p minus D(d-1) at p - 1 (reads p[-d .. 0]).
SIGMATAU_NOISE_INLINE double difference(const double* p, int d) {
  switch (d) {
    case 0:
      return p[0];
    case 1:
      return p[0] - p[-1];
    case 2:
      return (p[0] - p[-1]) - (p[-1] - p[-2]);
    default:
      return ((p[0] - p[-1]) - (p[-1] - p[-2])) - ((p[-1] - p[-2]) - (p[-2] - p[-3]));
  }
}

/// Sums of `Orders` series over z[0 .. len) (z[-kHistory .. -1] readable), every series already
/// started (its shift set and a value before z[0]).
template <int Orders>
SIGMATAU_NOISE_INLINE void lag1_sums(const double* z, std::size_t len, const double (&shift)[4],
                                     LaneSums& out) {
  // One vector of kLanes doubles per sum (GCC/Clang vector extension, element-wise).
  using Lanes = double __attribute__((vector_size(kLanes * sizeof(double))));
  Lanes acc[Orders][3];
  for (int d = 0; d < Orders; ++d) {
    for (int s = 0; s < 3; ++s) __builtin_memcpy(&acc[d][s], out[d][s], sizeof(Lanes));
  }
  std::size_t i = 0;
  for (; i + kLanes <= len; i += kLanes) {
    Lanes z0, z1, z2, z3;
    __builtin_memcpy(&z0, z + i, sizeof z0);
    __builtin_memcpy(&z1, z + i - 1, sizeof z1);
    __builtin_memcpy(&z2, z + i - 2, sizeof z2);
    __builtin_memcpy(&z3, z + i - 3, sizeof z3);
    Lanes cur[4], prev[4];
    cur[0] = z0;
    prev[0] = z1;
    const Lanes a1 = z0 - z1, b1 = z1 - z2, c1 = z2 - z3;
    cur[1] = a1;
    prev[1] = b1;
    cur[2] = a1 - b1;
    prev[2] = b1 - c1;
    if constexpr (Orders == 4) {
      Lanes z4;
      __builtin_memcpy(&z4, z + i - 4, sizeof z4);
      const Lanes c2 = c1 - (z3 - z4);
      cur[3] = cur[2] - prev[2];
      prev[3] = prev[2] - c2;
    }
    for (int d = 0; d < Orders; ++d) {
      const Lanes b = cur[d] - shift[d];
      const Lanes p = prev[d] - shift[d];
      acc[d][0] += b;
      acc[d][1] += b * b;
      acc[d][2] += p * b;
    }
  }
  for (int d = 0; d < Orders; ++d) {
    for (int s = 0; s < 3; ++s) __builtin_memcpy(out[d][s], &acc[d][s], sizeof(Lanes));
  }
  for (std::size_t k = 0; i < len; ++i, ++k) {
    for (int d = 0; d < Orders; ++d) {
      const double b = difference(z + i, d) - shift[d];
      const double p = difference(z + i - 1, d) - shift[d];
      out[d][0][k] += b;
      out[d][1][k] += b * b;
      out[d][2][k] += p * b;
    }
  }
}

SIGMATAU_SIMD_CLONES void lag1_sums_3(const double* z, std::size_t len, const double (&shift)[4],
                                      LaneSums& out) {
  lag1_sums<3>(z, len, shift, out);
}
SIGMATAU_SIMD_CLONES void lag1_sums_4(const double* z, std::size_t len, const double (&shift)[4],
                                      LaneSums& out) {
  lag1_sums<4>(z, len, shift, out);
}

/// The difference order identify_noise uses (MDEV is an Allan variance).
int noise_order(Statistic s) { return (s == Statistic::hdev || s == Statistic::ohdev) ? 3 : 2; }

}  // namespace

SIGMATAU_SIMD_CLONES void mean_rates(const double* h, const double* l, std::size_t count,
                                     double inv_m, double* out) {
  for (std::size_t j = 0; j < count; ++j) out[j] = ((h[j] - h[j - 1]) + (l[j] - l[j - 1])) * inv_m;
}

double AcfSums::r1() const {
  if (n < 2) return std::numeric_limits<double>::quiet_NaN();
  using ld = long double;
  const ld nn = static_cast<ld>(n);
  const ld S1 = static_cast<ld>(s1.hi) + s1.lo;
  const ld S2 = static_cast<ld>(s2.hi) + s2.lo;
  const ld S12 = static_cast<ld>(s12.hi) + s12.lo;
  const ld first = 0;  // the first value minus shift
  const ld mean = S1 / nn;
  const ld den = S2 - nn * mean * mean;
  const ld num = S12 - mean * (S1 - last) - mean * (S1 - first) + (nn - 1) * mean * mean;
  if (!(den > 0)) return std::numeric_limits<double>::quiet_NaN();
  return static_cast<double>(num / den);
}

NoiseSums::NoiseSums(int orders) : orders_(std::clamp(orders, 3, 4)) {}

void NoiseSums::add(double* buffer, std::size_t count) {
  if (count == 0) return;
  std::memcpy(buffer, history_, sizeof history_);
  double* z = buffer + kHistory;
  double shift[4];
  for (int d = 0; d < 4; ++d) shift[d] = sums_[d].shift;
  // The first `orders_` values of the whole series, one by one: series d starts at value d
  // (its first value sets its shift and adds nothing to the sums).
  std::size_t i = 0;
  for (; i < count && count_ + static_cast<std::int64_t>(i) < orders_; ++i) {
    const std::int64_t g = count_ + static_cast<std::int64_t>(i);
    for (int d = 0; d < orders_ && d <= g; ++d) {
      const double v = difference(z + i, d);
      if (d == g) {
        shift[d] = sums_[d].shift = v;
        continue;
      }
      const double b = v - shift[d];
      const double p = difference(z + i - 1, d) - shift[d];
      lanes_[d][0][0] += b;
      lanes_[d][1][0] += b * b;
      lanes_[d][2][0] += p * b;
    }
  }
  if (orders_ == 4) {
    lag1_sums_4(z + i, count - i, shift, lanes_);
  } else {
    lag1_sums_3(z + i, count - i, shift, lanes_);
  }
  // The last kHistory values of history + new values.
  std::memcpy(history_, buffer + count, sizeof history_);
  count_ += static_cast<std::int64_t>(count);
  uncarried_ += static_cast<std::int64_t>(count);
  if (uncarried_ >= kCarryEvery) carry();
}

void NoiseSums::carry() {
  uncarried_ = 0;
  for (int d = 0; d < orders_; ++d) {
    AcfSums& sums = sums_[d];
    for (int k = 0; k < kLanes; ++k) {
      sums.s1.add(lanes_[d][0][k]);
      sums.s2.add(lanes_[d][1][k]);
      sums.s12.add(lanes_[d][2][k]);
      lanes_[d][0][k] = lanes_[d][1][k] = lanes_[d][2][k] = 0.0;
    }
    sums.n = std::max<std::int64_t>(0, count_ - d);
    if (sums.n > 0) sums.last = difference(history_ + kHistory - 1, d) - sums.shift;
  }
}

NoiseIdentification NoiseSums::identify(Statistic statistic, DataKind kind, std::int64_t m,
                                        double tau0_s) const {
  if (uncarried_ > 0) {  // the sums as they would be after a carry(), the state unchanged
    NoiseSums carried = *this;
    carried.carry();
    return carried.identify(statistic, kind, m, tau0_s);
  }
  NoiseIdentification result;
  const int d_max = noise_order(statistic);
  const int lowest = d_max == 3 ? -4 : -2;
  int alpha = 0;
  if (sums_[0].n >= kMinAcfPoints) {
    result.method = NoiseIdentification::Method::lag1_acf;
    bool found = false;
    for (int d = 0; d < orders_; ++d) {
      const double r1 = sums_[d].r1();
      if (std::isnan(r1)) break;
      const double delta = r1 / (1 + r1);
      if (delta < kStationaryDelta || d >= d_max || sums_[d].n < 3) {
        alpha =
            -static_cast<int>(std::lround(2 * delta)) - 2 * d + (kind == DataKind::phase ? 2 : 0);
        found = true;
        break;
      }
    }
    if (!found) {
      alpha = 0;
      result.method = NoiseIdentification::Method::assumed;
    }
  } else if (kept_.size() >= 3) {
    // The few m-sample means (or decimated phase points) as a short series at m' = 1.
    std::vector<double> z;
    if (kind == DataKind::phase) {
      z = kept_;
    } else {
      for (std::size_t k = 1; k < kept_.size(); ++k) {
        z.push_back((kept_[k] - kept_[k - 1]) / static_cast<double>(m));
      }
    }
    const PhaseSeries shortened =
        PhaseSeries::from_samples(z, kind, tau0_s * static_cast<double>(m));
    return identify_noise(shortened, statistic, 1);
  } else {
    result.method = NoiseIdentification::Method::assumed;
  }
  result.alpha = std::clamp(alpha, lowest, 2);
  return result;
}

std::size_t NoiseSums::memory_bytes() const {
  return sizeof(NoiseSums) + kept_.capacity() * sizeof(double);
}

}  // namespace sigmatau::detail
