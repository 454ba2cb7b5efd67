#pragma once
// Misspecification-aware weights of the joint fit (fit_model_error.cpp): when no model
// describes a curve within the estimates' own scatter, each point is also given a model error
// proportional to the model's AVAR there.
#include "fit_select.hpp"

namespace sigmatau::detail {

/// A fit whose weights include a relative model error kappa:
/// Sigma_t = Sigma(theta) + kappa^2 diag(mu^2), mu = A theta.
struct WidenedFit {
  Iterated fit;          ///< fit.sigma is Sigma_t
  double kappa = 0;      ///< relative model error (0: the estimates' own covariance alone)
  double deviance = 0;   ///< -2 ln L of the curve under N(mu, Sigma_t), up to a constant
};

/// Sigma(theta) + kappa^2 diag(mu^2).
Eigen::MatrixXd widened_covariance(const Eigen::MatrixXd& sigma_model, const Eigen::VectorXd& mu, double kappa);

/// The Gaussian deviance r^T S^-1 r + ln det S of the curve, S = widened_covariance.
double widened_deviance(const Design& d, const TermVector& theta, const Eigen::MatrixXd& sigma_model,
                        double kappa);

/// The kappa in [0, 1] that minimises widened_deviance at theta (maximum likelihood).
double fit_model_error(const Design& d, const TermVector& theta, const Eigen::MatrixXd& sigma_model);

/// GLS of `mask` with weights iterated under the model and kappa re-estimated at each step,
/// from the fit with the estimates' own covariance, or from the GLS weighted by `start`.
WidenedFit iterate_widened(const Design& d, Mask mask, const CovarianceBasis& basis,
                           const Eigen::MatrixXd* start = nullptr);

/// (v - A theta)^T Sigma(theta)^-1 (v - A theta): the goodness-of-fit statistic from the
/// estimates' own covariance, whatever weights the fit used.
double own_chi2(const Design& d, const TermVector& theta, const CovarianceBasis& basis);

}  // namespace sigmatau::detail
