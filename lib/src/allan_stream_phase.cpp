// The running phase of the stream mode (see allan_stream_phase.hpp).
//
// Per value the double-double phase needs two error-free sums and a renormalisation, about 20
// floating-point operations, but only two of them (the high part and the low part, one addition
// each) carry from one value to the next. So the chunk is integrated in three passes: the
// vectorised split y_i - y0bar = d_i + e_i (exactly), the sequential loop that carries only what
// must be carried, and the vectorised renormalisation of every point. Each point gets the same
// operations, in the same order, as the one-loop form of phase_series.cpp, so the same bits.
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include "allan_stream_phase.hpp"

#include <algorithm>

#include "simd_clones.hpp"

namespace sigmatau::detail {
namespace {

/// Values integrated per pass.
constexpr std::size_t kTile = 1024;

/// s[i] + e[i] = y[i] - offset exactly (TwoSum); returns 0 if every s[i] is finite.
SIGMATAU_SIMD_CLONES unsigned split_offset(const double* y, std::size_t n, double offset, double* s,
                                           double* e) {
  unsigned bad = 0;
  const double b = -offset;
  for (std::size_t i = 0; i < n; ++i) {
    const double a = y[i];
    const double sum = a + b;
    const double bb = sum - a;
    s[i] = sum;
    e[i] = (a - (sum - bb)) + (b - bb);
    bad |= static_cast<unsigned>(!(sum * 0.0 == 0.0));
  }
  return bad;
}

/// h[i], l[i] = TwoSum(h[i], l[i]) in place.
SIGMATAU_SIMD_CLONES void renormalise(double* h, double* l, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    const double a = h[i];
    const double b = l[i];
    const double sum = a + b;
    const double bb = sum - a;
    h[i] = sum;
    l[i] = (a - (sum - bb)) + (b - bb);
  }
}

/// The carried part: h[i], l[i] hold d_i, e_i on entry and the running high and low parts on
/// return (before renormalisation). Only hh = hh + d and ll = ll + (...) carry between values.
void carry(double* h, double* l, std::size_t n, double& hh, double& ll) {
  double a = hh, c = ll;
  for (std::size_t i = 0; i < n; ++i) {
    const double d = h[i];
    const double s = a + d;
    const double bb = s - a;
    const double err = (a - (s - bb)) + (d - bb);
    c += err + l[i];
    a = s;
    h[i] = a;
    l[i] = c;
  }
  hh = a;
  ll = c;
}

}  // namespace

bool StreamPhase::integrate(std::span<const double> y, std::int64_t samples_before, double* nh,
                            double* nl) {
  std::size_t w = 0;  // points written
  if (!started_) {
    started_ = true;
    if (kind_ == DataKind::phase) {
      offset_ = y[0];
    } else {
      long double total = 0;
      for (const double v : y) total += v;
      offset_ = static_cast<double>(total / static_cast<long double>(y.size()));
      nh[0] = 0.0;
      nl[0] = 0.0;
      w = 1;
    }
  }
  double* h = nh + w;
  double* l = nl + w;
  if (kind_ == DataKind::phase) return split_offset(y.data(), y.size(), offset_, h, l) == 0;
  // Pieces of at most kTile values (the three passes stay in the L1 cache), ending where the
  // whole stream reaches a multiple of kRenormalise values.
  unsigned bad = 0;
  std::size_t i = 0;
  while (i < y.size()) {
    const std::int64_t done = samples_before + static_cast<std::int64_t>(i);
    const std::size_t len = std::min<std::size_t>(
        {y.size() - i, kTile, static_cast<std::size_t>(kRenormalise - done % kRenormalise)});
    bad |= split_offset(y.data() + i, len, offset_, h + i, l + i);
    carry(h + i, l + i, len, h_, l_);
    renormalise(h + i, l + i, len);
    if ((done + static_cast<std::int64_t>(len)) % kRenormalise == 0) {
      h_ = h[i + len - 1];
      l_ = l[i + len - 1];
    }
    i += len;
  }
  return bad == 0 && (h_ * 0.0 == 0.0);
}

void StreamPhase::running_sum(const double* nh, const double* nl, std::size_t count, double* ph,
                              double* pl) {
  for (std::size_t k = 0; k < count; ++k) {
    ph[k] = p_run_.hi;
    pl[k] = p_run_.lo;
    p_run_.add(nh[k], nl[k]);
  }
}

}  // namespace sigmatau::detail
