#pragma once
// Intervals of a joint fit with added terms (fit_added_intervals.cpp): the covariance of the
// fitted parameters when each Gauss-Markov term's correlation time and the sinusoid's frequency
// are estimated too, and the scatter a noise adds to a sinusoid's AVAR estimates.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "fit_select.hpp"

namespace sigmatau::detail {

/// The OAVAR covariance a sinusoid adds on top of the noise's own (the noise-sinusoid cross term
/// of the squared second differences), phase-averaged, for sums over many periods:
///   Cov(s2_a, s2_b) += 8 A^2 a_a a_b S(f tau0) / max(n_a, n_b),
/// a_m the sinusoid's AVAR per unit A^2 at m (sinusoid_column), S the noise's two-sided
/// per-sample PSD at the sinusoid's frequency (the unit PSDs of fit_covariance.cpp times the
/// squared parameters), n_m = n_phase_points - 2 m the second differences at m.
/// `theta`: the fit's squared parameters, laid out as the design (Q, N, B, K, R, one per GM in
/// `tau_c_s` order, the sinusoid's A^2 last). Units: (rate unit)^4.
Eigen::MatrixXd sinusoid_cross_covariance(const std::vector<std::int64_t>& ms,
                                          std::int64_t n_phase_points, double tau0_s,
                                          const std::vector<double>& tau_c_s, double frequency_hz,
                                          const TermVector& theta);

/// Covariance of a fit with added terms, over its kept columns (fit.columns order) followed by
/// ln T_c of each Gauss-Markov term (tau_c_s order) and ln f of the sinusoid if any.
struct AddedCovariance {
  Eigen::MatrixXd theta;            ///< of the squared parameters, fit.columns order
  std::vector<double> ln_tau_c_sd;  ///< sd of ln T_c per Gauss-Markov term (dimensionless)
  double ln_frequency_sd = 0;       ///< sd of ln f of the sinusoid (0 when none)
};

/// The delta-method covariance of the fitted parameters with T_c and f floating: the GLS
/// Jacobian of the model AVAR A theta extended by d(A theta)/d ln T_c and d(A theta)/d ln f
/// (central differences of the exact columns), weighted as the fit was (`weights_sigma`, the
/// covariance of its last weights), with the estimates' covariance `weights_sigma` plus the
/// sinusoid's cross term (sinusoid_cross_covariance) in the sandwich. `d`: the design with the
/// added columns (GMs after the IEEE terms, then the sinusoid).
AddedCovariance added_term_covariance(const Design& d, const Gls& fit,
                                      const Eigen::MatrixXd& weights_sigma,
                                      const std::vector<std::int64_t>& ms,
                                      std::int64_t n_phase_points, double tau0_s,
                                      const std::vector<double>& tau_c_s,
                                      std::optional<double> sinusoid_hz);

/// An interval [low, high] of a profile (fit_added_intervals.cpp).
struct ProfileInterval {
  double low = 0;
  double high = 0;
};

/// Profile-likelihood interval of Gauss-Markov term `g`'s squared sigma [(rate unit)^2]: the
/// sigma^2 whose deviance, minimised over its T_c and the other kept terms (T_c by golden section
/// in ln T_c, the rest by the non-negative GLS), stays within `q` (the chi-squared(1) quantile of
/// the level) of the fit's, weighted by the fixed `sigma` (the fit's last weights). `d` holds the
/// fitted columns at the estimated T_c, `mask` the fit's kept columns.
ProfileInterval gauss_markov_sigma2_profile(const Design& d, Mask mask,
                                            const Eigen::MatrixXd& sigma,
                                            const std::vector<std::int64_t>& ms, double tau0_s,
                                            std::size_t g, double tau_c_s, double q);

/// Profile-likelihood interval of Gauss-Markov term `g`'s T_c [s]: the T_c whose deviance,
/// minimised over every kept term's squared parameter, stays within `q` of the fit's (as above),
/// searched from tau0 / 4 to the log's length (the search's range). A side the curve does not
/// bound there is 0 (low) or infinity (high); likewise sigma^2's high side above.
ProfileInterval gauss_markov_tau_c_profile(const Design& d, Mask mask, const Eigen::MatrixXd& sigma,
                                           const std::vector<std::int64_t>& ms,
                                           std::int64_t n_phase_points, double tau0_s,
                                           std::size_t g, double tau_c_s, double q);

}  // namespace sigmatau::detail
