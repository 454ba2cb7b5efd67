// Log-scale likelihood of an OAVAR curve under a model, for model selection (fit_joint.cpp).
//
// An OAVAR estimate v_j with nu_j equivalent degrees of freedom is distributed approximately as
// mu_j chi2_nu / nu (mu_j the model AVAR). At the largest taus of a log nu_j is 2-10, and there
// the chi-squared is far from Gaussian: skewed right, with a heavy upper tail and a light lower
// one, and a standard deviation proportional to mu_j. A Gaussian likelihood of v with the
// model's own variance therefore (a) finds a high last point very unlikely under a model
// without a large-tau term (its variance is small) and adds K or R for it, and (b) lets a model
// with a large-tau term "explain" any point by its larger variance. ln v removes both: for
// v = mu chi2_nu / nu,
//   E ln v   = ln mu + psi(nu/2) - ln(nu/2)        (psi: digamma)
//   Var ln v = psi'(nu/2)                          (psi': trigamma; -> 2/nu for large nu)
// so the variance of ln v depends on the EDF only, not on the level mu, and the residual of a
// point is the log of a ratio. The EDF of each point and the correlation between points come
// from the exact covariance Sigma under a reference model (fit_joint.cpp: the largest
// candidate model): nu_j = 2 mu_j^2 / Sigma_jj (bench_fit_accuracy sets it beside the spread
// of simulated estimates), and the correlation of ln v_a, ln v_b is taken as that of v_a, v_b
// (the delta method, exact for large nu):
//   r_j = ln v_j - ln mu_j - psi(nu_j/2) + ln(nu_j/2)
//   C   = S R S,  R = corr(Sigma),  S = diag(sqrt(psi'(nu_j/2)))
//   -2 ln L = r^T C^-1 r + ln det C   (+ constant)
#include <boost/math/special_functions/digamma.hpp>
#include <boost/math/special_functions/trigamma.hpp>

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <limits>

#include "fit_internal.hpp"

namespace sigmatau::detail {
namespace {

/// EDF cap: keeps nu finite when sigma_jj is tiny against mu_j^2 (a ramp-dominated point); at
/// 1e9 the offset of ln v is -1e-9 and its standard deviation 4.5e-5, an exact point for any
/// purpose of the fit.
constexpr double kMaxEdf = 1e9;

}  // namespace

LogScaleLikelihood::LogScaleLikelihood(const Eigen::VectorXd& v, const Eigen::VectorXd& mu,
                                       const Eigen::MatrixXd& sigma)
    : log_v_(v.size()) {
  const Eigen::Index n = v.size();
  Eigen::VectorXd s(n), sd(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    if (!(mu(j) > 0) || !(sigma(j, j) > 0) || !(v(j) > 0)) return;
    const double nu = std::min(2 * mu(j) * mu(j) / sigma(j, j), kMaxEdf);
    const double half = nu / 2;
    // ln v_j less its expected offset: the residual of a mean mu_j is log_v_(j) - ln mu_j.
    log_v_(j) = std::log(v(j)) - boost::math::digamma(half) + std::log(half);
    s(j) = std::sqrt(boost::math::trigamma(half));
    sd(j) = std::sqrt(sigma(j, j));
  }
  Eigen::MatrixXd c(n, n);
  for (Eigen::Index a = 0; a < n; ++a) {
    for (Eigen::Index b = 0; b < n; ++b) c(a, b) = s(a) * s(b) * sigma(a, b) / (sd(a) * sd(b));
  }
  llt_.compute(c);
  // Neighbouring points at averaging factors near N/2 can be correlated to within rounding of
  // 1: the same relative ridge as the GLS (fit_joint.cpp) restores positive definiteness.
  for (double ridge = 1e-12; llt_.info() != Eigen::Success && ridge <= 1e-3; ridge *= 10) {
    Eigen::MatrixXd ridged = c;
    ridged.diagonal() *= 1 + ridge;
    llt_.compute(ridged);
  }
  if (llt_.info() != Eigen::Success) return;
  log_det_ = 0;
  for (Eigen::Index j = 0; j < n; ++j) log_det_ += 2 * std::log(llt_.matrixL()(j, j));
  valid_ = true;
}

double LogScaleLikelihood::deviance(const Eigen::VectorXd& mu) const {
  if (!valid_ || !(mu.minCoeff() > 0)) return std::numeric_limits<double>::infinity();
  const Eigen::VectorXd r = log_v_ - mu.array().log().matrix();
  return llt_.matrixL().solve(r).squaredNorm() + log_det_;
}

}  // namespace sigmatau::detail
