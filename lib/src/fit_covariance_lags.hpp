#pragma once
// Lag correlations and lag sums of the OAVAR covariance (fit_covariance.cpp builds the basis
// from them). Notation as in fit_covariance.cpp: d^a_k the second difference at factor m_a,
// c_ab(L) = Cov(d^a_k, d^b_{k+L}) per unit squared parameter, u = L - (m_a - m_b) (c is even
// in u), w(L) the number of pairs of terms at lag L, n_a = N - 2 m_a.
//
// The stochastic terms are indexed in this order everywhere here: Q, N, B, K [, GM 1, GM 2, ...].
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "sigmatau/noise_model.hpp"

namespace sigmatau::detail {

/// Number of stochastic terms without Gauss-Markov (Q, N, B, K).
inline constexpr int kLagTerms = 4;

/// Lag sums of one pair of averaging factors over all lags -(n_a - 1) <= L <= n_b - 1.
struct LagSums {
  Eigen::MatrixXd cc;  ///< (t, r): sum_L w(L) c_t(L) c_r(L), symmetric
  Eigen::VectorXd c1;  ///< t: sum_L w(L) c_t(L)
};

/// c_ab(L) of each stochastic term for one pair (m_a, m_b), from the generalized covariance of
/// the integrated rate (fit_covariance_kernels.cpp). O(1) time and memory per lag.
class PairCorrelation {
 public:
  /// `gm_rates`: tau0 / tau_c (decay per sample) of each Gauss-Markov term modelled (empty:
  /// none); their correlations follow K's, in this order.
  PairCorrelation(std::int64_t ma, std::int64_t mb, double tau0_s,
                  std::span<const double> gm_rates = {});
  /// 4 + the number of Gauss-Markov terms.
  int terms() const { return kLagTerms + static_cast<int>(gm_.size()); }
  /// c_t(lag) for every term into `c` (size terms()). `lag` is an integer for every term; a
  /// non-integer lag (a quadrature node) is allowed strictly between the breakpoints
  /// m_a i - m_b j (i, j in 0..2), where the quantization spikes are zero. Units per unit
  /// squared parameter: Q [1/s^2], N [1/s], B [1], K [s], each GM [1].
  void evaluate(double lag, std::span<double> c) const;
  std::int64_t ma() const { return ma_; }
  std::int64_t mb() const { return mb_; }

 private:
  std::int64_t ma_, mb_;
  double tau0_s_;
  /// One first-order Gauss-Markov term's constants for this pair (see the constructor).
  struct GaussMarkovPair {
    double rate = 0;  ///< a = tau0 / tau_c
    double scale = 0, linear = 0, far = 0, inner = 0;
  };
  std::vector<GaussMarkovPair> gm_;
};

/// The flicker (Kasdin untruncated, S = 1 / (2 |sin pi f|)) generalized covariance of the
/// integrated rate at a lag of |l| >= 1 samples (0 at l = 0): (2/pi) [(4 l^2 - 1)/8 O(|l| - 1)
/// - |l| (|l| - 1)/2 + (|l| - 1)^2 / 8], O(n) = sum_{k=1}^n 1 / (2k - 1). Exposed for tests.
double flicker_phase_covariance(double l);

/// Lag sums of `corr` over every lag for N = n_phase_points: exact up to rounding for Q, N, K
/// and the ramp (piecewise polynomial), converged to ~1e-13 relative for B and GM (discrete
/// Gauss quadrature between breakpoints, fit_covariance_lagsum.cpp). O(log N) evaluations.
LagSums covariance_lag_sums(const PairCorrelation& corr, std::int64_t n_phase_points);

/// Nodes (offsets in [0, M-1]) and weights of the n-point Gauss rule for the uniform measure on
/// the integers 0..M-1: sum_{i<M} p(i) = sum_j weight_j p(node_j) for every polynomial of
/// degree < 2n. Requires M >= n. Exposed for tests.
struct DiscreteGaussRule {
  Eigen::VectorXd nodes, weights;
};
DiscreteGaussRule discrete_gauss_rule(std::int64_t big_m, int n);

}  // namespace sigmatau::detail
