// Checks of a computed curve (allan_curve.hpp): isolated noise-type jumps, a constant input.
#include <cstdlib>

#include "sigmatau/allan_curve.hpp"

namespace sigmatau {

std::vector<std::size_t> isolated_noise_types(const AllanCurve& curve) {
  std::vector<std::size_t> found;
  const auto& p = curve.points;
  for (std::size_t i = 1; i + 1 < p.size(); ++i) {
    const int before = p[i - 1].confidence.noise.alpha;
    const int here = p[i].confidence.noise.alpha;
    const int after = p[i + 1].confidence.noise.alpha;
    if (before == after && std::abs(here - before) >= 2) found.push_back(i);
  }
  return found;
}

bool all_deviations_zero(const AllanCurve& curve) {
  for (const CurvePoint& p : curve.points) {
    if (p.value.dev != 0) return false;
  }
  return true;
}

}  // namespace sigmatau
