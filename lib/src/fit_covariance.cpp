// Exact covariance of overlapping Allan variance estimates across averaging factors.
//
// Glossary:
//   y_i     rate samples (per-sample process), tau0 sample interval [s], N = M + 1 phase points
//   d^a_k   second difference over m_a: (1/m_a)[sum_{i=k+m_a+1}^{k+2m_a} y_i - sum_{i=k+1}^{k+m_a} y_i]
//           (OAVAR s2_a = sum_{k<n_a} (d^a_k)^2 / (2 n_a), n_a = N - 2 m_a)
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
//   B: 1 / (2 |s|) (Kasdin, untruncated)   K: tau0 / (4 s^2)   GM: (1-phi^2)/(1 - 2 phi cos w + phi^2)
// Quantization is the one term modelled as non-Gaussian: the phase error e of a rounding
// quantizer is uniform (THEORY.md section 6), with fourth cumulant kappa4 = -1.2 Q^4, which adds
//   kappa4 / (4 n_a n_b m_a^2 m_b^2 tau0^4) sum_i F_a(i) F_b(i)
// to Cov(s2_a, s2_b) (F_m(i): the sum over the second differences at m of their squared
// coefficient on e_i, kurtosis_overlap). It lowers the variance of the quantization-dominated
// estimates to ~0.7 of the Gaussian value, as measured on the simulator's quantizer.
// S Phi is a trigonometric polynomial for Q, N and K (c has compact support |L| < m_a + m_b + 1),
// so its P-point inverse DFT is exact once P > 2 (m_a + m_b + 1); flicker and Gauss-Markov
// decay and are aliased by less than their tail beyond P/2.
#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <map>
#include <mutex>
#include <numbers>
#include <tuple>

#include "fftw_planner.hpp"
#include "fit_internal.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau::detail {
namespace {

constexpr double kPi = std::numbers::pi;
/// FFT length per pair: kLagFactor (m_a + m_b) rounded up to a power of two. The compact terms
/// need > 2 (m_a + m_b + 1); 8 leaves the flicker tail (c ~ m_a m_b / L^2, so c^2 ~ L^-4) beyond
/// 4 (m_a + m_b) out of the window and aliased, an estimated ~1 % of sum c^2 (not measured
/// separately; the Monte Carlo test in tests/test_fit.cpp checks variances to 25 %).
constexpr std::int64_t kLagFactor = 8;
constexpr std::int64_t kMinFft = 256;
/// Excess kurtosis of a uniform rounding error (IEEE quantization, Q = step / sqrt(12)):
/// E e^4 / (E e^2)^2 - 3 = 9/5 - 3.
constexpr double kUniformExcessKurtosis = -1.2;
/// Most layouts a process keeps (a bench uses a handful).
constexpr std::size_t kCacheSize = 16;

/// sin(pi r / P) for r in [0, 2P): sin(pi p m / P) is table[(p m) mod 2P], the argument reduced
/// exactly in integers.
std::vector<double> sine_table(std::int64_t big_p) {
  std::vector<double> t(static_cast<std::size_t>(2 * big_p));
  for (std::int64_t r = 0; r < 2 * big_p; ++r) {
    t[static_cast<std::size_t>(r)] = std::sin(kPi * static_cast<double>(r) / static_cast<double>(big_p));
  }
  return t;
}

/// S Phi is real and even, so its inverse DFT of length P is a DCT-I of length P/2 + 1
/// (FFTW REDFT00: Y_L = x_0 + (-1)^L x_{P/2} + 2 sum_{0<p<P/2} x_p cos(2 pi p L / P)).
struct FftBuffers {
  std::int64_t size = 0;
  double* in = nullptr;
  double* out = nullptr;
  fftw_plan plan = nullptr;

  explicit FftBuffers(std::int64_t p) : size(p) {
    in = fftw_alloc_real(static_cast<std::size_t>(p / 2 + 1));
    out = fftw_alloc_real(static_cast<std::size_t>(p / 2 + 1));
    std::lock_guard lock(fftw_planner_mutex());
    plan = fftw_plan_r2r_1d(static_cast<int>(p / 2 + 1), in, out, FFTW_REDFT00, FFTW_ESTIMATE);
  }
  ~FftBuffers() {
    {
      std::lock_guard lock(fftw_planner_mutex());
      fftw_destroy_plan(plan);
    }
    fftw_free(in);
    fftw_free(out);
  }
  FftBuffers(const FftBuffers&) = delete;
  FftBuffers& operator=(const FftBuffers&) = delete;
};

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
                                       double tau0_s, std::optional<double> gm_tau_c_s) {
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
  const bool gm = gm_tau_c_s.has_value();
  basis.terms = kTermCount + (gm ? 1 : 0);
  const std::size_t taus = basis.m.size();
  basis.h.assign(taus * (taus + 1) / 2, Eigen::MatrixXd::Zero(basis.terms, basis.terms));
  const double phi = gm ? std::exp(-tau0_s / *gm_tau_c_s) : 0.0;

  // Stochastic terms (ramp excluded): indices into theta.
  std::vector<int> stochastic{0, 1, 2, 3};
  if (gm) stochastic.push_back(kTermCount);
  constexpr int kRamp = 4;
  const std::size_t ns = stochastic.size();

  // Pairs grouped by FFT length, so each length is planned once.
  std::map<std::int64_t, std::vector<std::pair<std::size_t, std::size_t>>> by_size;
  for (std::size_t b = 0; b < taus; ++b) {
    for (std::size_t a = 0; a <= b; ++a) {
      std::int64_t p = kMinFft;
      while (p < kLagFactor * (basis.m[a] + basis.m[b])) p *= 2;
      by_size[p].emplace_back(a, b);
    }
  }
  std::vector<std::vector<double>> c(ns);
  for (const auto& [big_p, pairs] : by_size) {
    FftBuffers fft(big_p);
    const std::int64_t half = big_p / 2;
    for (auto& v : c) v.assign(static_cast<std::size_t>(half + 1), 0.0);
    const std::vector<double> table = sine_table(big_p);
    // Captured by value: a lambda may not capture a structured binding before C++20's P1091
    // (clang 14 refuses it; the fuzz build uses clang).
    const auto sin_of = [&table, period = big_p](std::int64_t p, std::int64_t mult) {
      return table[static_cast<std::size_t>((p * mult) % (2 * period))];
    };
    std::vector<double> sines(static_cast<std::size_t>(half + 1)), nums(static_cast<std::size_t>(half + 1));
    for (const auto& [a, b] : pairs) {
      const std::int64_t ma = basis.m[a], mb = basis.m[b];
      const double mm = static_cast<double>(ma) * static_cast<double>(mb);
      // Per-frequency factors shared by the terms: num = sin^2(pi f m_a) sin^2(pi f m_b) / (m_a m_b).
      for (std::int64_t p = 1; p <= half; ++p) {
        const double s = sin_of(p, 1);
        const double sa = sin_of(p, ma);
        const double sb = sin_of(p, mb);
        sines[static_cast<std::size_t>(p)] = s;
        nums[static_cast<std::size_t>(p)] = sa * sa * sb * sb / mm;
      }
      for (std::size_t t = 0; t < ns; ++t) {
        // Only K's S Phi is non-zero at f = 0 (its limit is tau0 m_a m_b).
        fft.in[0] = stochastic[t] == 3 ? tau0_s * mm : 0.0;
        for (std::int64_t p = 1; p <= half; ++p) {
          const double s = sines[static_cast<std::size_t>(p)];
          const double num = nums[static_cast<std::size_t>(p)];
          const double s2 = s * s;
          double x = 0;
          switch (stochastic[t]) {
            case 0: x = 16 * num / (tau0_s * tau0_s); break;
            case 1: x = 4 * num / s2 / tau0_s; break;
            case 2: x = 2 * num / (s2 * std::abs(s)); break;
            case 3: x = tau0_s * num / (s2 * s2); break;
            default: {
              const double w = 2 * kPi * static_cast<double>(p) / static_cast<double>(big_p);
              x = (1 - phi * phi) / (1 - 2 * phi * std::cos(w) + phi * phi) * 4 * num / s2;
            }
          }
          fft.in[p] = x;
        }
        fftw_execute(fft.plan);
        const double scale = 1.0 / static_cast<double>(big_p);
        for (std::int64_t i = 0; i <= half; ++i) c[t][static_cast<std::size_t>(i)] = fft.out[i] * scale;
      }
      // Sum over lags L with u = L - (m_a - m_b) inside the alias-free window (-P/2, P/2).
      const std::int64_t na = n_phase_points - 2 * ma, nb = n_phase_points - 2 * mb;
      const std::int64_t shift = ma - mb;
      const std::int64_t l_lo = std::max(-(na - 1), shift - half + 1);
      const std::int64_t l_hi = std::min(nb - 1, shift + half - 1);
      Eigen::MatrixXd cc = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(ns), static_cast<Eigen::Index>(ns));
      Eigen::VectorXd c1 = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(ns));
      std::vector<double> cl(ns);
      for (std::int64_t lag = l_lo; lag <= l_hi; ++lag) {
        const std::int64_t w = std::min(na, nb - lag) - std::max<std::int64_t>(0, -lag);
        if (w <= 0) continue;
        const std::int64_t u = std::abs(lag - shift);  // c is even in u
        for (std::size_t t = 0; t < ns; ++t) cl[t] = c[t][static_cast<std::size_t>(u)];
        const double wd = static_cast<double>(w);
        for (std::size_t t = 0; t < ns; ++t) {
          c1(static_cast<Eigen::Index>(t)) += wd * cl[t];
          for (std::size_t r = 0; r <= t; ++r) cc(static_cast<Eigen::Index>(t), static_cast<Eigen::Index>(r)) += wd * cl[t] * cl[r];
        }
      }
      const double nn = static_cast<double>(na) * static_cast<double>(nb);
      Eigen::MatrixXd& h = basis.h[basis.pair_index(a, b)];
      for (std::size_t t = 0; t < ns; ++t) {
        for (std::size_t r = 0; r <= t; ++r) {
          const double v = cc(static_cast<Eigen::Index>(t), static_cast<Eigen::Index>(r)) / (2 * nn);
          h(stochastic[t], stochastic[r]) = v;
          h(stochastic[r], stochastic[t]) = v;
        }
        // Ramp cross term: (1/(n_a n_b)) tau_a tau_b sum w c, split over (R, t) and (t, R).
        const double ramp = static_cast<double>(ma) * tau0_s * static_cast<double>(mb) * tau0_s *
                            c1(static_cast<Eigen::Index>(t)) / nn / 2;
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
      build_covariance_basis(m, n_phase_points, tau0_s, std::nullopt));
  std::lock_guard lock(mutex);
  if (cache.size() >= kCacheSize) cache.clear();
  cache.emplace(std::move(key), basis);
  return basis;
}

}  // namespace sigmatau::detail

namespace sigmatau {

Eigen::MatrixXd oavar_covariance(const NoiseTerms& terms, std::span<const std::int64_t> m,
                                 std::int64_t n_phase_points, double tau0_s) {
  std::optional<double> tau_c;
  if (terms.gauss_markov) tau_c = terms.gauss_markov->tau_c_s;
  const auto basis = detail::build_covariance_basis(std::vector<std::int64_t>(m.begin(), m.end()),
                                                    n_phase_points, tau0_s, tau_c);
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(basis.terms);
  const auto sq = [](const std::optional<double>& v) { return v ? *v * *v : 0.0; };
  theta(0) = sq(terms.quantization);
  theta(1) = sq(terms.white);
  theta(2) = sq(terms.bias_instability);
  theta(3) = sq(terms.rate_random_walk);
  theta(4) = sq(terms.rate_ramp);
  if (tau_c) theta(detail::kTermCount) = terms.gauss_markov->sigma * terms.gauss_markov->sigma;
  return basis.covariance(theta);
}

}  // namespace sigmatau
