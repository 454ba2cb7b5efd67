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
// Search (used only on curves no IEEE model describes, p < 1e-3), forward then backward:
//  1. With Sigma fixed at the current model's (widened) covariance, every T_c on a grid of
//     kGridPerOctave per octave from kGridShortest tau0 to N tau0, and (while no sinusoid is in
//     the model) every f on a grid of kFrequenciesPerOctave per octave whose ADEV peak lies
//     from the second fitted octave to one octave beyond the last, is tried with the current
//     IEEE terms (every candidate at the first addition; the NNLS sets unneeded ones to 0): the
//     smallest chi2 wins. Then every subset of the IEEE candidates is tried with it (an added
//     term may stand in for B or K): the smallest chi2 + (IEEE terms + 3 per added term) ln n +
//     the priors wins. A subset that puts an added term at 0 is the smaller model and is skipped.
//  2. The winner's T_c or f is refined by golden-section search in its logarithm between its
//     grid neighbours, Sigma still fixed.
//  3. The covariance basis is built with the GMs' T_c and the weights are iterated under the
//     model with the model error (fit_model_error.cpp), from the estimates' own covariance and
//     from the previous model's weights (the lower deviance kept), with that subset and with
//     every IEEE candidate (the lower criterion kept: a subset chosen under the previous
//     model's weights can be far from the best under its own); every T_c and f is refined once
//     more under the new weights and the weights iterated again.
//  4. The model is kept when its criterion (the Gaussian deviance of the curve under its own
//     widened weights, kappa at its maximum likelihood) + (parameters) ln n + priors is below
//     the previous model's. When no single addition lowers it, two at once are tried (two GMs,
//     or a GM and the sinusoid: the grid of pairs with Sigma fixed, then 1-3 for both): a term
//     may help only beside another. The forward pass ends when neither lowers it, or when
//     kMaxGaussMarkov GMs and a sinusoid are in.
//  5. Backward: the model without each of its terms in turn (an IEEE term an added one made
//     redundant, an added term the later ones stand in for), weights settled; the lowest
//     criterion replaces the model when it is lower, and the forward pass runs again
//     (kMaxPasses at most).
// Measured on the 13 real channels (bench/results_fit_real.md) and the simulated profiles of
// bench/fit_added_terms_sim.py: step 3's second subset takes the ADIS16405 accelerometers x and
// z from p = 0 and 8e-12 to 0.36 and 0.49; with neither the pairs nor step 5 the candidates'
// extra IEEE terms stay (true model: GM sum 17 -> 0 %, filtered white 53 -> 3 %, 10 seeds);
// with step 5 and no pairs, GM sum 7 %; with both, 17 and 53 % as before the change.
// An added term counts three parameters in every penalty: its magnitude, and its T_c or f
// twice, since that position is the best of a grid over the whole tau range (some 80 T_c or
// 150 frequencies), and the best of many positions lowers a noise curve's deviance by more than
// one free parameter does. Measured with bench/fit_added_terms_sim.py on seeds 11-20 (seeds 1-10
// had been looked at while choosing): true model GM sum / sinusoid / filtered white 13 / 87 / 37 %
// at two, 13 / 97 / 73 % at three; filtered white's GM sigma coverage 74 -> 90 %; no model on
// the 13 real channels loses p >= 0.001 or the curve target (bench/results_fit_real.md).
#include "fit_added_terms.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <optional>

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
/// The grids' ratios (a refinement's bracket is one step either side).
const double kTauCStep = std::exp2(1.0 / kGridPerOctave);
const double kFrequencyStep = std::exp2(1.0 / kFrequenciesPerOctave);
/// Forward-backward passes at most (each kept change lowers the criterion, so the search ends
/// anyway; this bounds its time).
constexpr int kMaxPasses = 3;
/// A candidate whose criterion, settled before its values are refined under its own weights,
/// lies this far above the model it would replace is not refined (a refinement moves each
/// value by less than a grid step; it costs a covariance basis, most of the search's time).
/// On the 13 real channels it changes no selected model.
constexpr double kHopeless = 10;

constexpr Mask kIeeeBits = (1u << kTermCount) - 1;

double parameter_count(Mask used) {
  return std::popcount(used & kIeeeBits) + 3.0 * std::popcount(used & ~kIeeeBits);
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
void settle_weights(ExtendedModel& model, const Eigen::MatrixXd* start = nullptr) {
  WidenedFit w = iterate_widened(model.design, model.mask, *model.basis);
  if (start) {
    WidenedFit from_start = iterate_widened(model.design, model.mask, *model.basis, start);
    if (from_start.deviance < w.deviance) w = std::move(from_start);
  }
  model.fit = w.fit;
  model.kappa = w.kappa;
  model.mask = used_terms(model.fit.fit.theta);
  model.criterion = w.deviance +
                    parameter_count(model.mask) * std::log(static_cast<double>(model.design.v.size())) +
                    prior_penalty(model.mask);
}

/// What every step of the search shares: the curve, its log, the IEEE candidates and the
/// grids of correlation times and frequencies with their design columns.
struct Search {
  const Design& d;
  const std::vector<std::int64_t>& ms;
  const CurveSource& source;
  Mask candidates = 0;
  double penalty = 0;  ///< ln n
  double tau0 = 0;
  std::vector<double> tau_c_grid, frequency_grid;
  std::vector<Eigen::VectorXd> tau_c_columns, frequency_columns;

  Search(const Design& design, const std::vector<std::int64_t>& m, const CurveSource& src, Mask cand)
      : d(design), ms(m), source(src), candidates(cand),
        penalty(std::log(static_cast<double>(design.v.size()))), tau0(src.tau0_s) {
    const double span = static_cast<double>(source.n_phase_points) * tau0;
    for (double t = kGridShortest * tau0; t <= span; t *= kTauCStep) {
      tau_c_grid.push_back(t);
      tau_c_columns.push_back(gauss_markov_column(ms, tau0, t));
    }
    // Frequencies whose ADEV peak (tau = kSinusoidPeak / f) lies from the second fitted
    // octave to one octave beyond the last: a sinusoid peaking at the shortest tau raises that
    // point alone (at the Nyquist frequency its AVAR is 0 at every even m), which no octave
    // curve tells from a sensor's filter (left out instead: fit.cpp), and at f = k / (m tau0)
    // its AVAR is 0 at every octave m above: a column of zeros takes any amplitude.
    const double tau_lo = static_cast<double>(ms.front()) * tau0, tau_hi = static_cast<double>(ms.back()) * tau0;
    const double f_hi = std::min(0.5 / tau0, kSinusoidPeak / (2 * tau_lo));
    for (double f = std::max(1 / span, kSinusoidPeak / (2 * tau_hi)); f <= f_hi; f *= kFrequencyStep) {
      frequency_grid.push_back(f);
      frequency_columns.push_back(sinusoid_column(ms, tau0, f));
    }
  }

  /// The covariance basis of the layout `added` (its GMs' correlation times).
  std::shared_ptr<const CovarianceBasis> basis_for(const Added& added) const {
    return std::make_shared<const CovarianceBasis>(
        build_covariance_basis(ms, source.n_phase_points, tau0, added.tau_c_s));
  }

  /// The fit of `added` with the IEEE terms `mask`, its weights settled under `basis` (from
  /// the estimates' own covariance and from `start`, the better).
  ExtendedModel settled(const Added& added, Mask mask, const Eigen::MatrixXd* start,
                        std::shared_ptr<const CovarianceBasis> basis) const {
    ExtendedModel model;
    model.mask = mask | added.bits();
    model.tau_c_s = added.tau_c_s;
    model.sinusoid_hz = added.sinusoid_hz;
    model.design = design_with(d, ms, tau0, added);
    model.basis = std::move(basis);
    settle_weights(model, start);
    return model;
  }

  /// The better settled fit of `added` with the IEEE terms `mask` and with every IEEE
  /// candidate (the NNLS dropping those it does not need): a subset chosen under another
  /// model's weights can be far from the best under its own (the ADIS16405 accelerometers: N
  /// and a sinusoid chosen under weights of model error 0.7 settle at model error 1, where B, K
  /// and the sinusoid settle at 0.1). Terms the candidates keep that the curve does not need
  /// are dropped after the forward pass (drop_one). Empty when an added term falls to 0 in both.
  std::optional<ExtendedModel> settled_either(const Added& added, Mask mask, const Eigen::MatrixXd* start) const {
    const auto basis = basis_for(added);
    std::optional<ExtendedModel> out;
    for (const Mask m : {mask & kIeeeBits, candidates}) {
      ExtendedModel x = settled(added, m, start, basis);
      if ((x.mask & added.bits()) == added.bits() && (!out || x.criterion < out->criterion)) out = std::move(x);
      if ((mask & kIeeeBits) == candidates) break;
    }
    return out;
  }
};

/// A correlation time within a grid step of one in `tau_c_s` adds nothing new.
bool near_taken(double t, const std::vector<double>& tau_c_s) {
  for (const double u : tau_c_s) {
    if (t / u < kTauCStep * 1.01 && u / t < kTauCStep * 1.01) return true;
  }
  return false;
}

/// Stages 1-3 for a candidate layout `trial` whose new terms are `fresh` (found on a grid with
/// `best`'s weights): the IEEE subset chosen again, the new values refined, the weights settled,
/// every added value refined once more under them and the weights settled again. Empty when an
/// added term falls to 0.
std::optional<ExtendedModel> develop(const Search& s, const ExtendedModel& best, Added trial,
                                     const std::vector<Slot>& fresh) {
  const Choice choice =
      best_subset(design_with(s.d, s.ms, s.tau0, trial), s.candidates, trial.bits(), best.fit.sigma, s.penalty);
  if (!(choice.criterion < std::numeric_limits<double>::infinity())) return std::nullopt;
  const auto step_of = [](Slot slot) { return slot.sinusoid ? kFrequencyStep : kTauCStep; };
  for (const Slot slot : fresh) {
    const double v = value_of(trial, slot);
    value_of(trial, slot) =
        refine(s.d, s.ms, s.tau0, trial, slot, choice.mask, v / step_of(slot), v * step_of(slot), best.fit.sigma);
  }
  std::optional<ExtendedModel> model = s.settled_either(trial, choice.mask, &best.fit.sigma);
  if (!model) return std::nullopt;
  // Far above `best` the refinement (a grid step either side) will not bring it below: spared.
  if (model->criterion > best.criterion + kHopeless) return model;
  std::vector<Slot> all;
  for (std::size_t k = 0; k < trial.tau_c_s.size(); ++k) all.push_back({false, k});
  if (trial.sinusoid_hz) all.push_back({true, 0});
  for (const Slot slot : all) {
    const double v = value_of(trial, slot);
    value_of(trial, slot) =
        refine(s.d, s.ms, s.tau0, trial, slot, model->mask, v / step_of(slot), v * step_of(slot), model->fit.sigma);
  }
  const Eigen::MatrixXd start = model->fit.sigma;
  return s.settled_either(trial, model->mask, &start);
}

/// The layout of a settled model.
Added layout_of(const ExtendedModel& m) { return {m.tau_c_s, m.sinusoid_hz}; }

/// One addition (a GM or the sinusoid) to `best`: the grid's smallest chi2 with `best`'s
/// weights and the IEEE terms `ieee`, developed.
std::optional<ExtendedModel> add_one(const Search& s, const ExtendedModel& best, Mask ieee) {
  const Added current = layout_of(best);
  Added found;
  Slot slot;
  double found_chi2 = std::numeric_limits<double>::infinity();
  Design trial_design = design_with(s.d, s.ms, s.tau0, current);
  const auto try_column = [&](const Eigen::VectorXd& col, bool sinusoid) {
    // The new column goes last: a GM before the sinusoid keeps design_with's order below.
    trial_design.a.conservativeResize(Eigen::NoChange, trial_design.a.cols() + 1);
    trial_design.a.col(trial_design.a.cols() - 1) = col;
    const Mask bits = added_bits(current.tau_c_s.size() + 1, current.sinusoid_hz.has_value() || sinusoid);
    const double chi2 = gls(trial_design, ieee | bits, best.fit.sigma).chi2;
    trial_design.a.conservativeResize(Eigen::NoChange, trial_design.a.cols() - 1);
    return chi2;
  };
  if (current.tau_c_s.size() < kMaxGaussMarkov) {
    for (std::size_t i = 0; i < s.tau_c_grid.size(); ++i) {
      const double t = s.tau_c_grid[i];
      if (near_taken(t, current.tau_c_s)) continue;
      const double chi2 = try_column(s.tau_c_columns[i], false);
      if (chi2 < found_chi2) {
        found_chi2 = chi2;
        found = current;
        found.tau_c_s.push_back(t);
        slot = {false, found.tau_c_s.size() - 1};
      }
    }
  }
  if (!current.sinusoid_hz) {
    for (std::size_t i = 0; i < s.frequency_grid.size(); ++i) {
      const double chi2 = try_column(s.frequency_columns[i], true);
      if (chi2 < found_chi2) {
        found_chi2 = chi2;
        found = current;
        found.sinusoid_hz = s.frequency_grid[i];
        slot = {true, 0};
      }
    }
  }
  if (!(found_chi2 < std::numeric_limits<double>::infinity())) return std::nullopt;
  return develop(s, best, found, {slot});
}

/// Two additions at once (two GMs, or a GM and the sinusoid) to `best`, for when no single one
/// lowers the criterion: a term may help only beside another (a bump and a rise that each,
/// alone, the IEEE terms trade against), and the greedy search never reaches such a pair. The
/// grid of pairs' smallest chi2 with `best`'s weights and every IEEE candidate, developed.
std::optional<ExtendedModel> add_two(const Search& s, const ExtendedModel& best) {
  const Added current = layout_of(best);
  const std::size_t gms = current.tau_c_s.size();
  const bool gm_gm = gms + 2 <= kMaxGaussMarkov;
  const bool gm_sin = gms + 1 <= kMaxGaussMarkov && !current.sinusoid_hz;
  if (!gm_gm && !gm_sin) return std::nullopt;
  // Columns: IEEE, current GMs, new GM, then a second new GM or the sinusoid, then the current
  // sinusoid if any (design_with's order: GMs, then the sinusoid).
  Design base = design_with(s.d, s.ms, s.tau0, current);
  const Eigen::Index gm1 = kTermCount + static_cast<Eigen::Index>(gms);
  Design trial;
  trial.v = s.d.v;
  trial.a.resize(base.a.rows(), base.a.cols() + 2);
  trial.a.leftCols(gm1) = base.a.leftCols(gm1);
  if (current.sinusoid_hz) trial.a.col(gm1 + 2) = base.a.col(gm1);
  double best_chi2 = std::numeric_limits<double>::infinity();
  Added found;
  std::vector<Slot> fresh;
  const Mask ieee = s.candidates;
  for (std::size_t i = 0; i < s.tau_c_grid.size(); ++i) {
    if (near_taken(s.tau_c_grid[i], current.tau_c_s)) continue;
    trial.a.col(gm1) = s.tau_c_columns[i];
    if (gm_gm) {
      const Mask bits = added_bits(gms + 2, current.sinusoid_hz.has_value());
      for (std::size_t k = i + 1; k < s.tau_c_grid.size(); ++k) {
        if (near_taken(s.tau_c_grid[k], current.tau_c_s) || s.tau_c_grid[k] / s.tau_c_grid[i] < kTauCStep * 1.01) {
          continue;
        }
        trial.a.col(gm1 + 1) = s.tau_c_columns[k];
        const double chi2 = gls(trial, ieee | bits, best.fit.sigma).chi2;
        if (chi2 < best_chi2) {
          best_chi2 = chi2;
          found = current;
          found.tau_c_s.push_back(s.tau_c_grid[i]);
          found.tau_c_s.push_back(s.tau_c_grid[k]);
          fresh = {{false, gms}, {false, gms + 1}};
        }
      }
    }
    if (gm_sin) {
      Design with_sin;
      with_sin.v = s.d.v;
      with_sin.a = trial.a.leftCols(gm1 + 2);
      const Mask bits = added_bits(gms + 1, true);
      for (std::size_t k = 0; k < s.frequency_grid.size(); ++k) {
        with_sin.a.col(gm1 + 1) = s.frequency_columns[k];
        const double chi2 = gls(with_sin, ieee | bits, best.fit.sigma).chi2;
        if (chi2 < best_chi2) {
          best_chi2 = chi2;
          found = current;
          found.tau_c_s.push_back(s.tau_c_grid[i]);
          found.sinusoid_hz = s.frequency_grid[k];
          fresh = {{false, gms}, {true, 0}};
        }
      }
    }
  }
  if (!(best_chi2 < std::numeric_limits<double>::infinity())) return std::nullopt;
  return develop(s, best, found, fresh);
}

/// Backward elimination: `best` without one of its terms (an IEEE term an added one made
/// redundant, or an added term the later ones stand in for), weights settled; the smallest
/// criterion of them. Empty when `best` has a single term.
std::optional<ExtendedModel> drop_one(const Search& s, const ExtendedModel& best) {
  if (std::popcount(best.mask) < 2) return std::nullopt;
  std::optional<ExtendedModel> out;
  const auto consider = [&](ExtendedModel m) {
    if (!out || m.criterion < out->criterion) out = std::move(m);
  };
  const Added current = layout_of(best);
  const Mask ieee = best.mask & kIeeeBits;
  for (int k = 0; k < kTermCount; ++k) {
    const Mask bit = 1u << k;
    if (!(ieee & bit)) continue;
    ExtendedModel m = s.settled(current, ieee & ~bit, &best.fit.sigma, best.basis);
    if ((m.mask & current.bits()) == current.bits()) consider(std::move(m));
  }
  for (std::size_t g = 0; g < current.tau_c_s.size(); ++g) {
    Added fewer = current;
    fewer.tau_c_s.erase(fewer.tau_c_s.begin() + static_cast<std::ptrdiff_t>(g));
    ExtendedModel m = s.settled(fewer, ieee, &best.fit.sigma, s.basis_for(fewer));
    if ((m.mask & fewer.bits()) == fewer.bits()) consider(std::move(m));
  }
  if (current.sinusoid_hz) {
    Added fewer = current;
    fewer.sinusoid_hz.reset();
    ExtendedModel m = s.settled(fewer, ieee, &best.fit.sigma, best.basis);  // the same GMs
    if ((m.mask & fewer.bits()) == fewer.bits()) consider(std::move(m));
  }
  return out;
}

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
  const Search s(d, ms, source, candidates);
  ExtendedModel best;
  best.design = d;
  best.basis = std::move(basis);
  best.mask = base;
  settle_weights(best);
  Mask ieee = candidates;  // the IEEE terms offered with the next addition
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    // Forward: one addition at a time while one lowers the criterion, two at once when none does.
    for (;;) {
      std::optional<ExtendedModel> next = add_one(s, best, ieee);
      if (!(next && next->criterion < best.criterion)) {
        next = add_two(s, best);
      }
      if (!(next && next->criterion < best.criterion)) break;
      best = std::move(*next);
      ieee = best.mask & kIeeeBits;
    }
    // Backward: a term the others now stand in for is dropped; then additions are tried again.
    std::optional<ExtendedModel> fewer = drop_one(s, best);
    if (!(fewer && fewer->criterion < best.criterion)) break;
    best = std::move(*fewer);
    ieee = best.mask & kIeeeBits;
  }
  return best;
}

}  // namespace sigmatau::detail
