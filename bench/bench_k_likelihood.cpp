// Experiment (issue 5, K's median error): how much more does the log itself say about K than its
// octave OADEV curve? For the MEMS gyro profile of bench_fit_accuracy, each simulated channel
// is fitted three ways: the joint fit (model selected), the joint fit told the true terms, and
// the exact Gaussian likelihood of the increments of the log's block means (blocks of
// BLOCK_S seconds), maximised over (N^2, B^2, K^2).
//
// The increments e_j = y_j - y_{j-1} of block means y_j (block length T) are a stationary
// series whatever K: e_j = (phi_{j+1} - 2 phi_j + phi_{j-1}) / T, phi the integrated rate, and
//   Cov(e_j, e_{j+h}) = T^-2 sum_{a,b=0..2} c_a c_b G(|h + b - a| T),  c = (1, -2, 1),
// with the generalised covariance of the phase G(tau) = -N^2 |tau| / 2 + B^2 tau^2 ln|tau| /
// (2 pi) + K^2 |tau|^3 / 12 (each term checked against its AVAR: 2 tau^2 AVAR(tau) = -8 G(tau) +
// 2 G(2 tau), giving N^2 / tau, (2 ln 2 / pi) B^2 and K^2 tau / 3). The covariance is Toeplitz:
// Durbin-Levinson gives ln det and the quadratic form in O(n^2). Maximised by Nelder-Mead in
// the logarithms of the three parameters, started at the joint fit's values; the interval of K
// from the curvature of the log-likelihood in ln K^2 (observed information).
// Before the seeds, the Cramer-Rao bound of K at the truth: the Fisher information of
// (N^2, B^2, K^2) in the same increments, with all three estimated, N known, N and B known.
// Result (bench/results_k_likelihood.md): on 300 MEMS channels the likelihood's K is no better
// than the curve fit's (16.7 % against 14.6 % median error): the curve is not what limits K.
// The bound (1 s blocks, N known) is sd(K-hat)/K = 21.9 %, a median |error| of 14.8 % for a
// normal unbiased estimator; the told fit's spread is 22.4-22.9 % (seeds 1-200 / 1-1000).
// Usage: bench_k_likelihood OUT_PREFIX [SEEDS=100] [FIRST_SEED=1001] [BLOCK_S=4] [MODEL=the
// MEMS gyro's "N=0.15 deg/sqrt(h), B=3 deg/h, K=15 deg/h/sqrt(h)"]; SEEDS=0: the bound only.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <fstream>
#include <iostream>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bench_stats.hpp"
#include "sigmatau/allan_curve.hpp"
#include "sigmatau/fit.hpp"
#include "sigmatau/noise_model.hpp"
#include "sigmatau/simulate.hpp"
#include "sigmatau/taus.hpp"

namespace {

using sigmatau::bench::median;

using namespace sigmatau;
using Clock = std::chrono::steady_clock;

/// Generalised covariance of the phase for theta = (N^2, B^2, K^2) at lag tau [s].
double generalised_covariance(const std::array<double, 3>& theta, double tau) {
  const double t = std::abs(tau);
  if (t == 0) return 0;
  return -theta[0] * t / 2 + theta[1] * t * t * std::log(t) / (2 * std::numbers::pi) +
         theta[2] * t * t * t / 12;
}

/// Autocovariance of the block-mean increments at lags 0..n-1.
std::vector<double> increment_autocovariance(const std::array<double, 3>& theta, double block_s,
                                             std::size_t n) {
  constexpr double c[3] = {1, -2, 1};
  std::vector<double> gamma(n);
  for (std::size_t h = 0; h < n; ++h) {
    double sum = 0;
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        sum += c[a] * c[b] *
               generalised_covariance(theta, (static_cast<double>(h) + b - a) * block_s);
      }
    }
    gamma[h] = sum / (block_s * block_s);
  }
  return gamma;
}

/// -2 ln L (up to a constant) of x under a zero-mean stationary Gaussian with autocovariance
/// gamma, by Durbin-Levinson; +inf when gamma is not positive definite.
double minus_two_log_likelihood(const std::vector<double>& gamma, const std::vector<double>& x) {
  const std::size_t n = x.size();
  std::vector<double> phi(n, 0.0), previous(n, 0.0);
  double v = gamma[0];
  if (!(v > 0)) return INFINITY;
  double deviance = std::log(v) + x[0] * x[0] / v;
  for (std::size_t t = 1; t < n; ++t) {
    // Reflection coefficient for order t.
    double acc = gamma[t];
    for (std::size_t j = 1; j < t; ++j) acc -= previous[j] * gamma[t - j];
    const double kappa = acc / v;
    phi[t] = kappa;
    for (std::size_t j = 1; j < t; ++j) phi[j] = previous[j] - kappa * previous[t - j];
    v *= 1 - kappa * kappa;
    if (!(v > 0)) return INFINITY;
    double prediction = 0;
    for (std::size_t j = 1; j <= t; ++j) prediction += phi[j] * x[t - j];
    const double innovation = x[t] - prediction;
    deviance += std::log(v) + innovation * innovation / v;
    std::copy(phi.begin(), phi.begin() + static_cast<std::ptrdiff_t>(t) + 1, previous.begin());
  }
  return deviance;
}

/// Nelder-Mead minimum of f over R^3 from x0 with initial step `step`.
template <class F>
Eigen::Vector3d nelder_mead(F f, Eigen::Vector3d x0, double step, int evaluations) {
  std::array<Eigen::Vector3d, 4> p;
  std::array<double, 4> y{};
  p[0] = x0;
  for (int i = 1; i < 4; ++i) {
    p[i] = x0;
    p[i](i - 1) += step;
  }
  for (int i = 0; i < 4; ++i) y[i] = f(p[i]);
  for (int used = 4; used < evaluations;) {
    std::array<int, 4> order{0, 1, 2, 3};
    std::sort(order.begin(), order.end(), [&](int a, int b) { return y[a] < y[b]; });
    const int best = order[0], worst = order[3], second = order[2];
    if (std::abs(y[worst] - y[best]) < 1e-7) break;
    Eigen::Vector3d centre = (p[order[0]] + p[order[1]] + p[order[2]]) / 3;
    const Eigen::Vector3d reflected = centre + (centre - p[worst]);
    const double yr = f(reflected);
    ++used;
    if (yr < y[best]) {
      const Eigen::Vector3d expanded = centre + 2 * (centre - p[worst]);
      const double ye = f(expanded);
      ++used;
      if (ye < yr) { p[worst] = expanded; y[worst] = ye; } else { p[worst] = reflected; y[worst] = yr; }
    } else if (yr < y[second]) {
      p[worst] = reflected;
      y[worst] = yr;
    } else {
      const Eigen::Vector3d contracted = centre + 0.5 * (p[worst] - centre);
      const double yc = f(contracted);
      ++used;
      if (yc < y[worst]) {
        p[worst] = contracted;
        y[worst] = yc;
      } else {
        for (int i = 0; i < 4; ++i) {
          if (i == best) continue;
          p[i] = p[best] + 0.5 * (p[i] - p[best]);
          y[i] = f(p[i]);
          ++used;
        }
      }
    }
  }
  int best = 0;
  for (int i = 1; i < 4; ++i) if (y[i] < y[best]) best = i;
  return p[best];
}

/// Fisher information of (N^2, B^2, K^2) in n block-mean increments at theta:
/// I_ij = tr(S^-1 S_i S^-1 S_j) / 2 with S = sum_i theta_i S_i (each S_i Toeplitz, the
/// covariance of a unit of term i alone). Dense: O(n^3), seconds at n ~ 2000.
Eigen::Matrix3d fisher_information(const std::array<double, 3>& theta, double block_s,
                                   std::size_t n) {
  std::array<Eigen::MatrixXd, 3> unit;
  Eigen::MatrixXd total = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  for (int i = 0; i < 3; ++i) {
    std::array<double, 3> e{};
    e[static_cast<std::size_t>(i)] = 1;
    const std::vector<double> gamma = increment_autocovariance(e, block_s, n);
    unit[static_cast<std::size_t>(i)].resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
    for (std::size_t r = 0; r < n; ++r) {
      for (std::size_t c = 0; c < n; ++c) {
        unit[static_cast<std::size_t>(i)](static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) =
            gamma[r > c ? r - c : c - r];
      }
    }
    total += theta[static_cast<std::size_t>(i)] * unit[static_cast<std::size_t>(i)];
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(total);
  std::array<Eigen::MatrixXd, 3> solved;
  for (std::size_t i = 0; i < 3; ++i) solved[i] = llt.solve(unit[i]);
  Eigen::Matrix3d info;
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = 0; j <= i; ++j) {
      // tr(A B) = sum of A .* B^T.
      info(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) =
          info(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(i)) =
              0.5 * solved[i].cwiseProduct(solved[j].transpose()).sum();
    }
  }
  return info;
}

/// Cramer-Rao standard deviation of K-hat / K (delta method from K^2) with the parameters in
/// `unknown` estimated and the others known.
double k_relative_bound(const Eigen::Matrix3d& info, const std::array<double, 3>& theta,
                        const std::vector<int>& unknown) {
  const auto m = static_cast<Eigen::Index>(unknown.size());
  Eigen::MatrixXd sub(m, m);
  for (Eigen::Index i = 0; i < m; ++i) {
    for (Eigen::Index j = 0; j < m; ++j) sub(i, j) = info(unknown[static_cast<std::size_t>(i)], unknown[static_cast<std::size_t>(j)]);
  }
  const double var_k2 = sub.inverse()(m - 1, m - 1);  // K^2 is listed last
  return std::sqrt(var_k2) / (2 * theta[2]);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: bench_k_likelihood OUT_PREFIX [SEEDS=100] [FIRST_SEED=1001] [BLOCK_S=4]\n";
    return 2;
  }
  const std::string prefix = argv[1];
  const int seeds = argc > 2 ? std::stoi(argv[2]) : 100;
  const int first_seed = argc > 3 ? std::stoi(argv[3]) : 1001;
  const double block_s = argc > 4 ? std::stod(argv[4]) : 4;
  const double rate_hz = 100;
  const std::string model_text =
      argc > 5 ? argv[5] : "N=0.15 deg/sqrt(h), B=3 deg/h, K=15 deg/h/sqrt(h)";
  const NoiseTerms truth = parse_noise_terms(model_text, Sensor::gyro);
  std::vector<NoiseTerm> true_terms;
  for (const NoiseTerm t : kFitTerms) {
    if (has_term(truth, t)) true_terms.push_back(t);
  }
  const double k_true = *truth.rate_random_walk;
  SimulationConfig config;
  config.rate_hz = rate_hz;
  config.samples = static_cast<std::int64_t>(2 * 3600 * rate_hz);
  ErrorModel model;
  model.noise = {truth, truth, truth};
  config.gyro = model;
  const auto block = static_cast<std::size_t>(std::llround(block_s * rate_hz));

  // The Cramer-Rao bound at the truth, for this log length and block (no simulation).
  const std::array<double, 3> theta_true{*truth.white * *truth.white,
                                         *truth.bias_instability * *truth.bias_instability,
                                         k_true * k_true};
  const auto bound_start = Clock::now();
  const std::size_t increments = static_cast<std::size_t>(config.samples) / block - 1;
  const Eigen::Matrix3d info = fisher_information(theta_true, block_s, increments);
  const double bound_all = k_relative_bound(info, theta_true, {0, 1, 2});
  const double bound_n_known = k_relative_bound(info, theta_true, {1, 2});
  const double bound_nb_known = k_relative_bound(info, theta_true, {2});
  std::cerr << "Cramer-Rao sd(K)/K with " << increments << " increments of " << block_s
            << " s block means: N, B, K unknown " << 100 * bound_all << " %, N known "
            << 100 * bound_n_known << " %, N and B known " << 100 * bound_nb_known << " % ("
            << std::chrono::duration<double>(Clock::now() - bound_start).count() << " s)\n";

  std::vector<double> err_selected, err_told, err_mle;
  int covered_mle = 0, covered_told = 0, runs = 0;
  double mle_seconds = 0;
  std::ofstream channels(prefix + ".channels.csv");
  channels.precision(9);
  channels << "seed,axis,k_selected,k_told,k_mle,k_mle_low,k_mle_high\n";
  for (int seed = first_seed; seed < first_seed + seeds; ++seed) {
    config.seed = static_cast<std::uint64_t>(seed);
    Simulator sim(config);
    std::vector<std::vector<double>> axes(3);
    std::vector<double> rows(static_cast<std::size_t>(65536 * 3));
    for (std::int64_t n; (n = sim.next(rows, 65536)) > 0;) {
      for (std::int64_t r = 0; r < n; ++r) {
        for (int a = 0; a < 3; ++a) axes[a].push_back(rows[static_cast<std::size_t>(r * 3 + a)]);
      }
    }
    for (int a = 0; a < 3; ++a) {
      const auto series = PhaseSeries::from_rate(axes[a], 1 / rate_hz);
      const AllanCurve curve = compute_allan_curve(series, Statistic::oadev, TauSpec{}, 0.683);
      const CurveSource source{1 / rate_hz, series.size(), 0};
      FitOptions options;
      const NoiseFit selected = fit_noise(curve, source, options);
      options.terms = true_terms;
      const NoiseFit told = fit_noise(curve, source, options);
      const auto& ks = selected.joint->parameter(NoiseTerm::rate_random_walk);
      const auto& kt = told.joint->parameter(NoiseTerm::rate_random_walk);

      const auto t0 = Clock::now();
      std::vector<double> means;
      for (std::size_t i = 0; i + block <= axes[a].size(); i += block) {
        double s = 0;
        for (std::size_t j = i; j < i + block; ++j) s += axes[a][j];
        means.push_back(s / static_cast<double>(block));
      }
      std::vector<double> e(means.size() - 1);
      for (std::size_t j = 1; j < means.size(); ++j) e[j - 1] = means[j] - means[j - 1];
      const auto deviance = [&](const Eigen::Vector3d& psi) {
        const std::array<double, 3> theta{std::exp(psi(0)), std::exp(psi(1)), std::exp(psi(2))};
        return minus_two_log_likelihood(increment_autocovariance(theta, block_s, e.size()), e);
      };
      const auto start = [&](NoiseTerm t, double fallback) {
        const double v = told.joint->parameter(t).value;
        return std::log(std::max(v, fallback) * std::max(v, fallback));
      };
      Eigen::Vector3d psi0(start(NoiseTerm::white, 1e-5), start(NoiseTerm::bias_instability, 1e-6),
                           start(NoiseTerm::rate_random_walk, 1e-7));
      Eigen::Vector3d psi = nelder_mead(deviance, psi0, 0.5, 400);
      psi = nelder_mead(deviance, psi, 0.1, 200);  // restart: Nelder-Mead can stall
      // Observed information in psi (central differences), variance of psi_K from its inverse.
      const double h = 0.05;
      Eigen::Matrix3d hess;
      const double f0 = deviance(psi);
      for (int i = 0; i < 3; ++i) {
        for (int j = i; j < 3; ++j) {
          Eigen::Vector3d pp = psi, pm = psi, mp = psi, mm = psi;
          pp(i) += h; pp(j) += h; pm(i) += h; pm(j) -= h; mp(i) -= h; mp(j) += h; mm(i) -= h; mm(j) -= h;
          hess(i, j) = hess(j, i) =
              i == j ? (deviance(pp) - 2 * f0 + deviance(mm)) / (4 * h * h)
                     : (deviance(pp) - deviance(pm) - deviance(mp) + deviance(mm)) / (4 * h * h);
        }
      }
      // deviance = -2 ln L: information = hess / 2.
      const Eigen::Matrix3d cov = (hess / 2).inverse();
      mle_seconds += std::chrono::duration<double>(Clock::now() - t0).count();
      const double k_mle = std::exp(psi(2) / 2);
      const double sd = std::sqrt(std::max(cov(2, 2), 0.0)) / 2;  // of ln K
      const double low = k_mle * std::exp(-1.96 * sd), high = k_mle * std::exp(1.96 * sd);
      ++runs;
      err_selected.push_back(ks.in_model ? std::abs(ks.value / k_true - 1) : 1.0);
      err_told.push_back(std::abs(kt.value / k_true - 1));
      err_mle.push_back(std::abs(k_mle / k_true - 1));
      covered_mle += low <= k_true && k_true <= high;
      covered_told += kt.ci_low <= k_true && k_true <= kt.ci_high;
      channels << seed << ',' << a << ',' << (ks.in_model ? ks.value : 0.0) << ',' << kt.value << ','
               << k_mle << ',' << low << ',' << high << '\n';
    }
    if ((seed - first_seed + 1) % 10 == 0) {
      std::cerr << seed << ": K median |error| selected " << 100 * median(err_selected) << " %, told "
                << 100 * median(err_told) << " %, likelihood " << 100 * median(err_mle) << " %\n";
    }
  }
  std::ofstream md(prefix + ".md");
  md << "Cramer-Rao bound of K at the truth, " << increments << " increments of " << block_s
     << " s block means: sd(K-hat)/K = " << 100 * bound_all << " % with N, B, K estimated, "
     << 100 * bound_n_known << " % with N known, " << 100 * bound_nb_known
     << " % with N and B known; a normal estimator at that sd has median |error| "
     << 100 * 0.6745 * bound_all << " / " << 100 * 0.6745 * bound_n_known << " / "
     << 100 * 0.6745 * bound_nb_known << " %\n\n";
  if (runs == 0) {
    md.close();
    std::ifstream in(prefix + ".md");
    std::cout << in.rdbuf();
    return 0;
  }
  md << "MEMS gyro (N=0.15 deg/sqrt(h), B=3 deg/h, K=15 deg/h/sqrt(h), 100 Hz, 2 h), " << runs
     << " channels (seeds " << first_seed << "-" << first_seed + seeds - 1 << " x 3 axes), K's median |relative error| "
     << "(95 % interval coverage):\n\n"
     << "- joint fit, model selected: " << 100 * median(err_selected) << " %\n"
     << "- joint fit, true terms: " << 100 * median(err_told) << " % (" << 100.0 * covered_told / runs << " %)\n"
     << "- exact likelihood of " << block_s << " s block-mean increments: " << 100 * median(err_mle)
     << " % (" << 100.0 * covered_mle / runs << " %), " << 1e3 * mle_seconds / runs << " ms/channel\n";
  md.close();
  std::ifstream in(prefix + ".md");
  std::cout << in.rdbuf();
  return 0;
}
