// Reference lag correlations by FFT (the covariance basis's previous path, kept for
// tests/test_fit_covariance.cpp and bench/bench_fit_covariance.cpp only; the library's basis
// uses lib/src/fit_covariance_lagsum.cpp).
//
// Glossary: S Phi_ab(f) the spectral density of c_ab in u = L - (m_a - m_b) (fit_covariance.cpp),
// f = p / P cycles per sample, s = sin(pi f). S Phi is real and even, so its P-point inverse
// DFT is a DCT-I of length P/2 + 1 (FFTW REDFT00). Exact for the trigonometric polynomials of
// Q, N and K once P > 2 (m_a + m_b + 1); B and GM are aliased by their tail beyond P/2.
// Memory ~ 5 P doubles: this is what made the old basis cost 3.2 GiB at m = 2^22.
#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <numbers>

#include "../../lib/src/fftw_planner.hpp"  // the library's one FFTW planner lock
#include "fit_covariance_fft.hpp"

namespace sigmatau::detail {
namespace {

constexpr double kPi = std::numbers::pi;
/// Shortest transform (the old basis's floor).
constexpr std::int64_t kMinFft = 256;

}  // namespace

std::vector<std::vector<double>> fft_lag_correlations(std::int64_t ma, std::int64_t mb,
                                                      double tau0_s, std::optional<double> gm_rate,
                                                      std::int64_t big_p) {
  const std::int64_t half = big_p / 2;
  const int terms = gm_rate ? kLagTerms + 1 : kLagTerms;
  const double phi = gm_rate ? std::exp(-*gm_rate) : 0.0;
  double* in = fftw_alloc_real(static_cast<std::size_t>(half + 1));
  double* out = fftw_alloc_real(static_cast<std::size_t>(half + 1));
  fftw_plan plan;
  {
    std::lock_guard lock(fftw_planner_mutex());
    plan = fftw_plan_r2r_1d(static_cast<int>(half + 1), in, out, FFTW_REDFT00, FFTW_ESTIMATE);
  }
  // sin(pi p m / P) with p m reduced exactly modulo 2P.
  const auto sin_of = [big_p](std::int64_t p, std::int64_t mult) {
    return std::sin(kPi * static_cast<double>((p * mult) % (2 * big_p)) /
                    static_cast<double>(big_p));
  };
  const double mm = static_cast<double>(ma) * static_cast<double>(mb);
  std::vector<std::vector<double>> c(static_cast<std::size_t>(terms));
  for (int t = 0; t < terms; ++t) {
    // Only K's S Phi is non-zero at f = 0 (its limit is tau0 m_a m_b).
    in[0] = t == 3 ? tau0_s * mm : 0.0;
    for (std::int64_t p = 1; p <= half; ++p) {
      const double s = sin_of(p, 1), sa = sin_of(p, ma), sb = sin_of(p, mb);
      const double num = sa * sa * sb * sb / mm, s2 = s * s;
      double x = 0;
      switch (t) {
        case 0:
          x = 16 * num / (tau0_s * tau0_s);
          break;
        case 1:
          x = 4 * num / s2 / tau0_s;
          break;
        case 2:
          x = 2 * num / (s2 * std::abs(s));
          break;
        case 3:
          x = tau0_s * num / (s2 * s2);
          break;
        default: {
          const double w = 2 * kPi * static_cast<double>(p) / static_cast<double>(big_p);
          x = (1 - phi * phi) / (1 - 2 * phi * std::cos(w) + phi * phi) * 4 * num / s2;
        }
      }
      in[p] = x;
    }
    fftw_execute(plan);
    auto& ct = c[static_cast<std::size_t>(t)];
    ct.resize(static_cast<std::size_t>(half + 1));
    for (std::int64_t i = 0; i <= half; ++i)
      ct[static_cast<std::size_t>(i)] = out[i] / static_cast<double>(big_p);
  }
  {
    std::lock_guard lock(fftw_planner_mutex());
    fftw_destroy_plan(plan);
  }
  fftw_free(in);
  fftw_free(out);
  return c;
}

LagSums covariance_lag_sums_fft(std::int64_t ma, std::int64_t mb, std::int64_t n_phase_points,
                                double tau0_s, std::optional<double> gm_rate,
                                std::int64_t lag_factor) {
  std::int64_t big_p = kMinFft;
  while (big_p < lag_factor * (ma + mb)) big_p *= 2;
  const auto c = fft_lag_correlations(ma, mb, tau0_s, gm_rate, big_p);
  const int terms = static_cast<int>(c.size());
  const std::int64_t half = big_p / 2;
  // Sum over lags L with u = L - (m_a - m_b) inside the alias-free window (-P/2, P/2).
  const std::int64_t na = n_phase_points - 2 * ma, nb = n_phase_points - 2 * mb;
  const std::int64_t shift = ma - mb;
  const std::int64_t l_lo = std::max(-(na - 1), shift - half + 1);
  const std::int64_t l_hi = std::min(nb - 1, shift + half - 1);
  LagSums sums{Eigen::MatrixXd::Zero(terms, terms), Eigen::VectorXd::Zero(terms)};
  for (std::int64_t lag = l_lo; lag <= l_hi; ++lag) {
    const std::int64_t w = std::min(na, nb - lag) - std::max<std::int64_t>(0, -lag);
    if (w <= 0) continue;
    const auto u = static_cast<std::size_t>(std::abs(lag - shift));  // c is even in u
    const double wd = static_cast<double>(w);
    for (int t = 0; t < terms; ++t) {
      const double ct = c[static_cast<std::size_t>(t)][u];
      sums.c1(t) += wd * ct;
      for (int r = 0; r <= t; ++r) sums.cc(t, r) += wd * ct * c[static_cast<std::size_t>(r)][u];
    }
  }
  for (int t = 0; t < terms; ++t) {
    for (int r = 0; r < t; ++r) sums.cc(r, t) = sums.cc(t, r);
  }
  return sums;
}

}  // namespace sigmatau::detail
