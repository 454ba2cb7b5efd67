// Consistency guards: what a fit reports, checked against the curve it was fitted to
// (fit.hpp, Contradiction; docs/fit.md "Consistency guards").
//
// Glossary:
//   dev_j, nu_j, m_j   the fitted OADEV points, their EDF under the fit's model (model_edf)
//                      and averaging factor
//   hi_j, lo_j         the edges of dev_j's chi-squared interval at 1 - 0.05 / K (K fitted
//                      points: a family-wise 95 %, guard_point_level)
//   j*                 the point with the smallest dev (the curve's minimum)
//   A_t(m)             term t's exact sampled AVAR (noise_model.hpp, sampled_avar)
// Terms are independent, so their AVARs add: each kept term alone must stay at or below the
// curve (A_t(m_j) <= hi_j^2 at every fitted j), the flicker floor 0.664 B at or below the
// minimum (0.664 B <= hi_j*), and a model with B at its upper bound must reach the minimum
// (sum_t A_t(m_j*) + A_B(m_j*; B = bound) >= lo_j*^2), or the bound is below a floor the curve
// reaches. The exact sampled flicker AVAR exceeds its floor at short taus (2/pi against
// 2 ln2/pi per unit at m = 1), so the per-term check is the stricter one there and the floor
// check the one a data sheet reads.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fit_internal.hpp"
#include "sigmatau/confidence.hpp"
#include "sigmatau/display_units.hpp"
#include "sigmatau/units.hpp"

namespace sigmatau {

double guard_point_level(int points) {
  return 1 - (1 - kGuardLevel) / std::max(points, 1);
}

namespace detail {
namespace {

/// The EDF of each point's AVAR estimate under `fit`'s model: 2 A_j^2 / Var(s2_j), the variance
/// from the exact covariance of the estimates (oavar_covariance, the joint fit's own weights).
/// Not the curve's EDF: that follows the noise type identified at each point, which a
/// low-EDF point can misread (white noise alone, 20 min at 200 Hz: a point at 164 s read with an
/// interval a third as wide as its scatter, and a right N called contradicted). A point whose
/// model variance is not positive keeps the curve's EDF.
std::vector<double> model_edf(const ChannelFit& fit, const std::vector<AvarPoint>& points,
                              const CurveSource& source) {
  std::vector<double> edf;
  for (const auto& q : points) edf.push_back(q.edf);
  std::vector<std::int64_t> m;
  for (const auto& q : points) m.push_back(q.m);
  // A model without stochastic terms (a ramp or a sinusoid alone) has zero covariance: every
  // point then keeps the curve's EDF below.
  const NoiseTerms model = fit.noise_terms();
  const Eigen::MatrixXd cov = oavar_covariance(model, m, source.n_phase_points, source.tau0_s);
  const Sampling sampling{source.tau0_s, source.flicker_taps, false};
  for (std::size_t j = 0; j < points.size(); ++j) {
    const double var = cov(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(j));
    const double avar = sampled_avar(model, points[j].m, sampling);
    if (var > 0 && avar > 0 && std::isfinite(var)) edf[j] = 2 * avar * avar / var;
  }
  return edf;
}

}  // namespace

std::vector<Contradiction> check_against_curve(const ChannelFit& fit,
                                               const std::vector<AvarPoint>& points,
                                               std::size_t j_min, const CurveSource& source) {
  std::vector<Contradiction> out;
  if (points.empty()) return out;
  const Sampling sampling{source.tau0_s, source.flicker_taps, false};
  const NoiseTerms model = fit.noise_terms();
  const double level = guard_point_level(static_cast<int>(points.size()));
  const std::vector<double> edf = model_edf(fit, points, source);
  const auto interval = [&](std::size_t j) { return chi_squared_interval(points[j].dev, edf[j], level); };
  const AvarPoint& low_point = points[j_min];
  const Interval at_min = interval(j_min);

  bool floor_contradicted = false;
  for (const auto& p : fit.parameters) {
    if (p.term != NoiseTerm::bias_instability) continue;
    if ((p.in_model || p.from_model_floor) && kFlickerFloorFactor * p.value > at_min.high) {
      out.push_back({Contradiction::Kind::floor_above_minimum, p.term, low_point.tau_s,
                     kFlickerFloorFactor * p.value, low_point.dev, at_min.high});
      floor_contradicted = true;
    }
    if (!p.in_model && !p.from_model_floor && std::isfinite(p.upper_bound) && p.upper_bound >= 0) {
      NoiseTerms bounded;
      bounded.bias_instability = p.upper_bound;
      const double reach = std::sqrt(sampled_avar(model, low_point.m, sampling) +
                                     sampled_avar(bounded, low_point.m, sampling));
      if (reach < at_min.low) {
        out.push_back({Contradiction::Kind::bound_below_minimum, p.term, low_point.tau_s, reach,
                       low_point.dev, at_min.low});
      }
    }
  }
  // Each term alone, IEEE and added: its own exact sampled ADEV above the curve at a fitted tau.
  const auto check_term = [&](NoiseTerm term, const NoiseTerms& one) {
    double worst = 1;
    Contradiction c{Contradiction::Kind::term_above_curve, term, 0, 0, 0, 0};
    for (std::size_t j = 0; j < points.size(); ++j) {
      const double own = std::sqrt(sampled_avar(one, points[j].m, sampling));
      const double high = interval(j).high;
      if (own > worst * high) {
        worst = own / high;
        c = {Contradiction::Kind::term_above_curve, term, points[j].tau_s, own, points[j].dev, high};
      }
    }
    if (c.tau_s > 0) out.push_back(c);
  };
  for (const NoiseTerm term : fit.model_terms) {
    if (term == NoiseTerm::bias_instability && floor_contradicted) continue;
    check_term(term, only(model, term));
  }
  for (std::size_t g = 0; g < model.gauss_markov.size(); ++g) {
    check_term(NoiseTerm::gauss_markov, only_gauss_markov(model, g));
  }
  if (model.sinusoid) check_term(NoiseTerm::sinusoid, only(model, NoiseTerm::sinusoid));
  return out;
}

void lower_to_curve(ChannelFit& fit, const std::vector<AvarPoint>& points, const CurveSource& source) {
  const Sampling sampling{source.tau0_s, source.flicker_taps, false};
  const double level = guard_point_level(static_cast<int>(points.size()));
  // The intervals follow the model (model_edf), so a lowered term moves them a little: again
  // until nothing moves (two rounds on the real logs; 8 is a cap).
  for (int round = 0; round < 8; ++round) {
    const NoiseTerms model = fit.noise_terms();
    const std::vector<double> edf = model_edf(fit, points, source);
    bool lowered = false;
    for (auto& p : fit.parameters) {
      if (!p.in_model || p.term == NoiseTerm::bias_instability) continue;
      // Every term's sampled AVAR is its parameter squared times a function of m alone, so its
      // ADEV scales with the parameter.
      double factor = 1;
      for (std::size_t j = 0; j < points.size(); ++j) {
        const double own = std::sqrt(sampled_avar(model, p.term, points[j].m, sampling));
        const double high = chi_squared_interval(points[j].dev, edf[j], level).high;
        if (own > 0) factor = std::min(factor, high / own);
      }
      if (factor < 1) {
        // Just inside the edge: at the edge itself, rounding would leave it above.
        factor *= 1 - 1e-9;
        p.lowered_to_curve *= factor;
        p.value *= factor;
        p.ci_low *= factor;
        p.ci_high *= factor;
        p.upper_bound *= factor;
        lowered = true;
      }
    }
    if (!lowered) return;
  }
}

}  // namespace detail

std::string describe(const Contradiction& c, Sensor sensor) {
  const NoiseTerm rate_term = NoiseTerm::bias_instability;  // ADEVs are in the rate unit of B
  const std::string unit(display_unit(rate_term, sensor));
  const double f = convert(1.0, si_unit(rate_term, sensor), unit);
  const std::string symbol(term_symbol(c.term));
  char text[400];
  switch (c.kind) {
    case Contradiction::Kind::floor_above_minimum:
      std::snprintf(text, sizeof text,
                    "the flicker floor 0.664 B = %.4g %s lies above the curve's minimum %.4g %s at "
                    "tau = %.4g s (%.0f %% family-wise interval up to %.4g %s): no curve with that B reaches so low",
                    c.reported * f, unit.c_str(), c.curve * f, unit.c_str(), c.tau_s,
                    100 * kGuardLevel, c.curve_limit * f, unit.c_str());
      break;
    case Contradiction::Kind::bound_below_minimum:
      std::snprintf(text, sizeof text,
                    "the upper bound on B is below the floor the curve reaches: the model with B at "
                    "its bound gives %.4g %s at the curve's minimum, tau = %.4g s, where the curve "
                    "is %.4g %s (%.0f %% family-wise interval down to %.4g %s)",
                    c.reported * f, unit.c_str(), c.tau_s, c.curve * f, unit.c_str(),
                    100 * kGuardLevel, c.curve_limit * f, unit.c_str());
      break;
    case Contradiction::Kind::term_above_curve:
      std::snprintf(text, sizeof text,
                    "the %s term alone, %.4g %s at tau = %.4g s, lies above the curve's %.4g %s "
                    "there (%.0f %% family-wise interval up to %.4g %s): terms add, so none can exceed the curve",
                    symbol.c_str(), c.reported * f, unit.c_str(), c.tau_s, c.curve * f,
                    unit.c_str(), 100 * kGuardLevel, c.curve_limit * f, unit.c_str());
      break;
  }
  return text;
}

}  // namespace sigmatau
