// Terms real sensors add to the five IEEE terms, in the joint fit.
//
// Glossary (as fit_joint.cpp): v the measured OAVAR, A the design, theta the squared
// parameters, Sigma the covariance of v under a model.
//  - A first-order Gauss-Markov (GM) term of correlation time T_c adds the column A_jg =
//    sampled_avar of a unit-sigma GM at m_j: linear in sigma^2 at a fixed T_c. Its ADEV rises
//    like a random walk's (~ sqrt(tau)) for tau << T_c, peaks near 1.9 T_c and falls like white
//    noise's for tau >> T_c: the broad bumps of real curves, a sum of a few standing in for a
//    flicker floor (GMWM practice), and, at T_c below a few tau0, white noise through a
//    first-order filter (that filter's output is the same AR(1) process).
//  - A sinusoid of frequency f adds A_js = its phase-averaged sampled AVAR per unit amplitude:
//    linear in A^2 at a fixed f. Its ADEV peaks near tau = 0.371 / f and falls as 1/tau beyond:
//    the narrow bump of a vibration or a periodic disturbance. Its AVAR estimates are taken as
//    exact (no covariance term; their scatter is left to the model error).
//
// Search, one term at a time (used only on curves no IEEE model describes, p < 1e-3):
//  1. With Sigma fixed at the current model's (widened) covariance, every T_c on a grid of
//     kGridPerOctave per octave from kGridShortest tau0 to N tau0, and (while no sinusoid is in
//     the model) every f on a grid of kFrequenciesPerOctave per octave whose ADEV peak lies
//     from the second fitted octave to one octave beyond the last, is tried with the current IEEE terms (every candidate at the first
//     addition; the NNLS sets unneeded ones to 0): the smallest chi2 wins. Then every subset of
//     the IEEE candidates is tried with it (an added term may stand in for B or K): the
//     smallest chi2 + (IEEE terms + 2 per added term) ln n + the priors wins. A subset that puts
//     an added term at 0 is the smaller model and is skipped.
//  2. The winner's T_c or f is refined by golden-section search in its logarithm between its
//     grid neighbours, Sigma still fixed.
//  3. The covariance basis is built with the GMs' T_c and the weights are iterated under the
//     model with the model error (fit_model_error.cpp); each T_c and f is refined once more
//     under the new weights and the weights iterated again.
//  4. The model is kept when its criterion (the Gaussian deviance of the curve under its own
//     widened weights, kappa at its maximum likelihood) + (parameters) ln n + priors is below
//     the previous model's; the search stops at the first addition that does not lower it, or
//     when kMaxGaussMarkov GMs and a sinusoid are in.
// An added term counts two parameters (magnitude and T_c or f) in every penalty.
#include "fit_added_terms.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "golden_section.hpp"
#include "sigmatau/noise_model.hpp"

namespace sigmatau::detail {
namespace {

/// Grid of correlation times: this many per octave (a GM's ADEV bump is about two octaves
/// wide, so a quarter octave puts the grid within 9 % of any T_c before refinement).
constexpr int kGridPerOctave = 4;
/// Shortest correlation time tried, in sample intervals: a GM this short is white noise
/// through a filter of a quarter sample (its AVAR differs from white noise's only at m = 1-2).
constexpr double kGridShortest = 0.25;
/// Grid of sinusoid frequencies: this many per octave (its ADEV bump is about one octave wide
/// and oscillates beyond it: a finer grid than the GM's).
constexpr int kFrequenciesPerOctave = 8;
/// A sinusoid's ADEV peaks at tau = kSinusoidPeak / f (the first maximum of
/// sin^2(pi f tau) / (pi f tau), at pi f tau = 1.1656).
constexpr double kSinusoidPeak = 0.371;
/// Golden-section steps of a refinement (the bracket shrinks by 0.618 a step: a grid step to
/// 1e-5 of it).
constexpr int kRefineSteps = 24;

constexpr Mask kIeeeBits = (1u << kTermCount) - 1;

double parameter_count(Mask used) {
  return std::popcount(used & kIeeeBits) + 2.0 * std::popcount(used & ~kIeeeBits);
}

/// The added columns' bits of a design with `gms` GM columns and `sinusoid` or not.
Mask added_bits(std::size_t gms, bool sinusoid) {
  const int count = static_cast<int>(gms) + (sinusoid ? 1 : 0);
  return ((1u << count) - 1) << kTermCount;
}

/// The layout of the added terms: the GMs' T_c and the sinusoid's f.
struct Added {
  std::vector<double> tau_c_s;
  std::optional<double> sinusoid_hz;
  Mask bits() const { return added_bits(tau_c_s.size(), sinusoid_hz.has_value()); }
};

Design design_with(const Design& d, const std::vector<std::int64_t>& ms, double tau0_s, const Added& added) {
  Design out;
  out.v = d.v;
  const auto gms = static_cast<Eigen::Index>(added.tau_c_s.size());
  out.a.resize(d.a.rows(), kTermCount + gms + (added.sinusoid_hz ? 1 : 0));
  out.a.leftCols(kTermCount) = d.a.leftCols(kTermCount);
  for (Eigen::Index g = 0; g < gms; ++g) {
    out.a.col(kTermCount + g) = gauss_markov_column(ms, tau0_s, added.tau_c_s[static_cast<std::size_t>(g)]);
  }
  if (added.sinusoid_hz) out.a.col(kTermCount + gms) = sinusoid_column(ms, tau0_s, *added.sinusoid_hz);
  return out;
}

struct Choice {
  double criterion = std::numeric_limits<double>::infinity();
  Mask mask = 0;
};

/// Stage 1's subsets: the best subset of the IEEE `candidates` with every added column of `d`
/// kept, weighted by the fixed `sigma`.
Choice best_subset(const Design& d, Mask candidates, Mask added, const Eigen::MatrixXd& sigma, double penalty) {
  Choice best;
  for (Mask s = 0; s <= candidates; ++s) {
    if ((s & candidates) != s) continue;
    const Gls g = gls(d, s | added, sigma);
    const Mask used = used_terms(g.theta);
    if ((used & added) != added) continue;
    const double crit = g.chi2 + parameter_count(used) * penalty + prior_penalty(used);
    if (crit < best.criterion) best = {crit, used};
  }
  return best;
}

/// Which added parameter a refinement moves: GM `index`, or the sinusoid.
struct Slot {
  bool sinusoid = false;
  std::size_t index = 0;
};

double& value_of(Added& added, Slot slot) {
  return slot.sinusoid ? *added.sinusoid_hz : added.tau_c_s[slot.index];
}

/// Golden-section search of ln(value) of `slot` in [lo, hi], Sigma fixed; returns the value.
double refine(const Design& d, const std::vector<std::int64_t>& ms, double tau0_s, Added added, Slot slot,
              Mask mask, double lo, double hi, const Eigen::MatrixXd& sigma) {
  const auto chi2 = [&](double x) {
    value_of(added, slot) = std::exp(x);
    return gls(design_with(d, ms, tau0_s, added), mask, sigma).chi2;
  };
  return std::exp(golden_section_minimum(chi2, std::log(lo), std::log(hi), kRefineSteps).x);
}

/// Iterates `model`'s weights with the model error under its basis and sets its criterion.
void settle_weights(ExtendedModel& model) {
  const WidenedFit w = iterate_widened(model.design, model.mask, *model.basis);
  model.fit = w.fit;
  model.kappa = w.kappa;
  model.mask = used_terms(model.fit.fit.theta);
  model.criterion = w.deviance +
                    parameter_count(model.mask) * std::log(static_cast<double>(model.design.v.size())) +
                    prior_penalty(model.mask);
}

/// One candidate addition found on a grid: its layout and chi2.
struct Addition {
  Added added;
  Slot slot;
  double chi2 = std::numeric_limits<double>::infinity();
  double step = 1;  ///< the grid's ratio (the refinement's bracket)
};

}  // namespace

Eigen::VectorXd gauss_markov_column(const std::vector<std::int64_t>& m, double tau0_s, double tau_c_s) {
  NoiseTerms unit;
  unit.gauss_markov = {GaussMarkov{1.0, tau_c_s}};
  const Sampling sampling{tau0_s, 0, false};
  Eigen::VectorXd col(static_cast<Eigen::Index>(m.size()));
  for (std::size_t j = 0; j < m.size(); ++j) {
    col(static_cast<Eigen::Index>(j)) = sampled_avar(unit, NoiseTerm::gauss_markov, m[j], sampling);
  }
  return col;
}

Eigen::VectorXd sinusoid_column(const std::vector<std::int64_t>& m, double tau0_s, double frequency_hz) {
  NoiseTerms unit;
  unit.sinusoid = Sinusoid{1.0, frequency_hz, 0.0};
  const Sampling sampling{tau0_s, 0, false};
  Eigen::VectorXd col(static_cast<Eigen::Index>(m.size()));
  for (std::size_t j = 0; j < m.size(); ++j) {
    col(static_cast<Eigen::Index>(j)) = sampled_avar(unit, NoiseTerm::sinusoid, m[j], sampling);
  }
  return col;
}

ExtendedModel extend_with_added_terms(const Design& d, const std::vector<std::int64_t>& ms,
                                      const CurveSource& source, Mask base, Mask candidates,
                                      std::shared_ptr<const CovarianceBasis> basis) {
  const double penalty = std::log(static_cast<double>(d.v.size()));
  const double tau0 = source.tau0_s;
  const double span = static_cast<double>(source.n_phase_points) * tau0;
  ExtendedModel best;
  best.design = d;
  best.basis = std::move(basis);
  best.mask = base;
  settle_weights(best);
  Added current;
  Mask ieee = candidates;  // the IEEE terms offered with the next addition

  for (int round = 0; round < static_cast<int>(kMaxGaussMarkov) + 1; ++round) {
    // 1. Grids, Sigma fixed.
    Addition found;
    const auto try_addition = [&](const Added& trial, Slot slot, double step) {
      const double chi2 = gls(design_with(d, ms, tau0, trial), ieee | trial.bits(), best.fit.sigma).chi2;
      if (chi2 < found.chi2) found = {trial, slot, chi2, step};
    };
    if (current.tau_c_s.size() < kMaxGaussMarkov) {
      const double step = std::exp2(1.0 / kGridPerOctave);
      for (double t = kGridShortest * tau0; t <= span; t *= step) {
        // A T_c within a grid step of one already in the model adds nothing new.
        bool taken = false;
        for (const double u : current.tau_c_s) taken = taken || (t / u < step * 1.01 && u / t < step * 1.01);
        if (taken) continue;
        Added trial = current;
        trial.tau_c_s.push_back(t);
        try_addition(trial, {false, trial.tau_c_s.size() - 1}, step);
      }
    }
    if (!current.sinusoid_hz) {
      // Frequencies whose ADEV peak (tau = kSinusoidPeak / f) lies from the second fitted
      // octave to one octave beyond the last: a sinusoid peaking at the shortest tau raises that
      // point alone (at the Nyquist frequency its AVAR is 0 at every even m), which no octave
      // curve tells from a sensor's filter (left out instead: fit.cpp), and at f = k / (m tau0)
      // its AVAR is 0 at every octave m above: a column of zeros takes any amplitude.
      const double step = std::exp2(1.0 / kFrequenciesPerOctave);
      const double tau_lo = static_cast<double>(ms.front()) * tau0, tau_hi = static_cast<double>(ms.back()) * tau0;
      const double f_hi = std::min(0.5 / tau0, kSinusoidPeak / (2 * tau_lo));
      for (double f = std::max(1 / span, kSinusoidPeak / (2 * tau_hi)); f <= f_hi; f *= step) {
        Added trial = current;
        trial.sinusoid_hz = f;
        try_addition(trial, {true, 0}, step);
      }
    }
    if (!(found.chi2 < std::numeric_limits<double>::infinity())) break;
    // 2. The IEEE terms again with the addition, then its value refined.
    const Choice choice = best_subset(design_with(d, ms, tau0, found.added), candidates, found.added.bits(),
                                      best.fit.sigma, penalty);
    if (!(choice.criterion < std::numeric_limits<double>::infinity())) break;
    Added added = found.added;
    const double start = value_of(added, found.slot);
    value_of(added, found.slot) = refine(d, ms, tau0, added, found.slot, choice.mask, start / found.step,
                                         start * found.step, best.fit.sigma);
    // 3. Own weights; every added value refined once more under them.
    ExtendedModel model;
    model.mask = choice.mask;
    const auto settle = [&](const Added& a) {
      model.tau_c_s = a.tau_c_s;
      model.sinusoid_hz = a.sinusoid_hz;
      model.design = design_with(d, ms, tau0, a);
      model.basis = std::make_shared<const CovarianceBasis>(
          build_covariance_basis(ms, source.n_phase_points, tau0, a.tau_c_s));
      settle_weights(model);
    };
    settle(added);
    if ((model.mask & added.bits()) != added.bits()) break;  // an added term fell to 0
    for (std::size_t k = 0; k < added.tau_c_s.size(); ++k) {
      const double t = added.tau_c_s[k];
      const double step = std::exp2(1.0 / kGridPerOctave);
      added.tau_c_s[k] = refine(d, ms, tau0, added, {false, k}, model.mask, t / step, t * step, model.fit.sigma);
    }
    if (added.sinusoid_hz) {
      const double f = *added.sinusoid_hz;
      const double step = std::exp2(1.0 / kFrequenciesPerOctave);
      added.sinusoid_hz = refine(d, ms, tau0, added, {true, 0}, model.mask, f / step, f * step, model.fit.sigma);
    }
    settle(added);
    if ((model.mask & added.bits()) != added.bits()) break;
    // 4. Kept while the criterion falls.
    if (!(model.criterion < best.criterion)) break;
    current = added;
    ieee = model.mask & kIeeeBits;
    best = std::move(model);
  }
  return best;
}

}  // namespace sigmatau::detail
