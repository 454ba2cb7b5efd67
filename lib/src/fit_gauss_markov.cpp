// Gauss-Markov terms in the joint fit.
//
// Glossary (as fit_joint.cpp): v the measured OAVAR, A the design, theta the squared
// parameters, Sigma the covariance of v under a model. A first-order Gauss-Markov (GM) term of
// correlation time T_c adds the column A_jg = sampled_avar of a unit-sigma GM at m_j: linear in
// sigma^2 at a fixed T_c, so a GM enters the generalised least squares as any other term once
// T_c is chosen. Its ADEV rises like a random walk's (~ sqrt(tau)) for tau << T_c, peaks near
// 1.9 T_c and falls like white noise's for tau >> T_c: the bumps of real curves (and, at T_c
// below a few tau0, white noise through a first-order filter: the AR(1) filter's output is the
// same process).
//
// Search, one GM at a time (GMWM practice describes a real MEMS bias by a sum of a few):
//  1. With Sigma fixed at the current model's covariance, every T_c on a grid of
//     kGridPerOctave per octave from kGridShortest tau0 to N tau0 is tried with the current
//     IEEE terms (every candidate at the first addition; the NNLS sets unneeded ones to 0), the
//     smallest chi2 wins; then every subset of the IEEE candidates is tried with it (the new
//     term may stand in for B or K): the smallest chi2 + (IEEE terms + 2 per GM) ln n + the
//     priors wins. A subset that puts a GM at 0 is the smaller model and is skipped.
//  2. The winner's T_c is refined by golden-section search in ln T_c between its grid
//     neighbours, Sigma still fixed.
//  3. The covariance basis is built with the GMs' T_c and the weights are iterated under the
//     model with the model error (fit_model_error.cpp: the search runs only on curves no IEEE
//     model describes); each T_c is refined once more under the new weights and the weights
//     iterated again.
//  4. The model is kept when its criterion (the Gaussian deviance of the curve under its own
//     widened weights, kappa at its maximum likelihood) + (parameters) ln n + priors is below
//     the previous model's; the search stops at the first addition that does not lower it, or
//     at kMaxGaussMarkovTerms.
// A GM counts two parameters (sigma and T_c) in every penalty.
#include "fit_gauss_markov.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "sigmatau/noise_model.hpp"

namespace sigmatau::detail {
namespace {

/// Grid of correlation times: this many per octave (a GM's ADEV bump is about two octaves
/// wide, so a quarter octave puts the grid within 9 % of any T_c before refinement).
constexpr int kGridPerOctave = 4;
/// Shortest correlation time tried, in sample intervals: a GM this short is white noise
/// through a filter of a quarter sample (its AVAR differs from white noise's only at m = 1-2).
constexpr double kGridShortest = 0.25;
/// Golden-section steps of a refinement (the bracket shrinks by 0.618 a step: a quarter
/// octave to 1e-5 of it).
constexpr int kRefineSteps = 24;

double parameter_count(Mask used) {
  const Mask ieee = (1u << kTermCount) - 1;
  return std::popcount(used & ieee) + 2.0 * std::popcount(used & ~ieee);
}

Mask gm_bits(int count) { return ((1u << count) - 1) << kTermCount; }

/// The design of `d` with its Gauss-Markov columns replaced by those of `tau_c_s`.
Design design_with(const Design& d, const std::vector<std::int64_t>& ms, double tau0_s,
                   const std::vector<double>& tau_c_s) {
  Design out;
  out.v = d.v;
  out.a.resize(d.a.rows(), kTermCount + static_cast<Eigen::Index>(tau_c_s.size()));
  out.a.leftCols(kTermCount) = d.a.leftCols(kTermCount);
  for (std::size_t g = 0; g < tau_c_s.size(); ++g) {
    out.a.col(kTermCount + static_cast<Eigen::Index>(g)) = gauss_markov_column(ms, tau0_s, tau_c_s[g]);
  }
  return out;
}

struct Choice {
  double criterion = std::numeric_limits<double>::infinity();
  Mask mask = 0;
};

/// Stage 1 of the search: the best subset of the IEEE `candidates` with every GM column of
/// `d` kept, weighted by the fixed `sigma`.
Choice best_subset(const Design& d, Mask candidates, const Eigen::MatrixXd& sigma, double penalty) {
  const int n_gm = static_cast<int>(d.a.cols()) - kTermCount;
  const Mask gms = gm_bits(n_gm);
  Choice best;
  for (Mask s = 0; s <= candidates; ++s) {
    if ((s & candidates) != s) continue;
    const Gls g = gls(d, s | gms, sigma);
    const Mask used = used_terms(g.theta);
    if ((used & gms) != gms) continue;
    const double crit = g.chi2 + parameter_count(used) * penalty + prior_penalty(used);
    if (crit < best.criterion) best = {crit, used};
  }
  return best;
}

/// chi2 of the model `mask` on `d` with its GM column `g` at `tau_c`, Sigma fixed.
double chi2_at(const Design& d, const std::vector<std::int64_t>& ms, double tau0_s, Mask mask,
               Eigen::Index g, double tau_c, const Eigen::MatrixXd& sigma) {
  Design trial = d;
  trial.a.col(kTermCount + g) = gauss_markov_column(ms, tau0_s, tau_c);
  const Gls fit = gls(trial, mask, sigma);
  return fit.chi2;
}

/// Golden-section search of ln T_c of GM column `g` in [lo, hi] (Sigma fixed).
double refine(const Design& d, const std::vector<std::int64_t>& ms, double tau0_s, Mask mask,
              Eigen::Index g, double lo, double hi, const Eigen::MatrixXd& sigma) {
  const double r = (std::sqrt(5.0) - 1) / 2;
  double a = std::log(lo), b = std::log(hi);
  double x1 = b - r * (b - a), x2 = a + r * (b - a);
  double f1 = chi2_at(d, ms, tau0_s, mask, g, std::exp(x1), sigma);
  double f2 = chi2_at(d, ms, tau0_s, mask, g, std::exp(x2), sigma);
  for (int i = 0; i < kRefineSteps; ++i) {
    if (f1 <= f2) {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - r * (b - a);
      f1 = chi2_at(d, ms, tau0_s, mask, g, std::exp(x1), sigma);
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + r * (b - a);
      f2 = chi2_at(d, ms, tau0_s, mask, g, std::exp(x2), sigma);
    }
  }
  return std::exp(f1 <= f2 ? x1 : x2);
}

/// Iterates `model`'s weights with the model error under its basis and sets its criterion.
void settle_weights(ExtendedModel& model) {
  const WidenedFit w = iterate_widened(model.design, model.mask, *model.basis);
  model.fit = w.fit;
  model.kappa = w.kappa;
  model.mask = used_terms(model.fit.fit.theta);
  model.criterion = w.deviance + parameter_count(model.mask) * std::log(static_cast<double>(model.design.v.size())) +
                    prior_penalty(model.mask);
}

/// Builds the basis for `model`'s T_c, then settle_weights.
void settle(ExtendedModel& model, const std::vector<std::int64_t>& ms, const CurveSource& source) {
  model.basis = std::make_shared<const CovarianceBasis>(
      build_covariance_basis(ms, source.n_phase_points, source.tau0_s, model.tau_c_s));
  settle_weights(model);
}

}  // namespace

Eigen::VectorXd gauss_markov_column(const std::vector<std::int64_t>& m, double tau0_s, double tau_c_s) {
  NoiseTerms unit;
  unit.gauss_markov = GaussMarkov{1.0, tau_c_s};
  const Sampling sampling{tau0_s, 0, false};
  Eigen::VectorXd col(static_cast<Eigen::Index>(m.size()));
  for (std::size_t j = 0; j < m.size(); ++j) {
    col(static_cast<Eigen::Index>(j)) = sampled_avar(unit, NoiseTerm::gauss_markov, m[j], sampling);
  }
  return col;
}

ExtendedModel extend_with_gauss_markov(const Design& d, const std::vector<std::int64_t>& ms,
                                       const CurveSource& source, Mask base, Mask candidates,
                                       std::shared_ptr<const CovarianceBasis> basis) {
  const double penalty = std::log(static_cast<double>(d.v.size()));
  const double tau0 = source.tau0_s;
  ExtendedModel best;
  best.design = d;
  best.basis = std::move(basis);
  best.mask = base;
  settle_weights(best);
  double best_criterion = best.criterion;
  Eigen::MatrixXd sigma = best.fit.sigma;
  std::vector<double> tau_c;
  Mask current = candidates;
  // The grid: kGridShortest tau0 .. N tau0.
  std::vector<double> grid;
  const double longest = static_cast<double>(source.n_phase_points) * tau0;
  for (double t = kGridShortest * tau0; t <= longest; t *= std::exp2(1.0 / kGridPerOctave)) grid.push_back(t);
  const double step = std::exp2(1.0 / kGridPerOctave);

  for (int g = 0; g < kMaxGaussMarkovTerms; ++g) {
    // 1. Grid, Sigma fixed, with the current IEEE terms (all candidates on the first
    // addition); then the IEEE terms chosen again at the T_c found.
    double best_chi2 = std::numeric_limits<double>::infinity();
    double chosen = 0;
    for (const double t : grid) {
      bool taken = false;  // a T_c within a grid step of one already in the model adds nothing new
      for (const double u : tau_c) taken = taken || (t / u < step * 1.01 && u / t < step * 1.01);
      if (taken) continue;
      std::vector<double> trial_tc = tau_c;
      trial_tc.push_back(t);
      const Gls fit = gls(design_with(d, ms, tau0, trial_tc), current | gm_bits(g + 1), sigma);
      if (fit.chi2 < best_chi2) {
        best_chi2 = fit.chi2;
        chosen = t;
      }
    }
    if (!(chosen > 0)) break;
    std::vector<double> chosen_tc = tau_c;
    chosen_tc.push_back(chosen);
    const Choice choice = best_subset(design_with(d, ms, tau0, chosen_tc), candidates, sigma, penalty);
    if (!(choice.criterion < std::numeric_limits<double>::infinity())) break;
    ExtendedModel model;
    model.tau_c_s = tau_c;
    model.tau_c_s.push_back(chosen);
    model.mask = choice.mask;
    model.design = design_with(d, ms, tau0, model.tau_c_s);
    // 2. Refinement between the grid neighbours.
    const auto last = static_cast<Eigen::Index>(g);
    model.tau_c_s.back() = refine(model.design, ms, tau0, model.mask, last, chosen / step, chosen * step, sigma);
    model.design = design_with(d, ms, tau0, model.tau_c_s);
    // 3. Own weights; every T_c refined once more under them.
    settle(model, ms, source);
    if ((model.mask & gm_bits(g + 1)) != gm_bits(g + 1)) break;  // a GM fell to 0
    for (std::size_t k = 0; k < model.tau_c_s.size(); ++k) {
      const double t = model.tau_c_s[k];
      model.tau_c_s[k] = refine(model.design, ms, tau0, model.mask, static_cast<Eigen::Index>(k),
                                t / step, t * step, model.fit.sigma);
      model.design = design_with(d, ms, tau0, model.tau_c_s);
    }
    settle(model, ms, source);
    if ((model.mask & gm_bits(g + 1)) != gm_bits(g + 1)) break;
    // 4. Kept while the criterion falls.
    if (!(model.criterion < best_criterion)) break;
    best_criterion = model.criterion;
    tau_c = model.tau_c_s;
    sigma = model.fit.sigma;
    current = model.mask & ((1u << kTermCount) - 1);
    best = std::move(model);
  }
  return best;
}

}  // namespace sigmatau::detail
