#pragma once
// Terms real sensors add to the five IEEE terms, in the joint fit (fit_added_terms.cpp): when
// no model of the IEEE terms describes a curve, up to kMaxGaussMarkov (noise_model.hpp) first-order
// Gauss-Markov processes and one sinusoid are added, each a column of the design (linear in
// its squared magnitude at a fixed correlation time or frequency), the correlation time or
// frequency searched on a grid and refined.
#include <memory>
#include <optional>
#include <vector>

#include "fit_model_error.hpp"
#include "fit_select.hpp"

namespace sigmatau::detail {

/// The IEEE model is extended only when its goodness of fit is below this p value: a curve the
/// five terms describe keeps them (simulated IEEE logs are not given added terms).
inline constexpr double kExtendBelowPValue = 1e-3;

/// Exact sampled AVAR at each m of a Gauss-Markov process of unit sigma and correlation time
/// `tau_c_s` (sampled_avar).
Eigen::VectorXd gauss_markov_column(const std::vector<std::int64_t>& m, double tau0_s, double tau_c_s);
/// The same for a sinusoid of unit amplitude at `frequency_hz` (phase-averaged, point samples).
Eigen::VectorXd sinusoid_column(const std::vector<std::int64_t>& m, double tau0_s, double frequency_hz);

/// A model with added terms. Design columns: the kTermCount IEEE terms, one per Gauss-Markov
/// term (tau_c_s order), then the sinusoid if any. The covariance basis holds the IEEE and
/// Gauss-Markov terms; a sinusoid's AVAR estimates are taken as exact (their scatter is left
/// to the model error). `mask`: bits 0..4 the IEEE terms kept, the added terms always kept.
struct ExtendedModel {
  std::vector<double> tau_c_s;          ///< one per Gauss-Markov column
  std::optional<double> sinusoid_hz;    ///< the sinusoid's frequency, when one is added
  Design design;
  std::shared_ptr<const CovarianceBasis> basis;
  Mask mask = 0;
  Iterated fit;          ///< weights with the model error (fit_model_error.hpp)
  double kappa = 0;      ///< relative model error of the weights
  double criterion = 0;  ///< widened deviance + (parameters) ln n + priors
};

/// Fits the rejected IEEE model `base` (a subset of `candidates`) with misspecification-aware
/// weights (iterate_widened) and adds Gauss-Markov terms or a sinusoid, one at a time (the IEEE
/// terms chosen again with each addition) or two at once when no single one helps, while the
/// criterion falls, then drops any term the others stand in for (and searches forward again).
/// The result holds no added term when no addition lowers the criterion. `ms` are the design's
/// factors.
ExtendedModel extend_with_added_terms(const Design& d, const std::vector<std::int64_t>& ms,
                                      const CurveSource& source, Mask base, Mask candidates,
                                      std::shared_ptr<const CovarianceBasis> basis);

}  // namespace sigmatau::detail
