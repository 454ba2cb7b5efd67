#pragma once
// Model selection of the joint fit (fit_select.cpp) and the generalised least squares it shares
// with fit_joint.cpp (defined there).
#include <Eigen/Core>

#include <vector>

#include "fit_internal.hpp"

namespace sigmatau::detail {

/// Terms of a model as a bit set: bit k is term k of kFitTerms.
using Mask = unsigned;

/// Weight iterations of a fit at most (convergence takes 5-15 on simulated logs).
inline constexpr int kMaxWeightIterations = 60;

/// A curve to fit: design matrix A (n x terms: kTermCount, then one column per Gauss-Markov
/// term; exact AVAR per unit squared parameter) and the measured OAVAR v [(rate unit)^2].
struct Design {
  Eigen::MatrixXd a;
  Eigen::VectorXd v;
};

/// One non-negative GLS solution for a fixed weight matrix.
struct Gls {
  TermVector theta;          ///< one per column of the design
  double chi2 = 0;           ///< (v - A theta)^T Sigma^-1 (v - A theta)
  Eigen::MatrixXd whitened;  ///< L^-1 A restricted to the mask's columns
  std::vector<int> columns;  ///< term indices of the mask, ascending
};

/// A GLS whose weights are iterated with its own model.
struct Iterated {
  Gls fit;
  Eigen::MatrixXd sigma;  ///< the covariance of the last weights
  int iterations = 0;
};

/// Sigma under `theta`, its diagonal floored relative to v (keeps a ramp-only model definite).
Eigen::MatrixXd model_covariance(const CovarianceBasis& basis, const TermVector& theta,
                                 const Eigen::VectorXd& v);
/// Non-negative GLS of the terms in `mask` weighted by sigma^-1.
Gls gls(const Design& d, Mask mask, const Eigen::MatrixXd& sigma);
/// GLS iterated with its own model's covariance, from relative weights, at most
/// kMaxWeightIterations weight updates.
Iterated iterate(const Design& d, Mask mask, const CovarianceBasis& basis);
/// P(chi2_dof > chi2): the joint fit's goodness of fit (NaN when dof < 1 or chi2 is not finite).
double gof_p_value(double chi2, int dof);
/// Number of terms with theta_k > 0.
int count_positive(const TermVector& theta);
/// The terms with theta_k > 0 as a mask.
Mask used_terms(const TermVector& theta);
/// The prior penalties of the terms in `used` (kRampPriorPenalty, kQuantizationPriorPenalty).
double prior_penalty(Mask used);

/// Added to the criterion of every model with a rate ramp: -2 ln 0.02, a prior probability of
/// 2 % for a ramp. A ramp is a deterministic drift, rare in a static log, and from the last
/// three octave points of a 2 h log (EDF 23, 10, 4) its AVAR (~ tau^2) is hard to tell from a
/// random walk's (~ tau): without the prior R took K's place in 12 % of the MEMS gyro's
/// channels (bench_fit_accuracy, exploration seeds). A ramp that crosses the flicker floor
/// near 250 s (bench profile ramp_gyro) is still found in 89 % of channels (seeds 1-200; 87 %
/// on the exploration seeds), K in its place in 10 %.
inline constexpr double kRampPriorPenalty = 7.824046010856292;

/// Added to the criterion of every model with quantization (Q): -2 ln 0.1, a prior probability
/// of 10 %. Q and N are told apart at the shortest taus, where the estimates have 1e5-1e6 EDF,
/// so a quantization that matters is found with overwhelming evidence (bench profile
/// quantized_gyro: Q = 0.1 arcsec, 3.7 % of the AVAR at tau0, kept in every channel with or
/// without the prior); what the prior removes is BIC's chi-bar-squared false positive, a Q of
/// nothing added in ~4.4 % of curves with ln n alone (0.3 % with the prior). MEMS gyro true set
/// 89 -> 92 %, accelerometer 95 -> 99 % (exploration seeds 1001-1100).
inline constexpr double kQuantizationPriorPenalty = 4.605170185988091;

/// -2 ln L of the curve d.v under the model theta, up to a constant common to all models:
/// Wilson-Hilferty cube-root normal marginals with EDF 2 mu_j^2 / Sigma_jj, joined by a
/// Gaussian copula with Sigma's correlation (fit_select.cpp). +infinity when the model mean
/// or a v_j is not > 0.
double curve_deviance(const Design& d, const TermVector& theta, const CovarianceBasis& basis);

/// The model the joint fit keeps among the subsets of `candidates` (fit_select.cpp): BIC with
/// the largest model's weights for every subset; when that finds B, K and R decided again by
/// curve_deviance + (terms) ln n with each model's own iterated weights. A ramp pays
/// kRampPriorPenalty more in both stages, a quantization kQuantizationPriorPenalty more.
Mask select_model(const Design& d, Mask candidates, const CovarianceBasis& basis);

}  // namespace sigmatau::detail
