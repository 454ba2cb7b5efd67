// Normal gravity of the WGS-84 ellipsoid (earth.hpp).
#include "sigmatau/earth.hpp"

#include <cmath>

namespace sigmatau {

double normal_gravity(double latitude_rad) {
  // WGS-84 Somigliana: gamma_e (1 + k sin^2) / sqrt(1 - e^2 sin^2).
  constexpr double kGammaEquator = 9.7803253359;
  constexpr double kSomiglianaK = 0.00193185265241;
  constexpr double kE2 = 0.00669437999013;
  const double s2 = std::pow(std::sin(latitude_rad), 2);
  return kGammaEquator * (1 + kSomiglianaK * s2) / std::sqrt(1 - kE2 * s2);
}

}  // namespace sigmatau
