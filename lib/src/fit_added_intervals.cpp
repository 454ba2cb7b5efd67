// Intervals of a joint fit with added terms.
//
// Glossary (as fit_joint.cpp and fit_covariance.cpp): v the measured OAVAR at m_j, A the design,
// theta the squared parameters, mu = A theta; T_g a Gauss-Markov term's correlation time, f the
// sinusoid's frequency; W = Sigma_w^-1 the fit's last weights; n_m = N_phase - 2 m the second
// differences d^m_k at m; S(nu) the noise's two-sided per-sample PSD at nu cycles per sample.
//
// 1. T_c and f float. The fit estimates each T_g and f besides theta, and an error in them moves
//    the magnitudes: a GM seen only on its falling side fixes sigma^2 T_g, not sigma^2 (median
//    T_c error 12 % on the bench's GM sum). The covariance is the GLS delta method on the
//    extended Jacobian J = [A_kept, theta_g dA_g/d ln T_g, theta_s dA_s/d ln f]:
//      Cov = B J^T W Sigma W J B,  B = (J^T W J)^-1,
//    with Sigma the estimates' covariance (the weights' own, plus the sinusoid's term below).
//    With Sigma = Sigma_w it is B; the fixed-T_c interval was the theta block of B without the
//    extra columns, so this one is never narrower (a Schur complement).
// 2. A sinusoid's scatter. With y = s + w (s = A cos(2 pi f tau0 k + phi), w the noise) the
//    OAVAR at m is sum_k (ds_k + dw_k)^2 / (2 n_m); besides the noise's own term it holds the
//    cross term C_m = sum_k ds_k dw_k / n_m, of mean 0 and, averaged over the phase phi, with
//      Cov(C_a, C_b) = (A^2 / 2) / (n_a n_b) sum_L w_ab(L) Re[e^{-i 2 pi nu L} conj(G_a) G_b]
//      c_ab(L),
//    nu = f tau0, G_m the transfer function of the d^m kernel, c_ab the noise's lag covariance
//    of the d's and w_ab(L) the pairs at lag L. For sums over many periods and lags short next
//    to n (w_ab ~ min(n_a, n_b)), sum_L c_ab(L) e^{-i 2 pi nu L} = S(nu) G_a conj(G_b), so
//      Cov(C_a, C_b) = (A^2 / 2) S(nu) |G_a|^2 |G_b|^2 / max(n_a, n_b)
//                    = 8 A^2 a_a a_b S(nu) / max(n_a, n_b),
//    a_m = |G_m|^2 / 4 the sinusoid's AVAR per unit A^2. On the bench's sinusoid profile (A = 30
//    deg/h at 0.5 Hz on N = 0.15 deg/sqrt(h), 2 h) it is ~1 % of the sinusoid's AVAR at its peak,
//    ~3.5x the noise's own sd there: the fit took the sinusoid's AVAR as exact. The phase term
//    (sum_k ds_k^2 / n about its phase average) is O(1 / n^2) and left out.
#include "fit_added_intervals.hpp"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

#include "fit_added_terms.hpp"
#include "golden_section.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau::detail {
namespace {

/// Relative step in ln T_c or ln f of the central differences: the columns are exact closed
/// forms, smooth in T_c and f; 1e-4 keeps the truncation error (~1e-8) and the rounding
/// (~1e-16 / 1e-4) both far below the 1e-3 any interval needs.
constexpr double kLogStep = 1e-4;

/// The noise's two-sided per-sample PSD at nu cycles per sample (fit_covariance.cpp's unit PSDs
/// times the squared parameters; the ramp is deterministic and has none).
double noise_psd(const TermVector& theta, double tau0_s, const std::vector<double>& tau_c_s,
                 double nu) {
  const double s = std::sin(std::numbers::pi * nu);
  double psd = theta(0) * 4 * s * s / (tau0_s * tau0_s)  // Q
               + theta(1) / tau0_s                       // N
               + theta(2) / (2 * std::abs(s))            // B (Kasdin, untruncated)
               + theta(3) * tau0_s / (4 * s * s);        // K
  for (std::size_t g = 0; g < tau_c_s.size(); ++g) {
    const double phi = std::exp(-tau0_s / tau_c_s[g]);
    psd += theta(kTermCount + static_cast<Eigen::Index>(g)) * (1 - phi * phi) /
           (1 - 2 * phi * std::cos(2 * std::numbers::pi * nu) + phi * phi);
  }
  return psd;
}

/// A profile's T_c is searched within this factor of the estimate (golden section in ln T_c):
/// sigma^2 T_c is what a GM's falling side fixes, so sigma^2 at 8x its estimate pairs with a
/// T_c near 1/8 of it, beyond any bound the bench's curves reach (ln T_c sd <= 0.3).
constexpr double kProfileSpan = 8;
/// A T_c interval is searched within the range the search tries (fit_added_terms.cpp): from a
/// quarter sample interval to the log's length. A side not bounded there is 0 or infinity.
constexpr double kTauCShortest = 0.25;
/// Golden-section steps of a profile's inner T_c search (the bracket of ln 64 to ~1e-5).
constexpr int kProfileSteps = 30;
/// Bisection steps of a bound, and the growth of its bracket (factor per step, steps at most).
constexpr int kBisectionSteps = 30;
constexpr double kBracketGrowth = 1.25;
constexpr int kBracketSteps = 40;

/// The point where `rises(x)` turns true between `inside` (false) and `outside` (true) by
/// bisection in x.
template <class F>
double bisect(F&& rises, double inside, double outside) {
  for (int i = 0; i < kBisectionSteps; ++i) {
    const double mid = (inside + outside) / 2;
    (rises(mid) ? outside : inside) = mid;
  }
  return (inside + outside) / 2;
}

/// The bound of a one-dimensional profile `excess(ln x)` (its deviance above the minimum) on
/// one side of `ln_x0`: the ln x where it reaches q; nullopt when it does not before `ln_limit`
/// or the bracket's end (the curve does not bound x on that side).
template <class F>
std::optional<double> profile_bound(F&& excess, double ln_x0, double q, double direction,
                                    double ln_limit) {
  const double step = direction * std::log(kBracketGrowth);
  double inside = ln_x0;
  for (int i = 0; i < kBracketSteps && direction * (ln_limit - inside) > 0; ++i) {
    const double next =
        direction > 0 ? std::min(inside + step, ln_limit) : std::max(inside + step, ln_limit);
    if (excess(next) > q) return bisect([&](double x) { return excess(x) > q; }, inside, next);
    inside = next;
  }
  return std::nullopt;
}

/// (J^T J)^-1 of a whitened Jacobian, inverted with its columns scaled to unit diagonal (the
/// parameters span many orders of magnitude).
Eigen::MatrixXd scaled_inverse(const Eigen::MatrixXd& info) {
  const Eigen::VectorXd s =
      info.diagonal().cwiseSqrt().cwiseMax(std::numeric_limits<double>::min()).cwiseInverse();
  const Eigen::MatrixXd scaled = s.asDiagonal() * info * s.asDiagonal();
  return s.asDiagonal() * scaled.completeOrthogonalDecomposition().pseudoInverse() * s.asDiagonal();
}

}  // namespace

Eigen::MatrixXd sinusoid_cross_covariance(const std::vector<std::int64_t>& ms,
                                          std::int64_t n_phase_points, double tau0_s,
                                          const std::vector<double>& tau_c_s, double frequency_hz,
                                          const TermVector& theta) {
  const auto n = static_cast<Eigen::Index>(ms.size());
  const Eigen::Index s_col = kTermCount + static_cast<Eigen::Index>(tau_c_s.size());
  if (!(theta.size() > s_col)) throw Error("covariance: no sinusoid in the parameters");
  const Eigen::VectorXd a = sinusoid_column(ms, tau0_s, frequency_hz);
  const double psd = noise_psd(theta, tau0_s, tau_c_s, frequency_hz * tau0_s);
  Eigen::MatrixXd cov(n, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index l = 0; l < n; ++l) {
      const auto nj = static_cast<double>(n_phase_points - 2 * ms[static_cast<std::size_t>(j)]);
      const auto nl = static_cast<double>(n_phase_points - 2 * ms[static_cast<std::size_t>(l)]);
      cov(j, l) = 8 * theta(s_col) * a(j) * a(l) * psd / std::max(nj, nl);
    }
  }
  return cov;
}

AddedCovariance added_term_covariance(const Design& d, const Gls& fit,
                                      const Eigen::MatrixXd& weights_sigma,
                                      const std::vector<std::int64_t>& ms,
                                      std::int64_t n_phase_points, double tau0_s,
                                      const std::vector<double>& tau_c_s,
                                      std::optional<double> sinusoid_hz) {
  const auto rows = d.a.rows();
  const auto kept = static_cast<Eigen::Index>(fit.columns.size());
  const auto gms = static_cast<Eigen::Index>(tau_c_s.size());
  const Eigen::Index extra = gms + (sinusoid_hz ? 1 : 0);
  Eigen::MatrixXd j(rows, kept + extra);
  for (Eigen::Index c = 0; c < kept; ++c)
    j.col(c) = d.a.col(fit.columns[static_cast<std::size_t>(c)]);
  const double up = std::exp(kLogStep), down = std::exp(-kLogStep);
  for (Eigen::Index g = 0; g < gms; ++g) {
    const double t = tau_c_s[static_cast<std::size_t>(g)];
    j.col(kept + g) =
        fit.theta(kTermCount + g) *
        (gauss_markov_column(ms, tau0_s, t * up) - gauss_markov_column(ms, tau0_s, t * down)) /
        (2 * kLogStep);
  }
  if (sinusoid_hz) {
    const double f = *sinusoid_hz;
    j.col(kept + gms) =
        fit.theta(kTermCount + gms) *
        (sinusoid_column(ms, tau0_s, f * up) - sinusoid_column(ms, tau0_s, f * down)) /
        (2 * kLogStep);
  }
  const Eigen::LLT<Eigen::MatrixXd> llt(weights_sigma);
  if (llt.info() != Eigen::Success) throw Error("fit: AVAR covariance is not positive definite");
  const Eigen::MatrixXd jw = llt.matrixL().solve(j);
  Eigen::MatrixXd cov = scaled_inverse(jw.transpose() * jw);
  if (sinusoid_hz) {
    // Sandwich: the estimates' covariance is the weights' plus the cross term C:
    // B J^T W (Sigma_w + C) W J B = B + B (Jw^T L^-1 C L^-T Jw) B.
    const Eigen::MatrixXd c =
        sinusoid_cross_covariance(ms, n_phase_points, tau0_s, tau_c_s, *sinusoid_hz, fit.theta);
    const Eigen::MatrixXd lc = llt.matrixL().solve(c);
    const Eigen::MatrixXd cw = llt.matrixL().solve(lc.transpose());  // L^-1 C L^-T (C symmetric)
    cov += cov * (jw.transpose() * cw * jw) * cov;
  }
  AddedCovariance out;
  out.theta = cov.topLeftCorner(kept, kept);
  for (Eigen::Index g = 0; g < gms; ++g) {
    out.ln_tau_c_sd.push_back(std::sqrt(std::max(cov(kept + g, kept + g), 0.0)));
  }
  if (sinusoid_hz) out.ln_frequency_sd = std::sqrt(std::max(cov(kept + gms, kept + gms), 0.0));
  return out;
}

ProfileInterval gauss_markov_sigma2_profile(const Design& d, Mask mask,
                                            const Eigen::MatrixXd& sigma,
                                            const std::vector<std::int64_t>& ms, double tau0_s,
                                            std::size_t g, double tau_c_s, double q) {
  const auto col = kTermCount + static_cast<Eigen::Index>(g);
  const Mask others = mask & ~(1u << col);
  // The deviance at sigma^2 = s2, minimised over ln T_c and the other terms.
  const auto deviance = [&](double s2) {
    Design r = d;
    const auto at = [&](double ln_t) {
      r.v = d.v - s2 * gauss_markov_column(ms, tau0_s, std::exp(ln_t));
      return gls(r, others, sigma).chi2;
    };
    const double ln_t0 = std::log(tau_c_s), span = std::log(kProfileSpan);
    return std::min(at(ln_t0),
                    golden_section_minimum(at, ln_t0 - span, ln_t0 + span, kProfileSteps).f);
  };
  const double s2_hat = gls(d, mask, sigma).theta(col);
  const double d_min = std::min(deviance(s2_hat), gls(d, mask, sigma).chi2);
  ProfileInterval out;
  const auto excess = [&](double ln_s2) { return deviance(std::exp(ln_s2)) - d_min; };
  const auto high =
      profile_bound(excess, std::log(s2_hat), q, +1, std::numeric_limits<double>::infinity());
  out.high = high ? std::exp(*high) : std::numeric_limits<double>::infinity();
  if (deviance(0) - d_min <= q) {
    out.low = 0;
  } else {
    out.low = bisect([&](double s2) { return deviance(s2) - d_min > q; }, s2_hat, 0.0);
  }
  return out;
}

ProfileInterval gauss_markov_tau_c_profile(const Design& d, Mask mask, const Eigen::MatrixXd& sigma,
                                           const std::vector<std::int64_t>& ms,
                                           std::int64_t n_phase_points, double tau0_s,
                                           std::size_t g, double tau_c_s, double q) {
  const auto col = kTermCount + static_cast<Eigen::Index>(g);
  Design r = d;
  const auto deviance = [&](double ln_t) {
    r.a.col(col) = gauss_markov_column(ms, tau0_s, std::exp(ln_t));
    return gls(r, mask, sigma).chi2;
  };
  const double ln_t0 = std::log(tau_c_s);
  const double d_min = deviance(ln_t0);
  const auto excess = [&](double ln_t) { return deviance(ln_t) - d_min; };
  const double shortest = std::log(std::min(kTauCShortest * tau0_s, tau_c_s));
  const double longest =
      std::log(std::max(static_cast<double>(n_phase_points - 1) * tau0_s, tau_c_s));
  // A side the curve does not bound within the search range: 0 or infinity, not the range's
  // end (which would read as a measured bound).
  const auto low = profile_bound(excess, ln_t0, q, -1, shortest);
  const auto high = profile_bound(excess, ln_t0, q, +1, longest);
  return {low ? std::exp(*low) : 0.0, high ? std::exp(*high) : std::numeric_limits<double>::infinity()};
}

}  // namespace sigmatau::detail
