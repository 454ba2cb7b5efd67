// The gyroscope's scale and misalignment from the rotations between static intervals
// (calibrate.hpp step 3).
//
// Glossary: G = I + T_g the gyroscope matrix in the accelerometer frame (9 parameters, row-major);
// rotation j goes from interval k (last sample e) to interval k+1 (first sample s); z_i the gyro
// sample minus the bias interpolated between the two intervals; e_k = G^-1 (reading_k - bias_k) the
// Earth rate seen in interval k, which turns with the body: R_i^T e_k at step i (the local-level
// frame, in which gravity is fixed, turns with the Earth); dtheta_i = G^-1 dz_i - R_i^T e_k tau0
// the calibrated angle of step i relative to the local level; R_j = prod Exp(dtheta_i) the rotation from
// frame k to frame k+1; u_k the calibrated gravity direction (accelerometer fit); the residual is
// B_j^T (u_{k+1} - R_j^T u_k), B_j an orthonormal basis of the plane normal to u_{k+1};
// C_{k+1} = C_k R_k the attitude of interval k relative to interval 0 (interval_attitudes, for the
// bias model's Earth rate: every pair of consecutive intervals, however small its rotation).
#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <functional>

#include "calibrate_internal.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau::detail {
namespace {

/// Finite-difference step for G's entries (O(1), smooth): see kAccelStep in calibrate_fit.cpp.
constexpr double kGyroStep = 1e-6;
/// Rotations turning less than this [rad] carry no information on G and are skipped (1 deg).
constexpr double kMinRotation = 0.0174533;

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

struct Rotation {
  int from = 0;                       // interval k
  Eigen::Vector3d earth = Eigen::Vector3d::Zero();  // reading_k - bias_k (before G^-1) [rad/s]
  double step_s = 0;                  // duration of each step [s]
  std::int64_t begin = 0, end = 0;    // its steps dz (before G^-1 [rad]): rows of the step store
  double white_var = 0;               // per-axis variance of the integrated white noise [rad^2]
  Eigen::Matrix3d basis;              // 3x2 used: columns 0, 1 normal to u_{k+1}
};

/// Calibrated gravity directions and their covariances for accelerometer parameters q.
void directions(const std::vector<StaticInterval>& iv, const AccelFit& accel, const Eigen::VectorXd& q,
                double t0, std::vector<Eigen::Vector3d>& u, std::vector<Eigen::Matrix3d>* cov) {
  const Eigen::Matrix3d ainv = accel_matrix(q).inverse();
  u.resize(iv.size());
  if (cov) cov->resize(iv.size());
  for (std::size_t k = 0; k < iv.size(); ++k) {
    const Eigen::Vector3d x =
        ainv * (iv[k].accel_mean - accel_bias_at(q, accel.degree, iv[k].temperature_k, t0));
    u[k] = x.normalized();
    if (cov) {
      const Eigen::Matrix3d ju = (Eigen::Matrix3d::Identity() - u[k] * u[k].transpose()) / x.norm();
      (*cov)[k] = ju * ainv * iv[k].accel_cov * ainv.transpose() * ju.transpose();
    }
  }
}

}  // namespace

Eigen::Matrix3d exp_so3(const Eigen::Vector3d& v) {
  const double a = v.norm();
  if (a < 1e-300) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(a, v / a).toRotationMatrix();
}

void rotation_steps(const CalibrationSamples& in, const StaticInterval& a, const StaticInterval& b,
                    const Eigen::Vector3d& ba, const Eigen::Vector3d& bb,
                    const std::function<void(const Eigen::Vector3d&)>& step) {
  const double tau0 = 1 / in.rate_hz();
  const bool increments = in.increments();
  // Static reading interpolated linearly in time between the two interval centres.
  const double ta = (a.start_s + a.end_s) / 2, tb = (b.start_s + b.end_s) / 2;
  const auto lam = [&](double t) { return (t - ta) / (tb - ta); };
  Eigen::Vector3d previous = Eigen::Vector3d::Zero();
  in.for_each(a.last, b.first + 1, [&](const SampleRows& rows) {
    for (std::int64_t j = 0; j < rows.count; ++j) {
      const std::int64_t i = rows.first + j;
      const Eigen::Vector3d sample(rows.value(kGyroChannel, j), rows.value(kGyroChannel + 1, j),
                                   rows.value(kGyroChannel + 2, j));
      if (!increments) {
        // Trapezoid on rate samples e..s (step i - 1 -> i).
        if (i > a.last) {
          const double t1 = static_cast<double>(i - 1) * tau0, t2 = t1 + tau0;
          const double l1 = lam(t1), l2 = lam(t2);
          const Eigen::Vector3d z1 = previous - ((1 - l1) * ba + l1 * bb);
          const Eigen::Vector3d z2 = sample - ((1 - l2) * ba + l2 * bb);
          step((z1 + z2) / 2 * tau0);
        }
        previous = sample;
      } else if (i > a.last && i < b.first) {
        // Sample i integrates over the interval before t_i + tau0.
        const double l = lam((static_cast<double>(i) + 0.5) * tau0);
        step(sample - ((1 - l) * ba + l * bb) * tau0);
      }
    }
  });
}

std::vector<Eigen::Matrix3d> interval_attitudes(const CalibrationSamples& in,
                                                const std::vector<StaticInterval>& iv,
                                                const Eigen::Matrix3d& g,
                                                const std::vector<Eigen::Vector3d>& interval_bias) {
  const double tau0 = 1 / in.rate_hz();
  const Eigen::Matrix3d ginv = g.inverse();
  std::vector<Eigen::Matrix3d> c(iv.size(), Eigen::Matrix3d::Identity());
  for (std::size_t k = 0; k + 1 < iv.size(); ++k) {
    // R_k as in the matrix fit (relative to the local level: interval k's Earth rate, turned
    // into the current body frame, is removed at each step). Every pair is chained, however
    // small its rotation: an interval split by the detector gives R_k = I (no steps).
    const Eigen::Vector3d earth = ginv * (iv[k].gyro_mean - interval_bias[k]);
    Eigen::Matrix3d rot = Eigen::Matrix3d::Identity();
    rotation_steps(in, iv[k], iv[k + 1], interval_bias[k], interval_bias[k + 1],
                   [&](const Eigen::Vector3d& dz) {
                     rot = rot * exp_so3(ginv * dz - rot.transpose() * earth * tau0);
                   });
    c[k + 1] = c[k] * rot;
  }
  return c;
}

GyroMatrixFit fit_gyroscope_matrix(const CalibrationSamples& in, const std::vector<StaticInterval>& iv,
                                   const AccelFit& accel, double t0,
                                   const std::vector<Eigen::Vector3d>& interval_bias,
                                   std::int64_t step_memory_bytes) {
  const double tau0 = 1 / in.rate_hz();
  const bool increments = in.increments();
  std::vector<Eigen::Vector3d> u0;
  directions(iv, accel, accel.params, t0, u0, nullptr);
  std::vector<Rotation> rots;
  // The steps of every rotation, three values each: in memory up to step_memory_bytes, beyond
  // in a temporary file that each evaluation of the residuals reads through.
  CalibrationLog store(false, false, step_memory_bytes);
  std::vector<double> pending;
  const auto flush_steps = [&] {
    store.append(pending);
    pending.clear();
  };
  const auto add_step = [&](const Eigen::Vector3d& dz) {
    pending.insert(pending.end(), {dz.x(), dz.y(), dz.z()});
    if (pending.size() >= 3 * 4096) flush_steps();
  };
  for (std::size_t k = 0; k + 1 < iv.size(); ++k) {
    const StaticInterval& a = iv[k];
    const StaticInterval& b = iv[k + 1];
    const double angle = std::acos(std::clamp(u0[k].dot(u0[k + 1]), -1.0, 1.0));
    // Steps: rate samples e..s by the trapezoid, or the increments of samples e+1..s-1.
    const std::int64_t steps = increments ? b.first - a.last - 1 : b.first - a.last;
    if (angle < kMinRotation && steps < 2) continue;
    Rotation r;
    r.from = static_cast<int>(k);
    r.step_s = tau0;
    const Eigen::Vector3d& ba = interval_bias[k];
    r.earth = a.gyro_mean - ba;
    const double sigma2 = (a.gyro_sample_cov.trace() + b.gyro_sample_cov.trace()) / 6;
    // Only the samples of this rotation are read; its steps go to the store.
    r.begin = store.rows();
    rotation_steps(in, a, b, ba, interval_bias[k + 1], add_step);
    flush_steps();
    r.end = store.rows();
    r.white_var = increments ? sigma2 * tau0 * tau0 * static_cast<double>(r.end - r.begin)
                             : sigma2 * tau0 * tau0 * (static_cast<double>(steps) - 0.5);
    // Basis of the plane normal to u_{k+1}.
    const Eigen::Vector3d n = u0[k + 1];
    const Eigen::Vector3d e1 = n.unitOrthogonal();
    r.basis.col(0) = e1;
    r.basis.col(1) = n.cross(e1);
    r.basis.col(2) = n;
    rots.push_back(std::move(r));
  }
  if (rots.size() < 5)
    throw Error("gyroscope: only " + std::to_string(rots.size()) +
                " rotations between static intervals (need >= 5 that change the gravity direction "
                "about different axes)");
  const auto nr = static_cast<Eigen::Index>(rots.size());

  // Rotation matrices and the sensitivity of the final angle to interval k's and k+1's readings.
  const auto integrate = [&](const Rotation& r, const Eigen::Matrix3d& ginv, Eigen::Matrix3d* mk,
                             Eigen::Matrix3d* mk1) {
    Eigen::Matrix3d rot = Eigen::Matrix3d::Identity();
    Eigen::Matrix3d sk = Eigen::Matrix3d::Zero();
    const Eigen::Vector3d earth = ginv * r.earth;
    store.read(r.begin, r.end, [&](std::int64_t, std::int64_t n, const double* v) {
      for (std::int64_t i = 0; i < n; ++i) {
        const Eigen::Vector3d dz(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
        // The Earth rate of interval k, turned into the current body frame (evaluated at the
        // step's start: the error is Omega times the step angle, < 1e-6 rad/s).
        rot = rot * exp_so3(ginv * dz - rot.transpose() * earth * r.step_s);
        if (mk) {
          sk += rot * r.step_s;  // each step's share of interval k's reading (times tau0)
        }
      }
    });
    if (mk) {
      *mk = rot.transpose() * sk * ginv;
      *mk1 = Eigen::Matrix3d::Zero();  // interval k+1's reading no longer enters
    }
    return rot;
  };

  // Whitening: the full covariance of the stacked 2-d residuals (adjacent rotations share an
  // interval's gravity direction), computed at the current estimate.
  Eigen::MatrixXd whiten;
  const auto build_whitening = [&](const Eigen::Matrix3d& g) {
    const Eigen::Matrix3d ginv = g.inverse();
    std::vector<Eigen::Vector3d> u;
    std::vector<Eigen::Matrix3d> pu;
    directions(iv, accel, accel.params, t0, u, &pu);
    Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(2 * nr, 2 * nr);
    std::vector<Eigen::Matrix3d> rotation(rots.size());
    for (Eigen::Index j = 0; j < nr; ++j) {
      const Rotation& r = rots[static_cast<std::size_t>(j)];
      Eigen::Matrix3d mk, mk1;
      const Eigen::Matrix3d rot = integrate(r, ginv, &mk, &mk1);
      rotation[static_cast<std::size_t>(j)] = rot;
      const auto k = static_cast<std::size_t>(r.from);
      const Eigen::Vector3d v = rot.transpose() * u[k];
      const Eigen::Matrix<double, 3, 2> bj = r.basis.leftCols<2>();
      const Eigen::Matrix3d angle_cov = r.white_var * Eigen::Matrix3d::Identity() +
                                        mk * iv[k].gyro_cov * mk.transpose() +
                                        mk1 * iv[k + 1].gyro_cov * mk1.transpose();
      const Eigen::Matrix3d full = pu[k + 1] + rot.transpose() * pu[k] * rot +
                                   skew(v) * angle_cov * skew(v).transpose();
      cov.block<2, 2>(2 * j, 2 * j) = bj.transpose() * full * bj;
      if (j > 0 && rots[static_cast<std::size_t>(j - 1)].from + 1 == r.from) {
        // Shared direction u_k: +delta u_k in residual j-1, -R_j^T delta u_k in residual j.
        const Eigen::Matrix<double, 3, 2> bp = rots[static_cast<std::size_t>(j - 1)].basis.leftCols<2>();
        const Eigen::Matrix2d c = -(bp.transpose() * pu[k] * rot * bj);
        cov.block<2, 2>(2 * (j - 1), 2 * j) = c;
        cov.block<2, 2>(2 * j, 2 * (j - 1)) = c.transpose();
      }
    }
    const Eigen::LLT<Eigen::MatrixXd> llt(cov);
    if (llt.info() != Eigen::Success) throw Error("gyroscope: residual covariance is not positive");
    whiten = llt.matrixL().solve(Eigen::MatrixXd::Identity(2 * nr, 2 * nr));
  };

  const auto raw_residuals = [&](const Eigen::VectorXd& gp, const Eigen::VectorXd& ap) {
    const Eigen::Matrix3d g = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(gp.data());
    const Eigen::Matrix3d ginv = g.inverse();
    std::vector<Eigen::Vector3d> u;
    directions(iv, accel, ap, t0, u, nullptr);
    Eigen::VectorXd r(2 * nr);
    for (Eigen::Index j = 0; j < nr; ++j) {
      const Rotation& rt = rots[static_cast<std::size_t>(j)];
      const Eigen::Matrix3d rot = integrate(rt, ginv, nullptr, nullptr);
      const auto k = static_cast<std::size_t>(rt.from);
      r.segment<2>(2 * j) = rt.basis.leftCols<2>().transpose() * (u[k + 1] - rot.transpose() * u[k]);
    }
    return r;
  };
  const Residuals residuals = [&](const Eigen::VectorXd& gp) {
    return Eigen::VectorXd(whiten * raw_residuals(gp, accel.params));
  };

  Eigen::VectorXd p(9);
  Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(p.data()) = Eigen::Matrix3d::Identity();
  LmResult lm;
  for (int pass = 0; pass < 2; ++pass) {  // weights at the start, then at the first estimate
    build_whitening(Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(p.data()));
    lm = levenberg_marquardt(residuals, p, kGyroStep);
    p = lm.p;
  }
  GyroMatrixFit fit;
  fit.matrix = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(p.data());
  fit.rotations = static_cast<int>(nr);
  fit.chi2 = lm.chi2;
  fit.dof = static_cast<int>(2 * nr - 9);
  const Eigen::MatrixXd own = covariance_of(lm.jacobian, "gyroscope rotation fit");
  fit.scale = covariance_scale(fit.chi2, fit.dof);
  // The accelerometer parameters' uncertainty moves the reference directions of every rotation:
  // dp = -(J^T J)^-1 J^T J_a dq, so Cov_p += H Cov_q H^T.
  const Residuals by_accel = [&](const Eigen::VectorXd& q) {
    return Eigen::VectorXd(whiten * raw_residuals(p, q));
  };
  const Eigen::MatrixXd ja = numeric_jacobian(by_accel, accel.params, kGyroStep);
  const Eigen::MatrixXd h = -own * lm.jacobian.transpose() * ja;
  fit.covariance = fit.scale * own + h * accel.covariance * h.transpose();
  const Eigen::VectorXd raw = raw_residuals(p, accel.params);
  fit.residual_rms = std::sqrt(raw.squaredNorm() / static_cast<double>(raw.size()));
  return fit;
}

}  // namespace sigmatau::detail
