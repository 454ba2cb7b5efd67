#pragma once
// Internals of the noise fit (fit.cpp, fit_covariance.cpp, fit_joint.cpp, fit_slopes.cpp).
#include <Eigen/Core>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "sigmatau/fit.hpp"

namespace sigmatau::detail {

/// Number of linear fit terms (Q, N, B, K, R, in kFitTerms order).
inline constexpr int kTermCount = 5;
/// Squared parameters of a model: the kTermCount linear terms, then the squared sigma of each
/// Gauss-Markov term the design holds (fit_added_terms.cpp).
using TermVector = Eigen::VectorXd;

/// Index of a term in kFitTerms (Error for Gauss-Markov and sinusoid).
int term_index(NoiseTerm term);

/// The OAVAR covariance as a quadratic form in the squared parameters:
/// Cov(s2_a, s2_b) = theta^T H_ab theta, theta = (Q^2, N^2, B^2, K^2, R^2 [, GM sigma_g^2...]).
/// Depends only on the averaging factors, N and tau0 (and the GM correlation time), so it is
/// built once per curve layout (covariance_basis caches it).
struct CovarianceBasis {
  std::vector<std::int64_t> m;
  std::int64_t n_phase_points = 0;
  double tau0_s = 0;
  int terms = kTermCount;               ///< 5 + the number of Gauss-Markov terms (last)
  std::vector<Eigen::MatrixXd> h;       ///< pair (a <= b) at index pair_index(a, b)

  std::size_t pair_index(std::size_t a, std::size_t b) const;
  /// The covariance matrix for squared parameters `theta` (size `terms`).
  Eigen::MatrixXd covariance(const Eigen::VectorXd& theta) const;
};

/// Builds the basis: closed-form lag correlations of every term summed by quadrature between
/// their kinks (fit_covariance_lagsum.cpp); O(1) memory, about 0.1 s per layout at any length.
/// `gm_tau_c_s`: the correlation times of the Gauss-Markov terms modelled (at most
/// kMaxGaussMarkov), whose squared sigmas follow the five linear terms in theta.
CovarianceBasis build_covariance_basis(std::vector<std::int64_t> m, std::int64_t n_phase_points,
                                       double tau0_s, std::span<const double> gm_tau_c_s);

/// Process-wide cache of build_covariance_basis for the five linear terms (a bench or a triad
/// fits many curves of the same layout). Thread-safe.
std::shared_ptr<const CovarianceBasis> covariance_basis(const std::vector<std::int64_t>& m,
                                                        std::int64_t n_phase_points,
                                                        double tau0_s);

/// One usable AVAR point.
struct AvarPoint {
  std::int64_t m = 0;
  double tau_s = 0;
  double avar = 0;  ///< [(rate unit)^2]
  double dev = 0;
  double edf = 0;
  int alpha = 0;
};

ChannelFit fit_joint(const std::vector<AvarPoint>& points, const CurveSource& source,
                     const FitOptions& options);
/// `j_min`: index in `points` of the smallest ADEV (B's read-out point).
ChannelFit fit_slopes(const std::vector<AvarPoint>& points, const CurveSource& source,
                      const FitOptions& options, std::size_t j_min);

/// The consistency guards (fit_guards.cpp) of `fit` on its fitted `points`, whose smallest
/// dev is at `j_min`: empty when the curve contradicts nothing the fit reports.
std::vector<Contradiction> check_against_curve(const ChannelFit& fit,
                                               const std::vector<AvarPoint>& points,
                                               std::size_t j_min, const CurveSource& source);

/// Lowers each kept term of the read-outs `fit` but B (whose read-out is the minimum itself) to
/// the largest value whose own ADEV stays within every fitted point's kGuardLevel interval
/// (ParameterEstimate::lowered_to_curve): the tangent read-out where the fitted line crosses
/// the curve.
void lower_to_curve(ChannelFit& fit, const std::vector<AvarPoint>& points, const CurveSource& source);

/// Non-negative least squares min ||A x - b||, x >= 0 (Lawson-Hanson active set).
Eigen::VectorXd nnls(const Eigen::MatrixXd& a, const Eigen::VectorXd& b);

}  // namespace sigmatau::detail
