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

namespace sigmatau {
namespace {

/// Step of the central differences [1]. A's entries are near 1 and the functions below are
/// smooth there, so the truncation error is ~h^2 = 1e-12 and the rounding error ~eps/h = 2e-10,
/// both far below any calibration's standard error (~1e-6 and up).
constexpr double kStep = 1e-6;

/// Jacobian of f (N components) at A with respect to A's entries, row-major: column n is the
/// gradient of component n. One pair of evaluations of f per entry serves every component.
template <int N, class F>
Eigen::Matrix<double, 9, N> jacobian(const F& f, const Eigen::Matrix3d& a) {
  Eigen::Matrix<double, 9, N> jac;
  for (int k = 0; k < 9; ++k) {
    Eigen::Matrix3d plus = a, minus = a;
    plus(k / 3, k % 3) += kStep;
    minus(k / 3, k % 3) -= kStep;
    jac.row(k) = ((f(plus) - f(minus)) / (2 * kStep)).transpose();
  }
  return jac;
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
  const auto f = [i, j](const Eigen::Matrix3d& a) {
    return Eigen::Matrix<double, 1, 1>::Constant(delta(a, i, j));
  };
  return {delta(triad.a, i, j), propagated_se(jacobian<1>(f, triad.a), triad.covariance)};
}

std::array<AngleEstimate, 3> relative_rotation(const TriadMatrix& from, const TriadMatrix& to) {
  std::array<AngleEstimate, 3> out;
  const Eigen::Vector3d phi = rotation_vector(from.a, to.a);
  const Eigen::Matrix<double, 9, 3> by_from = jacobian<3>(
      [&](const Eigen::Matrix3d& a) { return rotation_vector(a, to.a); }, from.a);
  const Eigen::Matrix<double, 9, 3> by_to = jacobian<3>(
      [&](const Eigen::Matrix3d& a) { return rotation_vector(from.a, a); }, to.a);
  for (int k = 0; k < 3; ++k) {
    const double se_from = propagated_se(by_from.col(k), from.covariance);
    const double se_to = propagated_se(by_to.col(k), to.covariance);
    out[static_cast<std::size_t>(k)] = {phi[k], std::hypot(se_from, se_to)};
  }
  return out;
}

}  // namespace sigmatau
