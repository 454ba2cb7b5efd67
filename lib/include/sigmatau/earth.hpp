#pragma once
/// \file earth.hpp
/// What a sensor at rest on the Earth senses: the Earth's rotation and normal gravity, in the
/// local north-east-down (NED) frame. Shared by the simulator (the truth it adds) and the
/// calibrator (what it expects at rest), so neither reaches into the other for a constant.

#include <Eigen/Core>

#include <cmath>

namespace sigmatau {

/// Earth rotation rate [rad/s] (WGS-84).
inline constexpr double kEarthRate = 7.292115e-5;

/// The Earth-rate vector [rad/s] in NED at geodetic latitude `latitude_rad` [rad]:
/// (kEarthRate cos(latitude), 0, -kEarthRate sin(latitude)).
inline Eigen::Vector3d earth_rate_ned(double latitude_rad) {
  return Eigen::Vector3d(kEarthRate * std::cos(latitude_rad), 0,
                         -kEarthRate * std::sin(latitude_rad));
}

/// WGS-84 normal gravity on the ellipsoid at geodetic latitude [rad] (Somigliana), [m/s^2].
double normal_gravity(double latitude_rad);

}  // namespace sigmatau
