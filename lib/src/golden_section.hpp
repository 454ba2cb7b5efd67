#pragma once
// Golden-section search for the minimum of a one-dimensional function (the noise fit's
// refinements of a correlation time, a frequency and the model error).
#include <cmath>

namespace sigmatau::detail {

struct GoldenMinimum {
  double x = 0;  ///< where the smallest value was found
  double f = 0;  ///< that value
};

/// Minimum of `f` on [a, b] by golden-section search: `steps` steps, each shrinking the bracket
/// by 0.618 and costing one evaluation. Returns the better of the last two interior points.
template <class F>
GoldenMinimum golden_section_minimum(F&& f, double a, double b, int steps) {
  const double r = (std::sqrt(5.0) - 1) / 2;
  double x1 = b - r * (b - a), x2 = a + r * (b - a);
  double f1 = f(x1), f2 = f(x2);
  for (int i = 0; i < steps; ++i) {
    if (f1 <= f2) {
      b = x2, x2 = x1, f2 = f1, x1 = b - r * (b - a), f1 = f(x1);
    } else {
      a = x1, x1 = x2, f1 = f2, x2 = a + r * (b - a), f2 = f(x2);
    }
  }
  return f1 <= f2 ? GoldenMinimum{x1, f1} : GoldenMinimum{x2, f2};
}

}  // namespace sigmatau::detail
