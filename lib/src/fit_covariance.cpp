// Exact covariance of overlapping Allan variance estimates across averaging factors.
//
// Glossary:
//   y_i     rate samples (per-sample process), tau0 sample interval [s], N = M + 1 phase points
//   d^a_k   second difference over m_a: (1/m_a)[sum_{i=k+m_a+1}^{k+2m_a} y_i -
//           sum_{i=k+1}^{k+m_a} y_i] (OAVAR s2_a = sum_{k<n_a} (d^a_k)^2 / (2 n_a),
//           n_a = N - 2 m_a)
//   c_ab(L) Cov(d^a_k, d^b_{k+L}) = int_{-1/2}^{1/2} S(f) G_a(f) conj(G_b(f)) e^{i 2 pi f L} df
//           with f in cycles per sample, S the two-sided per-sample PSD of y and G the transfer
//           function of the d kernel. G_a conj(G_b) = Phi_ab(f) e^{-i 2 pi f (m_a - m_b)},
//           Phi_ab = 4 sin^2(pi f m_a) sin^2(pi f m_b) / (m_a m_b sin^2(pi f)) (real, even).
//   w(L)    number of (k, l) with l - k = L, 0 <= k < n_a, 0 <= l < n_b
//   mu_a    mean of d^a for a rate ramp R: R m_a tau0
// For a Gaussian process Cov((d^a)^2, (d^b)^2) = 2 c^2 + 4 mu_a mu_b c, so
//   Cov(s2_a, s2_b) = (1/(4 n_a n_b)) sum_L w(L) [2 c_ab(L)^2 + 4 mu_a mu_b c_ab(L)].
// Per-sample PSDs for unit parameters (s = sin(pi f), THEORY.md sections 2 and 6):
//   Q: 4 s^2 / tau0^2 (y = (e_k - e_{k-1}) / tau0, var e = Q^2)   N: 1 / tau0
//   B: 1 / (2 |s|) (Kasdin, untruncated)   K: tau0 / (4 s^2)
//   GM: (1 - phi^2) / (1 - 2 phi cos w + phi^2)
// Quantization is the one term modelled as non-Gaussian: the phase error e of a rounding
// quantizer is uniform (THEORY.md section 6), with fourth cumulant kappa4 = -1.2 Q^4, which adds
//   kappa4 / (4 n_a n_b m_a^2 m_b^2 tau0^4) sum_i F_a(i) F_b(i)
// to Cov(s2_a, s2_b) (F_m(i): the sum over the second differences at m of their squared
// coefficient on e_i, kurtosis_overlap). It lowers the variance of the quantization-dominated
// estimates to ~0.7 of the Gaussian value, as measured on the simulator's quantizer.
// Lag sums (fit_covariance_lagsum.cpp, fit_covariance_kernels.cpp): c_ab(L) comes from the
// generalized covariance of the integrated rate in O(1) per lag (compact support |u| <= m_a +
// m_b and piecewise polynomial for Q, N, K; closed forms for B and GM), and the sum over every
// lag takes O(log N) evaluations with a discrete Gauss rule between c's breakpoints: exact up to
// rounding for Q, N, K and the ramp (3e-15 relative at m = 2^22), within 3e-14 of the direct sum
// over every lag for B and GM (tests/test_fit_covariance.cpp), O(1) memory per pair. The previous
// FFT of length 8 (m_a + m_b) (kept as a test and bench reference in
// tests/support/fit_covariance_fft.cpp) needed ~48 P bytes (3.2 GiB at m = 2^22) and truncated the flicker tail beyond 4 (m_a + m_b), which moved B's
// sums by up to ~1e-2 (bench/results_fit_covariance.md).
#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <tuple>

#include "fit_covariance_lags.hpp"
#include "fit_internal.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau::detail {
namespace {

/// Excess kurtosis of a uniform rounding error (IEEE quantization, Q = step / sqrt(12)):
/// E e^4 / (E e^2)^2 - 3 = 9/5 - 3.
constexpr double kUniformExcessKurtosis = -1.2;
/// Most layouts a process keeps (a bench uses a handful).
constexpr std::size_t kCacheSize = 16;

/// sum_i F_a(i) F_b(i) with F_m(i) = sum_k g_k(i)^2 over the n = N - 2m second differences
/// of the phase error e at factor m (g_k = 1, -2, 1 at i = k, k + m, k + 2m):
/// F_m(i) = [0 <= i < n] + 4 [m <= i < m + n] + [2m <= i < N]. Piecewise constant, so summed
/// over the segments between the breakpoints.
double kurtosis_overlap(std::int64_t ma, std::int64_t mb, std::int64_t big_n) {
  const auto f = [big_n](std::int64_t m, std::int64_t i) {
    const std::int64_t n = big_n - 2 * m;
    return (i < n ? 1.0 : 0.0) + (i >= m && i < m + n ? 4.0 : 0.0) + (i >= 2 * m ? 1.0 : 0.0);
  };
  std::vector<std::int64_t> cuts{0, big_n};
  for (const std::int64_t m : {ma, mb}) {
    const std::int64_t n = big_n - 2 * m;
    for (const std::int64_t c : {n, m, m + n, 2 * m}) cuts.push_back(c);
  }
  std::sort(cuts.begin(), cuts.end());
  double sum = 0;
  for (std::size_t j = 0; j + 1 < cuts.size(); ++j) {
    if (cuts[j + 1] <= cuts[j]) continue;
    sum += static_cast<double>(cuts[j + 1] - cuts[j]) * f(ma, cuts[j]) * f(mb, cuts[j]);
  }
  return sum;
}

/// Most pairs of factors whose lag sums a process keeps (~0.5 KB each with three GM terms).
constexpr std::size_t kPairCacheSize = 20000;

/// covariance_lag_sums of one pair, cached by (m_a, m_b, N, tau0, GM rates): the noise fit's
/// search for added terms (fit_added_terms.cpp), its refit without the filtered taus and its
/// guards build bases that share most pairs (the basis took 80 % of a real log's fit).
LagSums cached_lag_sums(std::int64_t ma, std::int64_t mb, double tau0_s, const std::vector<double>& rates,
                        std::int64_t n_phase_points) {
  using Key = std::tuple<std::int64_t, std::int64_t, std::int64_t, double, std::vector<double>>;
  static std::mutex mutex;
  static std::map<Key, LagSums> cache;
  Key key{ma, mb, n_phase_points, tau0_s, rates};
  {
    std::lock_guard lock(mutex);
    if (auto it = cache.find(key); it != cache.end()) return it->second;
  }
  LagSums sums = covariance_lag_sums(PairCorrelation(ma, mb, tau0_s, rates), n_phase_points);
  std::lock_guard lock(mutex);
  if (cache.size() >= kPairCacheSize) cache.clear();
  cache.emplace(std::move(key), sums);
  return sums;
}

}  // namespace

std::size_t CovarianceBasis::pair_index(std::size_t a, std::size_t b) const {
  if (a > b) std::swap(a, b);
  return b * (b + 1) / 2 + a;
}

Eigen::MatrixXd CovarianceBasis::covariance(const Eigen::VectorXd& theta) const {
  const auto n = static_cast<Eigen::Index>(m.size());
  Eigen::MatrixXd cov(n, n);
  for (Eigen::Index b = 0; b < n; ++b) {
    for (Eigen::Index a = 0; a <= b; ++a) {
      const double v = theta.dot(h[pair_index(a, b)] * theta);
      cov(a, b) = v;
      cov(b, a) = v;
    }
  }
  return cov;
}

CovarianceBasis build_covariance_basis(std::vector<std::int64_t> m, std::int64_t n_phase_points,
                                       double tau0_s, std::span<const double> gm_tau_c_s) {
  if (!(tau0_s > 0) || !std::isfinite(tau0_s)) throw Error("covariance: tau0 must be > 0 s");
  for (const auto mi : m) {
    if (!(mi >= 1) || !(n_phase_points - 2 * mi >= 1)) {
      throw Error("covariance: averaging factor " + std::to_string(mi) +
                  " has no OAVAR terms for N = " + std::to_string(n_phase_points));
    }
  }
  CovarianceBasis basis;
  basis.m = std::move(m);
  basis.n_phase_points = n_phase_points;
  basis.tau0_s = tau0_s;
  for (const double tc : gm_tau_c_s) {
    if (!(tc > 0) || !std::isfinite(tc)) throw Error("covariance: Gauss-Markov tau_c must be > 0 s");
  }
  basis.terms = kTermCount + static_cast<int>(gm_tau_c_s.size());
  const std::size_t taus = basis.m.size();
  basis.h.assign(taus * (taus + 1) / 2, Eigen::MatrixXd::Zero(basis.terms, basis.terms));

  // Stochastic terms (ramp excluded): indices into theta.
  std::vector<int> stochastic{0, 1, 2, 3};
  std::vector<double> gm_rates;
  for (std::size_t g = 0; g < gm_tau_c_s.size(); ++g) {
    stochastic.push_back(kTermCount + static_cast<int>(g));
    gm_rates.push_back(tau0_s / gm_tau_c_s[g]);
  }
  constexpr int kRamp = 4;
  const std::size_t ns = stochastic.size();

  for (std::size_t b = 0; b < taus; ++b) {
    for (std::size_t a = 0; a <= b; ++a) {
      const std::int64_t ma = basis.m[a], mb = basis.m[b];
      const LagSums sums = cached_lag_sums(ma, mb, tau0_s, gm_rates, n_phase_points);
      const double nn = static_cast<double>(n_phase_points - 2 * ma) *
                        static_cast<double>(n_phase_points - 2 * mb);
      Eigen::MatrixXd& h = basis.h[basis.pair_index(a, b)];
      for (std::size_t t = 0; t < ns; ++t) {
        const auto ti = static_cast<Eigen::Index>(t);
        for (std::size_t r = 0; r <= t; ++r) {
          const double v = sums.cc(ti, static_cast<Eigen::Index>(r)) / (2 * nn);
          h(stochastic[t], stochastic[r]) = v;
          h(stochastic[r], stochastic[t]) = v;
        }
        // Ramp cross term: (1/(n_a n_b)) tau_a tau_b sum w c, split over (R, t) and (t, R).
        const double ramp = static_cast<double>(ma) * tau0_s * static_cast<double>(mb) * tau0_s *
                            sums.c1(ti) / nn / 2;
        h(kRamp, stochastic[t]) = ramp;
        h(stochastic[t], kRamp) = ramp;
      }
    }
  }
  // Quantization's fourth cumulant (uniform rounding error, see the file comment).
  for (std::size_t b = 0; b < taus; ++b) {
    for (std::size_t a = 0; a <= b; ++a) {
      const double ma = static_cast<double>(basis.m[a]), mb = static_cast<double>(basis.m[b]);
      const double na = static_cast<double>(n_phase_points - 2 * basis.m[a]);
      const double nb = static_cast<double>(n_phase_points - 2 * basis.m[b]);
      const double s = kurtosis_overlap(basis.m[a], basis.m[b], n_phase_points);
      basis.h[basis.pair_index(a, b)](0, 0) +=
          kUniformExcessKurtosis * s / (4 * na * nb * ma * ma * mb * mb * std::pow(tau0_s, 4));
    }
  }
  return basis;
}

std::shared_ptr<const CovarianceBasis> covariance_basis(const std::vector<std::int64_t>& m,
                                                        std::int64_t n_phase_points,
                                                        double tau0_s) {
  using Key = std::tuple<std::vector<std::int64_t>, std::int64_t, double>;
  static std::mutex mutex;
  static std::map<Key, std::shared_ptr<const CovarianceBasis>> cache;
  Key key{m, n_phase_points, tau0_s};
  {
    std::lock_guard lock(mutex);
    if (auto it = cache.find(key); it != cache.end()) return it->second;
  }
  auto basis = std::make_shared<const CovarianceBasis>(
      build_covariance_basis(m, n_phase_points, tau0_s, {}));
  std::lock_guard lock(mutex);
  if (cache.size() >= kCacheSize) cache.clear();
  cache.emplace(std::move(key), basis);
  return basis;
}

}  // namespace sigmatau::detail

namespace sigmatau {

Eigen::MatrixXd oavar_covariance(const NoiseTerms& terms, std::span<const std::int64_t> m,
                                 std::int64_t n_phase_points, double tau0_s) {
  std::vector<double> tau_c;
  for (const auto& g : terms.gauss_markov) tau_c.push_back(g.tau_c_s);
  const auto basis = detail::build_covariance_basis(std::vector<std::int64_t>(m.begin(), m.end()),
                                                    n_phase_points, tau0_s, tau_c);
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(basis.terms);
  const auto sq = [](const std::optional<double>& v) { return v ? *v * *v : 0.0; };
  theta(0) = sq(terms.quantization);
  theta(1) = sq(terms.white);
  theta(2) = sq(terms.bias_instability);
  theta(3) = sq(terms.rate_random_walk);
  theta(4) = sq(terms.rate_ramp);
  for (std::size_t g = 0; g < tau_c.size(); ++g) {
    theta(detail::kTermCount + static_cast<Eigen::Index>(g)) = terms.gauss_markov[g].sigma * terms.gauss_markov[g].sigma;
  }
  return basis.covariance(theta);
}

}  // namespace sigmatau
