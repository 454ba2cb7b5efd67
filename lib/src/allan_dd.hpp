#pragma once
// Internal: error-free transformations and a small double-double accumulator, shared by the phase
// series construction and the Allan-family sums.
//
// Sources: Knuth's TwoSum and Dekker's FastTwoSum (error-free: a + b = sum + err exactly in IEEE
// binary64 with round-to-nearest); the double-double addition is the accurate ("IEEE") variant
// of Hida, Li & Bailey's QD library, relative error about 2^-104. Valid only without
// -ffast-math / -fassociative-math, which the build never sets; none of these contain a
// multiplication, so FMA contraction cannot change them.

namespace sigmatau::detail {

struct SumAndError {
  double sum;
  double err;
};

/// a + b = sum + err exactly, for any finite a, b.
inline SumAndError two_sum(double a, double b) {
  const double s = a + b;
  const double bb = s - a;
  return {s, (a - (s - bb)) + (b - bb)};
}

/// a + b = sum + err exactly, provided |a| >= |b| or a == 0.
inline SumAndError fast_two_sum(double a, double b) {
  const double s = a + b;
  return {s, b - (s - a)};
}

/// An unevaluated sum hi + lo with |lo| <= ulp(hi)/2.
struct DoubleDouble {
  double hi = 0.0;
  double lo = 0.0;

  /// this += (b_hi + b_lo), accurate to ~2^-104 relative even under cancellation.
  void add(double b_hi, double b_lo) {
    SumAndError s = two_sum(hi, b_hi);
    const SumAndError t = two_sum(lo, b_lo);
    s.err += t.sum;
    s = fast_two_sum(s.sum, s.err);
    s.err += t.err;
    s = fast_two_sum(s.sum, s.err);
    hi = s.sum;
    lo = s.err;
  }
  void add(double b) { add(b, 0.0); }
  double value() const { return hi + lo; }
};

}  // namespace sigmatau::detail
