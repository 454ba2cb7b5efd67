// Information limit (issue 24): how often can any model selection tell the gm_sum profile of
// bench/fit_added_terms_sim.py (N = 0.15 deg/sqrt(h), GM 20 deg/h @ 10 s, GM 10 deg/h @ 200 s,
// 100 Hz) from the nearest model with one Gauss-Markov term less, given its octave OADEV curve?
//
// The OAVAR estimates at the octave factors are taken as Gaussian with mean mu_1 (the truth's
// exact sampled AVAR) and the truth's covariance Sigma (oavar_covariance, the fit's own). The
// nearest one-GM model mu_0 is the one that minimises the Mahalanobis distance
//   d^2 = (mu_1 - mu_0)^T Sigma^-1 (mu_1 - mu_0)
// over every subset of the IEEE terms Q, N, B, K, R plus one GM (its sigma^2 and the IEEE
// terms' squares non-negative, by enumerating subsets; its T_c on a grid of 64 per octave,
// then golden section). With all parameters known, the two curves are two simple hypotheses,
// and the best test between them (Neyman-Pearson, a linear statistic of Gaussian data) picks
// each one correctly with probability at most Phi(d / 2) when both are to be picked equally
// often (equal error rates): no selector can find the second GM in more runs than that without
// also adding a GM to the one-GM curve as often. Unknown parameters only lower it.
// Beside it, the power of a likelihood-ratio selection that adds a term when the deviance falls
// by more than a threshold t: P(chi2'(k, d^2) > t), k = 2 (the GM's sigma^2 and T_c), for t =
// the joint fit's cost of an added term (3 ln n, n fitted points: fit_added_terms.cpp) and the
// 5 % test's chi2(2) quantile.
// The alternatives that do not nest in the truth (those with B or K) make that power an
// approximation; the Phi columns are exact for the Gaussian reading, which
// bench/gm_sum_limit_check.py tests on simulated curves.
// Usage: [GM_SUM_LIMIT_DUMP=FILE] bench_gm_sum_limit [DURATIONS_S...] (default 7200 14400 28800
// 57600); writes a markdown table to stdout (bench/results_fit_added_terms.md quotes it) and,
// with GM_SUM_LIMIT_DUMP, the first log's N + one-GM model as JSON for the check.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/non_central_chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>

#include "sigmatau/fit.hpp"
#include "sigmatau/noise_model.hpp"
#include "sigmatau/taus.hpp"

namespace {

using namespace sigmatau;

constexpr double kTau0 = 0.01;  // 100 Hz
constexpr double kDegPerHour = std::numbers::pi / 180 / 3600;  // rad/s
constexpr double kDegPerSqrtHour = std::numbers::pi / 180 / 60;  // rad/sqrt(s)

NoiseTerms gm_sum_truth() {
  NoiseTerms t;
  t.white = 0.15 * kDegPerSqrtHour;
  t.gauss_markov = {GaussMarkov{20 * kDegPerHour, 10.0}, GaussMarkov{10 * kDegPerHour, 200.0}};
  return t;
}

/// Exact AVAR of one unit term at each factor (a GM of correlation time tau_c_s).
Eigen::VectorXd unit_column(NoiseTerm term, const std::vector<std::int64_t>& ms, double tau_c_s) {
  NoiseTerms ones;
  ones.quantization = ones.white = ones.bias_instability = ones.rate_random_walk = ones.rate_ramp = 1;
  ones.gauss_markov = {GaussMarkov{1, tau_c_s}};
  Eigen::VectorXd c(static_cast<Eigen::Index>(ms.size()));
  for (std::size_t j = 0; j < ms.size(); ++j) {
    c(static_cast<Eigen::Index>(j)) = sampled_avar(ones, term, ms[j], Sampling{kTau0, 0, false});
  }
  return c;
}

struct Nearest {
  double d2 = std::numeric_limits<double>::infinity();
  double tau_c_s = 0;
  unsigned subset = 0;
  Eigen::VectorXd theta;
};

/// The nearest one-GM model at a fixed T_c: the smallest whitened residual over the IEEE subsets
/// whose least-squares coefficients (with the GM's) are all >= 0.
Nearest nearest_at(const Eigen::MatrixXd& l_inv_ieee, const Eigen::MatrixXd& l_inv,
                   const Eigen::VectorXd& w_mu, const std::vector<std::int64_t>& ms, double tau_c_s,
                   unsigned only = 32) {
  const Eigen::VectorXd gm = l_inv * unit_column(NoiseTerm::gauss_markov, ms, tau_c_s);
  Nearest best;
  for (unsigned s = 0; s < 32; ++s) {
    if (only < 32 && s != only) continue;
    std::vector<int> cols;
    for (int k = 0; k < 5; ++k) {
      if (s & (1u << k)) cols.push_back(k);
    }
    Eigen::MatrixXd a(w_mu.size(), static_cast<Eigen::Index>(cols.size()) + 1);
    for (std::size_t c = 0; c < cols.size(); ++c) a.col(static_cast<Eigen::Index>(c)) = l_inv_ieee.col(cols[c]);
    a.col(a.cols() - 1) = gm;
    const Eigen::VectorXd x = a.colPivHouseholderQr().solve(w_mu);
    if ((x.array() < 0).any()) continue;
    const double d2 = (w_mu - a * x).squaredNorm();
    if (d2 < best.d2) best = {d2, tau_c_s, s, x};
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<double> durations;
  const char* dump = std::getenv("GM_SUM_LIMIT_DUMP");  // a JSON file for the Monte-Carlo check
  for (int i = 1; i < argc; ++i) durations.push_back(std::atof(argv[i]));
  if (durations.empty()) durations = {7200, 14400, 28800, 57600};
  const NoiseTerms truth = gm_sum_truth();
  const boost::math::normal normal;
  std::printf("| log | octave points n | one-GM model: IEEE terms | its GM | d^2 | Phi(d/2): equal errors | "
              "Phi(d - z95): 5 %% false additions | criterion's cost t: P(LR > t) | P(LR > chi2(2) 95 %%) |\n"
              "|---|---|---|---|---|---|---|---|---|\n");
  for (const double duration : durations) {
    const auto samples = static_cast<std::int64_t>(std::llround(duration / kTau0));
    const std::int64_t n_phase = samples + 1;
    const std::vector<std::int64_t> ms = averaging_factors(TauSpec{}, Statistic::oadev, n_phase, kTau0);
    const auto n = static_cast<Eigen::Index>(ms.size());
    Eigen::VectorXd mu(n);
    for (Eigen::Index j = 0; j < n; ++j) mu(j) = sampled_avar(truth, ms[static_cast<std::size_t>(j)], Sampling{kTau0, 0, false});
    const Eigen::MatrixXd sigma = oavar_covariance(truth, ms, n_phase, kTau0);
    const Eigen::LLT<Eigen::MatrixXd> llt(sigma);
    if (llt.info() != Eigen::Success) {
      std::fprintf(stderr, "covariance not positive definite at %g s\n", duration);
      return 1;
    }
    const Eigen::MatrixXd l_inv = llt.matrixL().solve(Eigen::MatrixXd::Identity(n, n));
    Eigen::MatrixXd ieee(n, 5);
    const NoiseTerm terms[5] = {NoiseTerm::quantization, NoiseTerm::white, NoiseTerm::bias_instability,
                                NoiseTerm::rate_random_walk, NoiseTerm::rate_ramp};
    for (int k = 0; k < 5; ++k) ieee.col(k) = unit_column(terms[k], ms, 0);
    const Eigen::MatrixXd l_inv_ieee = l_inv * ieee;
    const Eigen::VectorXd w_mu = l_inv * mu;
    // Grid of 64 per octave over 2 tau0 .. the log's length, then golden section around the best.
    const auto search = [&](unsigned only) {
      Nearest best;
      for (double tc = 2 * kTau0; tc <= duration; tc *= std::exp2(1.0 / 64)) {
        const Nearest at = nearest_at(l_inv_ieee, l_inv, w_mu, ms, tc, only);
        if (at.d2 < best.d2) best = at;
      }
      double lo = std::log(best.tau_c_s) - std::log(2.0) / 64, hi = std::log(best.tau_c_s) + std::log(2.0) / 64;
      const double g = (std::sqrt(5.0) - 1) / 2;
      for (int it = 0; it < 60; ++it) {
        const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
        const Nearest na = nearest_at(l_inv_ieee, l_inv, w_mu, ms, std::exp(a), only);
        const Nearest nb = nearest_at(l_inv_ieee, l_inv, w_mu, ms, std::exp(b), only);
        if (na.d2 < best.d2) best = na;
        if (nb.d2 < best.d2) best = nb;
        (na.d2 < nb.d2 ? hi : lo) = (na.d2 < nb.d2 ? b : a);
      }
      return best;
    };
    // Every subset, then the ones the fit picks on these curves (N, N K, N B) for their cost.
    for (const unsigned only : {32u, 2u, 10u, 6u}) {
      const Nearest best = search(only);
      if (!std::isfinite(best.d2)) continue;
      if (dump && only == 2u && duration == durations.front()) {
        // For the Monte-Carlo check (bench/gm_sum_limit_check.py): the factors, both means and
        // Sigma, and the alternative's N [rad/sqrt(s)], sigma [rad/s] and T_c [s].
        std::FILE* f = std::fopen(dump, "w");
        if (!f) {
          std::perror(dump);
          return 1;
        }
        const Eigen::VectorXd mu0 = ieee.col(1) * best.theta(0) +
                                    unit_column(NoiseTerm::gauss_markov, ms, best.tau_c_s) * best.theta(1);
        std::fprintf(f, "{\"n_samples\": %lld, \"alt_white\": %.17g, \"alt_gm_sigma\": %.17g, \"alt_gm_tau_c_s\": %.17g,\n",
                     static_cast<long long>(samples), std::sqrt(best.theta(0)), std::sqrt(best.theta(1)), best.tau_c_s);
        const auto list = [&](const char* name, const Eigen::VectorXd& v) {
          std::fprintf(f, "\"%s\": [", name);
          for (Eigen::Index j = 0; j < v.size(); ++j) std::fprintf(f, "%s%.17g", j ? ", " : "", v(j));
          std::fprintf(f, "],\n");
        };
        Eigen::VectorXd mv(n);
        for (Eigen::Index j = 0; j < n; ++j) mv(j) = static_cast<double>(ms[static_cast<std::size_t>(j)]);
        list("m", mv);
        list("mu1", mu);
        list("mu0", mu0);
        std::fprintf(f, "\"sigma\": [");
        for (Eigen::Index r = 0; r < n; ++r) {
          std::fprintf(f, "%s[", r ? ", " : "");
          for (Eigen::Index c = 0; c < n; ++c) std::fprintf(f, "%s%.17g", c ? ", " : "", sigma(r, c));
          std::fprintf(f, "]");
        }
        std::fprintf(f, "]}\n");
        std::fclose(f);
      }
      const double d = std::sqrt(best.d2);
      const double equal_error = boost::math::cdf(normal, d / 2);
      const double at_5 = boost::math::cdf(normal, d - boost::math::quantile(normal, 0.95));
      const boost::math::non_central_chi_squared lr(2, best.d2);
      // The criterion's cost of the truth (N + 2 GM) over this alternative: ln n per IEEE term,
      // 3 ln n per added term (fit_added_terms.cpp).
      const int alt_params = std::popcount(best.subset) + 3;
      const double cost = (7 - alt_params) * std::log(static_cast<double>(n));
      // Not nested in cost when the alternative pays as much as the truth (4 IEEE terms + a GM).
      char cost_text[48] = "- (same cost as the truth)";
      if (cost > 0) {
        std::snprintf(cost_text, sizeof cost_text, "%.2f: %.1f %%", cost,
                      100 * boost::math::cdf(boost::math::complement(lr, cost)));
      }
      const double t95 = boost::math::quantile(boost::math::chi_squared(2), 0.95);
      const double power_95 = boost::math::cdf(boost::math::complement(lr, t95));
      std::string described;
      const char* names[5] = {"Q", "N", "B", "K", "R"};
      for (int k = 0; k < 5; ++k) {
        if (best.subset & (1u << k)) described += std::string(names[k]) + " ";
      }
      const double gm_sigma = std::sqrt(best.theta(best.theta.size() - 1)) / kDegPerHour;
      std::printf("| %.0f h | %lld | %s%s | GM %.1f deg/h @ %.1f s | %.2f | %.1f %% | %.1f %% | %s | %.1f %% |\n",
                  duration / 3600, static_cast<long long>(n), described.c_str(), only == 32 ? "(nearest of all)" : "",
                  gm_sigma, best.tau_c_s, best.d2, 100 * equal_error, 100 * at_5, cost_text, 100 * power_95);
    }
  }
  return 0;
}
