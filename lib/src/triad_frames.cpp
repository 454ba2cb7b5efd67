// Frame-independent properties of a triad's sensing matrix (see triad_frames.hpp).
//
// Notation: A sensing matrix (rows = sensing axes), G = A A^T its Gram matrix, R the rotation
// nearest to A, Q = R_to^T R_from, phi the rotation vector of Q, Sigma the covariance of vec(A)
// (row-major), J the gradient of a result with respect to vec(A).
#include "sigmatau/triad_frames.hpp"

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <functional>

namespace sigmatau {
namespace {

/// Step of the central differences [1]. A's entries are near 1 and the functions below are
/// smooth there, so the truncation error is ~h^2 = 1e-12 and the rounding error ~eps/h = 2e-10,
/// both far below any calibration's standard error (~1e-6 and up).
constexpr double kStep = 1e-6;

/// Gradient of f at A with respect to A's entries, row-major.
Eigen::Matrix<double, 9, 1> gradient(const std::function<double(const Eigen::Matrix3d&)>& f,
                                     const Eigen::Matrix3d& a) {
  Eigen::Matrix<double, 9, 1> g;
  for (int k = 0; k < 9; ++k) {
    Eigen::Matrix3d plus = a, minus = a;
    plus(k / 3, k % 3) += kStep;
    minus(k / 3, k % 3) -= kStep;
    g[k] = (f(plus) - f(minus)) / (2 * kStep);
  }
  return g;
}

double propagated_se(const Eigen::Matrix<double, 9, 1>& j, const Eigen::Matrix<double, 9, 9>& s) {
  return std::sqrt(std::max(0.0, j.dot(s * j)));
}

double delta(const Eigen::Matrix3d& a, int i, int j) {
  const Eigen::Matrix3d g = a * a.transpose();
  const double c = g(i, j) / std::sqrt(g(i, i) * g(j, j));
  return std::asin(std::clamp(c, -1.0, 1.0));
}

/// The rotation nearest to A (the polar factor), with determinant +1.
Eigen::Matrix3d nearest_rotation(const Eigen::Matrix3d& a) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(a, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d u = svd.matrixU();
  if ((u * svd.matrixV().transpose()).determinant() < 0) u.col(2) *= -1;
  return u * svd.matrixV().transpose();
}

Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& from, const Eigen::Matrix3d& to) {
  const Eigen::Matrix3d q = nearest_rotation(to).transpose() * nearest_rotation(from);
  const Eigen::AngleAxisd aa(q);
  return aa.angle() * aa.axis();
}

}  // namespace

AngleEstimate non_orthogonality(const TriadMatrix& triad, int i, int j) {
  const auto f = [i, j](const Eigen::Matrix3d& a) { return delta(a, i, j); };
  return {f(triad.a), propagated_se(gradient(f, triad.a), triad.covariance)};
}

std::array<AngleEstimate, 3> relative_rotation(const TriadMatrix& from, const TriadMatrix& to) {
  std::array<AngleEstimate, 3> out;
  const Eigen::Vector3d phi = rotation_vector(from.a, to.a);
  for (int k = 0; k < 3; ++k) {
    const auto by_from = [&](const Eigen::Matrix3d& a) { return rotation_vector(a, to.a)[k]; };
    const auto by_to = [&](const Eigen::Matrix3d& a) { return rotation_vector(from.a, a)[k]; };
    const double se_from = propagated_se(gradient(by_from, from.a), from.covariance);
    const double se_to = propagated_se(gradient(by_to, to.a), to.covariance);
    out[static_cast<std::size_t>(k)] = {phi[k], std::hypot(se_from, se_to)};
  }
  return out;
}

}  // namespace sigmatau
