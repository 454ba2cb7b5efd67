// Least-squares machinery and the accelerometer fit of the calibration (calibrate.hpp).
//
// Glossary: p parameters; r(p) whitened residuals; J = dr/dp; A lower-triangular I + T of the
// accelerometer; b(T) = b0 + sum_d c_d (T - T0)^d its bias; a_k the mean of interval k, S_k the
// covariance of that mean; x_k = A^-1 (a_k - b(T_k)) the calibrated specific force, u_k = x_k/|x_k|;
// g the gravity magnitude.
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>

#include <cmath>
#include <limits>

#include "calibrate_internal.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau::detail {
namespace {

/// LM stops after this many iterations (the calibration problems converge in < 10).
constexpr int kMaxIterations = 100;
/// Relative chi^2 change and relative step below which LM has converged.
constexpr double kTolerance = 1e-12;
/// Finite-difference step for the accelerometer parameters: they are O(1e-3..1) in SI and the
/// residuals are smooth (quadratic-like) in them, so a 1e-6 central step has truncation error
/// ~1e-12 and rounding error ~1e-16 |r| / 1e-6, far below the noise.
constexpr double kAccelStep = 1e-6;
/// Number of LM passes: weights depend (weakly) on the estimate, so they are recomputed once.
constexpr int kWeightPasses = 2;

}  // namespace

Eigen::MatrixXd numeric_jacobian(const Residuals& r, const Eigen::VectorXd& p, double step) {
  const Eigen::VectorXd r0 = r(p);
  Eigen::MatrixXd j(r0.size(), p.size());
  for (Eigen::Index i = 0; i < p.size(); ++i) {
    Eigen::VectorXd a = p, b = p;
    a[i] += step;
    b[i] -= step;
    j.col(i) = (r(a) - r(b)) / (2 * step);
  }
  return j;
}

LmResult levenberg_marquardt(const Residuals& r, const Eigen::VectorXd& p0, double step) {
  LmResult out;
  out.p = p0;
  Eigen::VectorXd res = r(out.p);
  out.chi2 = res.squaredNorm();
  double lambda = 1e-3;
  for (out.iterations = 0; out.iterations < kMaxIterations; ++out.iterations) {
    const Eigen::MatrixXd j = numeric_jacobian(r, out.p, step);
    const Eigen::MatrixXd jtj = j.transpose() * j;
    const Eigen::VectorXd g = j.transpose() * res;
    bool improved = false;
    for (int tries = 0; tries < 30; ++tries) {
      Eigen::MatrixXd m = jtj;
      m.diagonal() += lambda * jtj.diagonal().cwiseMax(1e-300);
      const Eigen::VectorXd dp = m.ldlt().solve(-g);
      const Eigen::VectorXd trial = out.p + dp;
      const Eigen::VectorXd tres = r(trial);
      const double chi2 = tres.squaredNorm();
      if (std::isfinite(chi2) && chi2 <= out.chi2) {
        const double change = (out.chi2 - chi2) / std::max(out.chi2, 1e-300);
        const double rel_step = dp.norm() / std::max(out.p.norm(), 1e-12);
        out.p = trial;
        res = tres;
        out.chi2 = chi2;
        lambda = std::max(lambda / 10, 1e-12);
        improved = true;
        if (change < kTolerance || rel_step < kTolerance) tries = 1000;
        break;
      }
      lambda *= 10;
    }
    if (!improved) break;
    if (out.chi2 == 0) break;
    // Converged when the last accepted step changed almost nothing.
    const Eigen::MatrixXd j2 = numeric_jacobian(r, out.p, step);
    const Eigen::MatrixXd m2 = j2.transpose() * j2;
    const Eigen::VectorXd dp2 = m2.ldlt().solve(-(j2.transpose() * res));
    if (dp2.norm() <= 1e-10 * std::max(out.p.norm(), 1e-6)) break;
  }
  out.jacobian = numeric_jacobian(r, out.p, step);
  return out;
}

Eigen::MatrixXd covariance_of(const Eigen::MatrixXd& jacobian, const std::string& what) {
  const Eigen::MatrixXd jtj = jacobian.transpose() * jacobian;
  const Eigen::VectorXd d = jtj.diagonal().cwiseSqrt();
  for (Eigen::Index i = 0; i < d.size(); ++i)
    if (!(d[i] > 0))
      throw Error(what + ": the data do not constrain parameter " + std::to_string(i + 1));
  const Eigen::MatrixXd scaled = d.cwiseInverse().asDiagonal() * jtj * d.cwiseInverse().asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(scaled);
  const double cond = eig.eigenvalues().maxCoeff() / std::max(eig.eigenvalues().minCoeff(), 0.0);
  if (!(cond <= kMaxCondition)) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.3g", cond);
    // What the schedule lacks, for the fit that found it out.
    std::string advice;
    if (what.rfind("accelerometer", 0) == 0) {
      advice = ": rest the IMU in at least 9 orientations spread over the sphere, not all in one "
               "plane through an axis (the 6 faces plus 3 or more tilted 45 deg between faces)";
    } else if (what.rfind("gyroscope rotation", 0) == 0) {
      advice = ": turn the IMU about each of its three axes between rests";
    }
    throw Error(what + ": the data do not determine every parameter (condition number " + buffer +
                " > 1e10)" + advice);
  }
  const Eigen::MatrixXd inv = scaled.inverse();
  return d.cwiseInverse().asDiagonal() * inv * d.cwiseInverse().asDiagonal();
}

double covariance_scale(double chi2, int dof) {
  if (dof <= 0) return 1;
  const boost::math::chi_squared dist(dof);
  return chi2 > boost::math::quantile(dist, 0.99) ? chi2 / dof : 1.0;
}

CalibratedValue make_value(double value, double se, double confidence) {
  const double z = boost::math::quantile(boost::math::normal(), (1 + confidence) / 2);
  return {value, se, value - z * se, value + z * se};
}

double aicc(double chi2, int p, int n) {
  if (n <= p + 1) return std::numeric_limits<double>::infinity();
  return chi2 + 2.0 * p + 2.0 * p * (p + 1) / (n - p - 1);
}

Eigen::Matrix3d accel_matrix(const Eigen::VectorXd& p) {
  Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
  a(0, 0) = 1 + p[0];
  a(1, 1) = 1 + p[1];
  a(2, 2) = 1 + p[2];
  a(1, 0) = p[3];
  a(2, 0) = p[4];
  a(2, 1) = p[5];
  return a;
}

Eigen::Vector3d accel_bias_at(const Eigen::VectorXd& p, const std::array<int, 3>& degree,
                              double temperature_k, double reference_temperature_k) {
  Eigen::Vector3d b = p.segment<3>(6);
  Eigen::Index k = 9;
  const double dt = temperature_k - reference_temperature_k;
  for (int a = 0; a < 3; ++a)
    for (int d = 1; d <= degree[static_cast<std::size_t>(a)]; ++d) b[a] += p[k++] * std::pow(dt, d);
  return b;
}

AccelFit fit_accelerometer(const std::vector<StaticInterval>& iv, double gravity, double t0,
                           const std::array<int, 3>& degree) {
  AccelFit fit;
  fit.degree = degree;
  fit.parameter_names = {"s_x", "s_y", "s_z", "m_yx", "m_zx", "m_zy", "b_x", "b_y", "b_z"};
  for (int a = 0; a < 3; ++a)
    for (int d = 1; d <= degree[static_cast<std::size_t>(a)]; ++d)
      fit.parameter_names.push_back(std::string("c") + std::to_string(d) + "_" + "xyz"[a]);
  const auto np = static_cast<Eigen::Index>(fit.parameter_names.size());
  const auto n = static_cast<Eigen::Index>(iv.size());
  Eigen::VectorXd p = Eigen::VectorXd::Zero(np);
  Eigen::VectorXd sigma(n);
  const auto update_sigma = [&](const Eigen::VectorXd& q) {
    const Eigen::Matrix3d ainv = accel_matrix(q).inverse();
    for (Eigen::Index k = 0; k < n; ++k) {
      const auto& s = iv[static_cast<std::size_t>(k)];
      const Eigen::Vector3d x = ainv * (s.accel_mean - accel_bias_at(q, degree, s.temperature_k, t0));
      const Eigen::Vector3d u = x.normalized();
      // Variance of |x| from the covariance of the mean: u^T A^-1 S A^-T u. A floor of
      // (1e-12 g)^2 keeps noise-free (simulated) input finite.
      sigma[k] = std::sqrt(std::max((u.transpose() * ainv * s.accel_cov * ainv.transpose() * u)(0),
                                    std::pow(1e-12 * gravity, 2)));
    }
  };
  const Residuals residuals = [&](const Eigen::VectorXd& q) {
    const Eigen::Matrix3d ainv = accel_matrix(q).inverse();
    Eigen::VectorXd r(n);
    for (Eigen::Index k = 0; k < n; ++k) {
      const auto& s = iv[static_cast<std::size_t>(k)];
      r[k] = ((ainv * (s.accel_mean - accel_bias_at(q, degree, s.temperature_k, t0))).norm() -
              gravity) / sigma[k];
    }
    return r;
  };
  LmResult lm;
  for (int pass = 0; pass < kWeightPasses; ++pass) {
    update_sigma(p);
    lm = levenberg_marquardt(residuals, p, kAccelStep);
    p = lm.p;
  }
  fit.params = p;
  fit.matrix = accel_matrix(p);
  fit.bias = p.segment<3>(6);
  fit.chi2 = lm.chi2;
  fit.dof = static_cast<int>(n - np);
  fit.covariance = covariance_of(lm.jacobian, "accelerometer fit");
  fit.scale = covariance_scale(fit.chi2, fit.dof);
  fit.covariance *= fit.scale;
  const Eigen::VectorXd r = residuals(p).cwiseProduct(sigma);
  fit.residual_rms = std::sqrt(r.squaredNorm() / static_cast<double>(n));
  fit.aicc = aicc(fit.chi2, static_cast<int>(np), static_cast<int>(n));
  return fit;
}

PolyFit weighted_polynomial(const std::vector<double>& x, const std::vector<double>& y,
                            const std::vector<double>& variance, int degree) {
  const auto n = static_cast<Eigen::Index>(x.size());
  Eigen::MatrixXd a(n, degree + 1);
  Eigen::VectorXd b(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double w = 1 / std::sqrt(variance[static_cast<std::size_t>(k)]);
    for (int d = 0; d <= degree; ++d) a(k, d) = w * std::pow(x[static_cast<std::size_t>(k)], d);
    b[k] = w * y[static_cast<std::size_t>(k)];
  }
  PolyFit f;
  f.covariance = covariance_of(a, "temperature regression");
  f.c = f.covariance * a.transpose() * b;
  f.chi2 = (a * f.c - b).squaredNorm();
  return f;
}

}  // namespace sigmatau::detail
