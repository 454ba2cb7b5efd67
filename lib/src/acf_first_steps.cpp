// The first steps of the lag-1 ACF noise identification (confidence.cpp) at many averaging
// factors in one pass over the phase, without storing any averaged series.
//
// Glossary (as in confidence.cpp):
//   z      series at averaging factor m: phase decimated by m (phase input), or rate averaged over
//          non-overlapping blocks of m samples; w the once-differenced series, w_i = z_{i+1} - z_i
//   d      differencing step (0: z, 1: w)
//   c      shift subtracted before summing (the first value of the series), y_i = v_i - c
//   S1, S2, S11  sums of y_i, y_i^2 and y_i y_{i+1}
//   r1     lag-1 autocorrelation, (S11 - ybar (2 S1 - y_0 - y_{n-1}) + (n-1) ybar^2) /
//          (S2 - n ybar^2) with ybar = S1 / n; delta = r1 / (1 + r1)
//
// Why the result is the one identify_noise_by_acf gives: that function computes r1 of the
// series and of its differences in long double, two passes each, and decides from delta. Here
// r1 comes from one pass in shifted double sums (blocks of at most kChunk values in four lanes,
// block totals in double-double): its error against the exact r1 stays below ~3e-12 S2 / den
// (S2 the shifted sum of squares, den the centred one), and the long double computation's below
// n 2^-63 (sum |a_i a_{i+1}| <= den) plus the effect of its mean's rounding (bounded in
// decide()). A decision is taken here only when it is the same at
// r1 - tol and r1 + tol, tol = max(1e-9 max(1, S2 / den), 4 n 2^-63), far above both errors;
// the decision (stop at this step, and the rounded 2 delta) is monotone in r1, so it is then
// the decision of the long double computation too. Everything else (a series that needs a
// second difference, r1 near a boundary, a constant or nearly constant series, values whose
// squares leave the normal range) is left to the exact identification.
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include <algorithm>
#include <cmath>
#include <limits>

#include "allan_dd.hpp"
#include "noise_identification.hpp"

namespace sigmatau::detail {
namespace {

/// Phase points per block of the pass: every factor takes the values of z whose windows start
/// in the block, so the block's hi and lo (256 KiB) are read from memory once for all factors.
constexpr std::int64_t kPhaseBlock = 16384;
/// Values per summed piece: plain-double lane sums over at most this many values, then added to
/// the double-double totals, so their rounding is that of a sum of kChunk / kLanes terms.
constexpr std::size_t kChunk = 4096;
constexpr int kLanes = 4;
/// Relative accuracy asked of r1 before a decision is taken (see the file comment).
constexpr double kRelativeTolerance = 1e-9;
/// Beyond this ratio S2 / den the shift is too far from the mean (or the series nearly
/// constant) for the shifted sums: left to the exact identification.
constexpr double kMaxShiftRatio = 1e6;
/// Mean squares outside this range: squares near underflow or overflow, left to the exact
/// identification.
constexpr double kMinMeanSquare = 1e-250;
constexpr double kMaxMeanSquare = 1e250;
/// delta below this value ends the differencing (confidence.cpp, kStationaryDelta).
constexpr double kStationaryDelta = 0.25;

/// Shifted lag sums of one series fed in pieces.
struct LagSums {
  std::int64_t n = 0;
  double c = 0.0;
  double first = 0.0;  // y_0
  double last = 0.0;   // y_{n-1}
  DoubleDouble s1, s2, s11;

  void add(const double* v, std::size_t len) {
    if (len == 0) return;
    std::size_t i = 0;
    if (n == 0) {
      c = v[0];
      first = 0.0;
      last = 0.0;
      n = 1;
      i = 1;  // y_0 = 0 adds nothing to the sums
    }
    while (i < len) {
      const std::size_t end = std::min(len, i + kChunk);
      // The pair (previous value, v[i]) first, then the lanes.
      const double y0 = v[i] - c;
      double a1[kLanes] = {}, a2[kLanes] = {}, a11[kLanes] = {};
      a1[0] = y0;
      a2[0] = y0 * y0;
      a11[0] = last * y0;
      const std::size_t count = end - i - 1;
      const double* p = v + i + 1;
      std::size_t j = 0;
      for (; j + kLanes <= count; j += kLanes) {
        for (int k = 0; k < kLanes; ++k) {
          const double y = p[j + k] - c;
          const double yp = p[j + k - 1] - c;
          a1[k] += y;
          a2[k] += y * y;
          a11[k] += yp * y;
        }
      }
      for (; j < count; ++j) {
        const double y = p[j] - c;
        const double yp = p[j - 1] - c;
        a1[0] += y;
        a2[0] += y * y;
        a11[0] += yp * y;
      }
      for (int k = 0; k < kLanes; ++k) {
        s1.add(a1[k]);
        s2.add(a2[k]);
        s11.add(a11[k]);
      }
      last = v[end - 1] - c;
      n += static_cast<std::int64_t>(end - i);
      i = end;
    }
  }
};

/// One decision of identify_by_acf from r1 (double, as it computes it): -1 when it would go on
/// differencing, else p = -round(2 delta) - 2 d offset by 1000 so that it is >= 0.
int decision(double r1, int d) {
  const double delta = r1 / (1 + r1);
  if (!(delta < kStationaryDelta)) return -1;
  return 1000 - static_cast<int>(std::lround(2 * delta)) - 2 * d;
}

/// The decision at step d when it is certain from the sums (see the file comment); nullopt
/// otherwise. `stop` tells whether the step ends the identification.
struct Step {
  bool certain = false;
  bool stop = false;
  int p = 0;
};

Step decide(const LagSums& s, int d) {
  Step out;
  if (s.n < 3) return out;
  const double n = static_cast<double>(s.n);
  const double S1 = s.s1.value(), S2 = s.s2.value(), S11 = s.s11.value();
  if (!std::isfinite(S1) || !std::isfinite(S2) || !std::isfinite(S11)) return out;
  if (!(S2 / n >= kMinMeanSquare && S2 / n <= kMaxMeanSquare)) return out;
  const double ybar = S1 / n;
  const double den = S2 - n * ybar * ybar;
  if (!(den > 0) || !(S2 / den <= kMaxShiftRatio)) return out;
  const double num = S11 - ybar * (2 * S1 - s.first - s.last) + (n - 1) * ybar * ybar;
  const double r1 = num / den;
  // The long double computation's mean is off by up to (n - 1) u sum|v| / n, which moves its r1
  // by up to (2 delta sqrt(den) + 2 n delta^2) / den (|a_0| + |a_{n-1}| <= 2 sqrt(den)); sum|v|
  // <= n (|c| + sqrt(S2 / n)). Taken four times over, with its summation error 4 n u.
  const double u = std::numeric_limits<long double>::epsilon();
  const double mean_error = (n - 1) * u * (std::abs(s.c) + std::sqrt(S2 / n));
  const double mean_shift = (2 * mean_error * std::sqrt(den) + 2 * n * mean_error * mean_error) / den;
  const double tol = std::max(kRelativeTolerance * std::max(1.0, S2 / den), 4 * n * u) +
                     4 * mean_shift;
  if (!(r1 - tol > -1 + 1e-3)) return out;  // near -1: delta is steep, left to the exact path
  const int lo = decision(r1 - tol, d), mid = decision(r1, d), hi = decision(r1 + tol, d);
  if (lo != mid || mid != hi) return out;
  out.certain = true;
  out.stop = mid >= 0;
  out.p = mid - 1000;
  return out;
}

/// The passes' state for one factor.
struct FactorState {
  std::int64_t m = 0;
  std::int64_t points = 0;  // values of z
  std::int64_t next = 0;    // index of the next z value
  bool have_previous = false;
  double previous = 0.0;    // the last z value, for w
  LagSums z, w;
};

}  // namespace

std::vector<std::optional<int>> acf_first_steps(const PhaseSeries& series,
                                                std::span<const std::int64_t> m) {
  std::vector<std::optional<int>> out(m.size());
  if (series.spilled() || m.empty()) return out;
  const bool phase_input = series.kind() == DataKind::phase;
  const std::int64_t N = series.size();
  const double* hi = series.hi().data();
  const double* lo = series.lo().data();
  std::vector<FactorState> states;
  states.reserve(m.size());
  for (const std::int64_t f : m) {
    FactorState s;
    s.m = f;
    s.points = f >= 1 && f < N ? averaged_series_points(series, f) : 0;
    states.push_back(s);
  }
  std::vector<double> zb(kChunk), wb(kChunk);
  for (std::int64_t b0 = 0; b0 < N; b0 += kPhaseBlock) {
    const std::int64_t b1 = std::min(N, b0 + kPhaseBlock);
    for (FactorState& s : states) {
      if (s.points < kMinAcfPoints) continue;
      // The values whose first point lies in [b0, b1): k m in the block.
      const std::int64_t end = std::min(s.points, (b1 + s.m - 1) / s.m);
      const double inv_m = 1.0 / static_cast<double>(s.m);
      while (s.next < end) {
        const std::int64_t count = std::min<std::int64_t>(end - s.next, kChunk);
        for (std::int64_t i = 0; i < count; ++i) {
          const std::int64_t k = (s.next + i) * s.m;
          // As fill_averaged_series computes them (PhaseSeries::x and window_sum).
          zb[static_cast<std::size_t>(i)] =
              phase_input ? hi[k] + lo[k]
                          : ((hi[k + s.m] - hi[k]) + (lo[k + s.m] - lo[k])) * inv_m;
        }
        s.z.add(zb.data(), static_cast<std::size_t>(count));
        // w_i = z_{i+1} - z_i, as identify_by_acf differences in place.
        std::size_t nw = 0;
        if (s.have_previous) wb[nw++] = zb[0] - s.previous;
        for (std::int64_t i = 0; i + 1 < count; ++i) {
          wb[nw++] = zb[static_cast<std::size_t>(i + 1)] - zb[static_cast<std::size_t>(i)];
        }
        s.w.add(wb.data(), nw);
        s.previous = zb[static_cast<std::size_t>(count - 1)];
        s.have_previous = true;
        s.next += count;
      }
    }
  }
  for (std::size_t t = 0; t < states.size(); ++t) {
    const FactorState& s = states[t];
    if (s.points < kMinAcfPoints) continue;
    const Step first = decide(s.z, 0);
    if (!first.certain) continue;
    Step decided = first;
    if (!first.stop) {
      decided = decide(s.w, 1);
      if (!decided.certain || !decided.stop) continue;  // a second difference: exact path
    }
    out[t] = decided.p + (phase_input ? 2 : 0);
  }
  return out;
}

}  // namespace sigmatau::detail
