// Lag sums sum_L w(L) c_t(L) c_r(L) and sum_L w(L) c_t(L) over every lag of one pair of
// averaging factors, in O(log N) evaluations of the lag correlations and O(1) memory.
//
// Glossary: L lag, -(n_a - 1) <= L <= n_b - 1; w(L) = min(n_a, n_b - L) - max(0, -L) (linear
// between L = 0 and L = n_b - n_a); breakpoints: the lags m_a i - m_b j (i, j in 0..2) where c
// has kinks (and Q its spikes), 0, n_b - n_a and the two ends.
//
// Between two breakpoints c_Q = 0, c_N, c_K are polynomials of degree <= 3 and w is linear, so
// every summand is a polynomial of degree <= 7; c_B and c_GM are analytic there, their nearest
// singularities within half a lag of the breakpoints. Each gap is summed as:
//   - kDirect lags next to each breakpoint one by one (the breakpoints themselves too);
//   - the rest in runs whose length does not exceed their distance to the nearest breakpoint
//     (lengths doubling away from both ends), each by a kNodes-point discrete Gauss rule for the
//     uniform measure on the run's integers.
// The rule sums polynomials of degree < 2 kNodes exactly, so Q, N, K and the ramp are exact up
// to rounding. For B and GM, a run whose singularity lies at least its own length away is the
// Bernstein-ellipse case rho = 3 + sqrt(8) = 5.83: the error falls as rho^(-2 kNodes) ~ 1e-18
// (measured against the direct sum over every lag in tests/test_fit_covariance.cpp).
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>

#include "fit_covariance_lags.hpp"

namespace sigmatau::detail {
namespace {

/// Gauss nodes per run: exact for the degree-7 compact terms with room to spare (degree 23),
/// and rho^-24 ~ 1e-18 for the analytic ones.
constexpr int kNodes = 12;
/// Lags summed one by one next to each breakpoint (the first run then starts kDirect + 1 away).
constexpr std::int64_t kDirect = 24;
/// Runs shorter than this are summed one by one (a Gauss rule saves little there).
constexpr std::int64_t kMinRun = 4 * kNodes;
/// Rules kept per process (run lengths repeat across pairs and layouts).
constexpr std::size_t kRuleCache = 4096;

DiscreteGaussRule cached_rule(std::int64_t big_m) {
  static std::mutex mutex;
  static std::map<std::int64_t, DiscreteGaussRule> cache;
  std::lock_guard lock(mutex);
  if (auto it = cache.find(big_m); it != cache.end()) return it->second;
  if (cache.size() >= kRuleCache) cache.erase(cache.begin());
  return cache.emplace(big_m, discrete_gauss_rule(big_m, kNodes)).first->second;
}

class Accumulator {
 public:
  Accumulator(const PairCorrelation& corr, std::int64_t na, std::int64_t nb)
      : corr_(corr),
        na_(static_cast<double>(na)),
        nb_(static_cast<double>(nb)),
        terms_(corr.terms()),
        c_(static_cast<std::size_t>(terms_)) {
    sums_.cc = Eigen::MatrixXd::Zero(terms_, terms_);
    sums_.c1 = Eigen::VectorXd::Zero(terms_);
  }
  /// Adds weight x w(lag) x (c c^T, c) at a lag (integer, or strictly inside a gap).
  void add(double lag, double weight) {
    corr_.evaluate(lag, c_);
    const double w = weight * (std::min(na_, nb_ - lag) - std::max(0.0, -lag));
    for (int t = 0; t < terms_; ++t) {
      const double wc = w * c_[static_cast<std::size_t>(t)];
      sums_.c1(t) += wc;
      for (int r = 0; r <= t; ++r) sums_.cc(t, r) += wc * c_[static_cast<std::size_t>(r)];
    }
  }
  void add_direct(std::int64_t first, std::int64_t last) {
    for (std::int64_t lag = first; lag <= last; ++lag) add(static_cast<double>(lag), 1.0);
  }
  void add_run(std::int64_t first, std::int64_t last) {
    const std::int64_t count = last - first + 1;
    if (count < kMinRun) return add_direct(first, last);
    const DiscreteGaussRule rule = cached_rule(count);
    for (int j = 0; j < kNodes; ++j)
      add(static_cast<double>(first) + rule.nodes(j), rule.weights(j));
  }
  LagSums finish() {
    for (int t = 0; t < terms_; ++t) {
      for (int r = 0; r < t; ++r) sums_.cc(r, t) = sums_.cc(t, r);
    }
    return std::move(sums_);
  }

 private:
  const PairCorrelation& corr_;
  double na_, nb_;
  int terms_;
  std::vector<double> c_;
  LagSums sums_;
};

/// The lags strictly between breakpoints s < e.
void sum_gap(Accumulator& acc, std::int64_t s, std::int64_t e) {
  const std::int64_t first = s + 1, last = e - 1;
  if (last < first) return;
  if (last - first + 1 <= 2 * kDirect + kMinRun) return acc.add_direct(first, last);
  acc.add_direct(first, first + kDirect - 1);
  acc.add_direct(last - kDirect + 1, last);
  std::int64_t a = first + kDirect, b = last - kDirect;  // remaining [a, b]
  while (b >= a) {
    const std::int64_t left = a - s, right = e - b, remaining = b - a + 1;
    if (remaining <= 2 * std::min(left, right)) {
      const std::int64_t half = remaining / 2;
      acc.add_run(a, a + half - 1);
      acc.add_run(a + half, b);
      return;
    }
    if (left <= right) {
      acc.add_run(a, a + left - 1);
      a += left;
    } else {
      acc.add_run(b - right + 1, b);
      b -= right;
    }
  }
}

}  // namespace

DiscreteGaussRule discrete_gauss_rule(std::int64_t big_m, int n) {
  // Jacobi matrix of the monic discrete Chebyshev (Gram) polynomials on 0..M-1:
  // alpha_k = (M - 1)/2, beta_k = k^2 (M^2 - k^2) / (4 (4 k^2 - 1)) (Golub-Welsch).
  const double m = static_cast<double>(big_m);
  Eigen::VectorXd diag = Eigen::VectorXd::Constant(n, (m - 1) / 2);
  Eigen::VectorXd sub(n - 1);
  for (int k = 1; k < n; ++k) {
    const double kd = k;
    sub(k - 1) = std::sqrt(kd * kd * (m * m - kd * kd) / (4 * (4 * kd * kd - 1)));
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver;
  solver.computeFromTridiagonal(diag, sub, Eigen::ComputeEigenvectors);
  DiscreteGaussRule rule;
  rule.nodes = solver.eigenvalues();
  rule.weights = m * solver.eigenvectors().row(0).transpose().array().square();
  return rule;
}

LagSums covariance_lag_sums(const PairCorrelation& corr, std::int64_t n_phase_points) {
  const std::int64_t ma = corr.ma(), mb = corr.mb();
  const std::int64_t na = n_phase_points - 2 * ma, nb = n_phase_points - 2 * mb;
  const std::int64_t lo = -(na - 1), hi = nb - 1;
  std::vector<std::int64_t> cuts{lo, hi, 0, nb - na};
  for (std::int64_t i = 0; i < 3; ++i) {
    for (std::int64_t j = 0; j < 3; ++j) cuts.push_back(i * ma - j * mb);
  }
  for (auto& x : cuts) x = std::clamp(x, lo, hi);
  std::sort(cuts.begin(), cuts.end());
  cuts.erase(std::unique(cuts.begin(), cuts.end()), cuts.end());
  Accumulator acc(corr, na, nb);
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    acc.add(static_cast<double>(cuts[i]), 1.0);
    if (i + 1 < cuts.size()) sum_gap(acc, cuts[i], cuts[i + 1]);
  }
  return acc.finish();
}

}  // namespace sigmatau::detail
