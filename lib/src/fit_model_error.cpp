// Misspecification-aware weights of the joint fit.
//
// On a real sensor's curve no model of a few terms is exact, and at the shortest taus of a long
// log the OAVAR estimates have EDFs near 1e6 (relative sd 0.14 %): weighted by their own
// covariance alone, a 2 % departure there (a sensor's filter, a quantizer) outweighs everything
// the long taus say, and the other terms absorb it (the ADIS16405 accelerometers' fitted K sat
// 2-4x above the curve at 1000 s). Each point is therefore also given a model error
// proportional to the model's AVAR there, Sigma_t = Sigma(theta) + kappa^2 diag(mu^2), with
// kappa chosen by maximum likelihood of the curve under N(mu, Sigma_t) (a Gaussian in v, as the
// GLS itself), re-estimated at each weight update. A point then weighs 1 / (its own variance +
// (kappa mu_j)^2): the long taus count again, and the parameters' intervals widen by the
// scatter the model leaves. Used only when the model is rejected (p < 1e-3 from the estimates'
// own covariance, which is what goodness of fit keeps reporting: own_chi2).
#include "fit_model_error.hpp"

#include <Eigen/Cholesky>

#include <cmath>
#include <limits>

#include "golden_section.hpp"

namespace sigmatau::detail {
namespace {

/// kappa is searched in ln kappa over [kKappaMin, kKappaMax] (a model error below 1e-6 of the
/// AVAR is nothing next to any estimate's own scatter; above 1 the model says nothing).
constexpr double kKappaMin = 1e-6;
constexpr double kKappaMax = 1.0;
constexpr int kKappaSteps = 40;
/// Weight updates at most, and the relative change of theta and kappa that ends them.
constexpr int kMaxUpdates = 40;
constexpr double kConvergence = 1e-8;

}  // namespace

Eigen::MatrixXd widened_covariance(const Eigen::MatrixXd& sigma_model, const Eigen::VectorXd& mu, double kappa) {
  Eigen::MatrixXd s = sigma_model;
  s.diagonal() += (kappa * mu).array().square().matrix();
  return s;
}

double widened_deviance(const Design& d, const TermVector& theta, const Eigen::MatrixXd& sigma_model,
                        double kappa) {
  const Eigen::VectorXd mu = d.a * theta;
  const Eigen::LLT<Eigen::MatrixXd> llt(widened_covariance(sigma_model, mu, kappa));
  if (llt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  double log_det = 0;
  for (Eigen::Index j = 0; j < mu.size(); ++j) log_det += 2 * std::log(llt.matrixL()(j, j));
  return llt.matrixL().solve(d.v - mu).squaredNorm() + log_det;
}

double fit_model_error(const Design& d, const TermVector& theta, const Eigen::MatrixXd& sigma_model) {
  // Golden-section search in ln kappa; kappa = 0 (no model error) competes with the result.
  const GoldenMinimum best = golden_section_minimum(
      [&](double x) { return widened_deviance(d, theta, sigma_model, std::exp(x)); }, std::log(kKappaMin),
      std::log(kKappaMax), kKappaSteps);
  return best.f < widened_deviance(d, theta, sigma_model, 0) ? std::exp(best.x) : 0.0;
}

WidenedFit iterate_widened(const Design& d, Mask mask, const CovarianceBasis& basis, const Eigen::MatrixXd* start) {
  WidenedFit out;
  if (start) {
    out.fit.fit = gls(d, mask, *start);
    out.fit.sigma = *start;
  } else {
    out.fit = iterate(d, mask, basis);
  }
  Eigen::MatrixXd sigma_model = model_covariance(basis, out.fit.fit.theta, d.v);
  for (int it = 0; it < kMaxUpdates; ++it) {
    const double kappa = fit_model_error(d, out.fit.fit.theta, sigma_model);
    const Eigen::MatrixXd sigma = widened_covariance(sigma_model, d.a * out.fit.fit.theta, kappa);
    Gls next = gls(d, mask, sigma);
    double change = std::abs(kappa - out.kappa) / std::max(kappa, kKappaMin);
    for (Eigen::Index k = 0; k < next.theta.size(); ++k) {
      const double ref = std::max(next.theta(k), out.fit.fit.theta(k));
      if (ref > 0) change = std::max(change, std::abs(next.theta(k) - out.fit.fit.theta(k)) / ref);
    }
    out.kappa = kappa;
    out.fit.fit = std::move(next);
    out.fit.sigma = sigma;
    ++out.fit.iterations;
    sigma_model = model_covariance(basis, out.fit.fit.theta, d.v);
    if (change < kConvergence) break;
  }
  out.deviance = widened_deviance(d, out.fit.fit.theta, sigma_model, out.kappa);
  return out;
}

double own_chi2(const Design& d, const TermVector& theta, const CovarianceBasis& basis) {
  const Eigen::LLT<Eigen::MatrixXd> llt(model_covariance(basis, theta, d.v));
  if (llt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  return llt.matrixL().solve(d.v - d.a * theta).squaredNorm();
}

}  // namespace sigmatau::detail
