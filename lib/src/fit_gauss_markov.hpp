#pragma once
// Gauss-Markov terms in the joint fit (fit_gauss_markov.cpp): when no model of the five IEEE
// terms describes a curve, up to kMaxGaussMarkovTerms first-order Gauss-Markov processes are
// added, each a column of the design (linear in sigma^2 at a fixed correlation time) whose
// correlation time is searched on a grid and refined.
#include <memory>
#include <optional>
#include <vector>

#include "fit_model_error.hpp"
#include "fit_select.hpp"

namespace sigmatau::detail {

/// Most Gauss-Markov terms the fit adds (GMWM practice: a real MEMS bias is often a sum of a
/// few; the covariance basis models up to kMaxLagGaussMarkov).
inline constexpr int kMaxGaussMarkovTerms = 3;

/// The IEEE model is extended only when its goodness of fit is below this p value: a curve the
/// five terms describe keeps them (simulated IEEE logs are not given Gauss-Markov terms).
inline constexpr double kExtendBelowPValue = 1e-3;

/// Exact sampled AVAR at each m of a Gauss-Markov process of unit sigma and correlation time
/// `tau_c_s` (sampled_avar).
Eigen::VectorXd gauss_markov_column(const std::vector<std::int64_t>& m, double tau0_s, double tau_c_s);

/// A model with Gauss-Markov terms: the design (kTermCount columns, then one per term), its
/// covariance basis, the terms kept (bits 0..4 the IEEE terms, bit kTermCount + g the g-th
/// Gauss-Markov) and the fit with weights iterated under it.
struct ExtendedModel {
  std::vector<double> tau_c_s;  ///< ascending, one per Gauss-Markov column
  Design design;
  std::shared_ptr<const CovarianceBasis> basis;
  Mask mask = 0;
  Iterated fit;          ///< weights with the model error (fit_model_error.hpp)
  double kappa = 0;      ///< relative model error of the weights
  double criterion = 0;  ///< widened deviance + (parameters) ln n + priors
};

/// Fits the rejected IEEE model `base` (a subset of `candidates`) with misspecification-aware
/// weights (iterate_widened) and adds Gauss-Markov terms, one at a time (the IEEE terms chosen
/// again with each addition), while the criterion falls. The result holds no Gauss-Markov
/// term when the first addition does not lower it. `ms` are the design's averaging factors.
ExtendedModel extend_with_gauss_markov(const Design& d, const std::vector<std::int64_t>& ms,
                                       const CurveSource& source, Mask base, Mask candidates,
                                       std::shared_ptr<const CovarianceBasis> basis);

}  // namespace sigmatau::detail
