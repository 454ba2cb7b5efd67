// Model selection of the joint fit, in two stages (fit_joint.cpp's header records what was
// measured, kept and rejected):
//  1. Every subset of the candidates is fitted with one weight matrix, the largest model's,
//     and the smallest chi2 + (terms) ln n (BIC) wins, a rate ramp paying kRampPriorPenalty
//     more and a quantization kQuantizationPriorPenalty (fit_select.hpp says why). Common
//     weights judge every subset by the same variances, so no model can explain a point by its
//     own larger variance; that choice between a flicker floor (B) and a rise
//     at the end (K, R) is the robust one where the end of the curve is all there is.
//  2. When stage 1 found a flicker floor (B), the terms that show only above it at the end of
//     the curve, K and R, are decided again: the four combinations of K and R with the other
//     terms of stage 1 are each fitted with weights iterated under their own model and judged
//     by an approximate likelihood of the whole curve (curve_deviance) + (terms) ln n (+ the
//     ramp's prior). Judging a model without K by the variance of a model with K (stage 1)
//     understates the evidence for K; its own, small variance at large tau is where that
//     evidence lies.
//
// Likelihood of an OAVAR curve v under a model with mean mu = A theta and covariance
// Sigma(theta) (CovarianceBasis). Each v_j is approximately mu_j chi2_nu / nu, nu_j =
// 2 mu_j^2 / Sigma_jj: 51, 23, 10, 4 at the four largest octave taus of a 2 h, 100 Hz log, where
// K and R show. A Gaussian in v misjudges those skewed points, ln v needs an offset that
// depends on nu. The Wilson-Hilferty cube root is close to Gaussian even at nu = 2-4:
//   z_j = ((v_j / mu_j)^(1/3) - 1 + c_j) / sqrt(c_j),  c_j = 2 / (9 nu_j)
// (z_j ~ N(0, 1) under the model). The points are joined by a Gaussian copula whose
// correlation R is that of Sigma (exact for large nu). With the Jacobian of v -> z, whose
// model-dependent part is prod_j 3 sqrt(c_j) mu_j^(1/3) (the v_j^(-2/3) factor is the same
// for every model), the deviance is
//   D(theta) = z^T R^-1 z + ln det R + sum_j [ ln c_j + (2/3) ln mu_j ]   (+ a constant).
// It is a density of v for every model: a model that puts more variance at large tau pays for
// it in the normalisation, so K or R cannot "explain" a high last point by its variance alone
// (the bias of per-subset weights without a likelihood).
#include "fit_select.hpp"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sigmatau::detail {
namespace {

/// EDF cap: a ramp-dominated point can have Sigma_jj far below mu_j^2; at 1e9 the point is
/// exact for any purpose of the selection and c_j stays representable.
constexpr double kMaxEdf = 1e9;
/// Relative ridge on the correlation's diagonal when its Cholesky factorisation fails
/// (neighbouring points near m = N/2 correlated to within rounding): first and largest tried.
constexpr double kRidgeStart = 1e-12;
constexpr double kRidgeMax = 1e-3;


/// Stage 1: BIC with the largest model's weights for every subset (+ the priors).
Mask select_common_weights(const Design& d, Mask all, const CovarianceBasis& basis, double penalty) {
  const Iterated full = iterate(d, all, basis);
  double best = std::numeric_limits<double>::infinity();
  Mask model = all;
  for (Mask s = 1; s <= all; ++s) {
    if ((s & all) != s) continue;
    const Gls g = gls(d, s, full.sigma);
    const int k = count_positive(g.theta);
    if (k == 0) continue;
    const Mask used = used_terms(g.theta);
    const double crit = g.chi2 + k * penalty + prior_penalty(used);
    if (crit < best) {
      best = crit;
      model = used;
    }
  }
  return model;
}

/// Stage 2's criterion of one subset: fitted with its own iterated weights; +infinity when the
/// fit puts one of its terms at 0 (that is the smaller subset, judged on its own).
double own_weights_criterion(const Design& d, Mask s, const CovarianceBasis& basis, double penalty) {
  const Iterated fit = iterate(d, s, basis);
  if (used_terms(fit.fit.theta) != s) return std::numeric_limits<double>::infinity();
  return curve_deviance(d, fit.fit.theta, basis) + count_positive(fit.fit.theta) * penalty +
         prior_penalty(s);
}

}  // namespace

Mask used_terms(const TermVector& theta) {
  Mask used = 0;
  for (Eigen::Index t = 0; t < theta.size(); ++t) used |= theta(t) > 0 ? (1u << t) : 0u;
  return used;
}

double prior_penalty(Mask used) {
  const Mask ramp = 1u << term_index(NoiseTerm::rate_ramp);
  const Mask quantization = 1u << term_index(NoiseTerm::quantization);
  return ((used & ramp) ? kRampPriorPenalty : 0.0) +
         ((used & quantization) ? kQuantizationPriorPenalty : 0.0);
}

double curve_deviance(const Design& d, const TermVector& theta, const CovarianceBasis& basis) {
  const Eigen::VectorXd mu = d.a * theta;
  const Eigen::MatrixXd sigma = model_covariance(basis, theta, d.v);
  const Eigen::Index n = mu.size();
  Eigen::VectorXd z(n);
  const Eigen::VectorXd sd = sigma.diagonal().cwiseSqrt();
  double normalisation = 0;
  for (Eigen::Index j = 0; j < n; ++j) {
    if (!(mu(j) > 0) || !(d.v(j) > 0)) return std::numeric_limits<double>::infinity();
    const double nu = std::min(2 * mu(j) * mu(j) / sigma(j, j), kMaxEdf);
    const double c = 2 / (9 * nu);
    z(j) = (std::cbrt(d.v(j) / mu(j)) - 1 + c) / std::sqrt(c);
    normalisation += std::log(c) + (2.0 / 3.0) * std::log(mu(j));
  }
  Eigen::MatrixXd r(n, n);
  for (Eigen::Index a = 0; a < n; ++a) {
    for (Eigen::Index b = 0; b < n; ++b) r(a, b) = sigma(a, b) / (sd(a) * sd(b));
  }
  Eigen::LLT<Eigen::MatrixXd> llt(r);
  for (double ridge = kRidgeStart; llt.info() != Eigen::Success && ridge <= kRidgeMax; ridge *= 10) {
    Eigen::MatrixXd ridged = r;
    ridged.diagonal() *= 1 + ridge;
    llt.compute(ridged);
  }
  if (llt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  double log_det = 0;
  for (Eigen::Index j = 0; j < n; ++j) log_det += 2 * std::log(llt.matrixL()(j, j));
  return llt.matrixL().solve(z).squaredNorm() + log_det + normalisation;
}

Mask select_model(const Design& d, Mask all, const CovarianceBasis& basis) {
  const double penalty = std::log(static_cast<double>(d.v.size()));
  const Mask stage1 = select_common_weights(d, all, basis, penalty);
  if (!(stage1 & (1u << term_index(NoiseTerm::bias_instability)))) return stage1;
  const Mask end_terms = (1u << term_index(NoiseTerm::rate_random_walk)) | (1u << term_index(NoiseTerm::rate_ramp));
  const Mask rest = stage1 & ~end_terms;
  double best = std::numeric_limits<double>::infinity();
  Mask model = stage1;
  for (Mask e = 0; e <= end_terms; ++e) {
    if ((e & end_terms) != e || (e & all) != e) continue;
    if (const double crit = own_weights_criterion(d, rest | e, basis, penalty); crit < best) {
      best = crit;
      model = rest | e;
    }
  }
  return model;
}

}  // namespace sigmatau::detail
