#pragma once
/// \file triad_frames.hpp
/// What a calibrated triad's sensing matrix says independently of the frame it is written in.
///
/// A triad's sensing matrix A (y = A x + b) has the sensing axes as its rows, written in some
/// frame (sigmatau calibrate: the accelerometer frame, calibrate.hpp). Rotating that frame
/// changes every cross-axis term m_ij = A_ij but not the Gram matrix A A^T, whose entries are
/// the dot products of the sensing axes. So:
///  - the non-orthogonality of axes i and j, delta_ij = 90 deg - angle(a_i, a_j)
///    = asin(G_ij / sqrt(G_ii G_jj)) with G = A A^T, is a property of the triad alone
///    (to first order delta_ij = m_ij + m_ji, the symmetric part of A - I);
///  - a triad's orientation is the rotation R nearest to A (polar decomposition A = P R with P
///    symmetric positive definite; R = U V^T from A = U S V^T). Between two triads written in
///    one frame, R_to^T R_from carries the first triad's axes onto the second's
///    (to first order the difference of the antisymmetric parts of A_to - I and A_from - I).
/// Uncertainties are propagated to first order (delta method) from the covariance of A's
/// entries.
///
/// Reference: Higham, "Computing the polar decomposition with applications", SIAM J. Sci.
/// Stat. Comput. 7(4), 1986 (the nearest orthogonal matrix is the polar factor).

#include <Eigen/Core>
#include <array>

namespace sigmatau {

/// A triad's sensing matrix and the covariance of its entries.
struct TriadMatrix {
  /// A [1]: rows are the sensing axes (scale included) in the frame of the calibration.
  Eigen::Matrix3d a = Eigen::Matrix3d::Identity();
  /// Covariance of A's entries in row-major order (A_xx, A_xy, A_xz, A_yx, ...) [1]; zero
  /// rows and columns for entries fixed by a convention (e.g. the accelerometer's upper
  /// triangle).
  Eigen::Matrix<double, 9, 9> covariance = Eigen::Matrix<double, 9, 9>::Zero();
};

/// An angle with its standard error.
struct AngleEstimate {
  double value = 0;           ///< [rad]
  double standard_error = 0;  ///< [rad], first-order propagation of the input covariance
};

/// Non-orthogonality delta_ij = 90 deg - angle between sensing axes i and j [rad], positive
/// when the two axes lean towards each other. i != j in 0..2. Frame-independent.
AngleEstimate non_orthogonality(const TriadMatrix& triad, int i, int j);

/// The rotation carrying the axes of `from` onto those of `to` (both written in one frame), as a
/// rotation vector (angle times unit axis) in that frame [rad], each component with its
/// standard error (the two triads' errors taken as independent).
std::array<AngleEstimate, 3> relative_rotation(const TriadMatrix& from, const TriadMatrix& to);

}  // namespace sigmatau
