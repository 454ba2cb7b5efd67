// IEEE 952 / 1293 slope read-outs, with lines fitted over the taus where the slope holds.
//
// Glossary:
//   dev_j, tau_j, nu_j   OADEV point, its tau [s] and EDF;  alpha_j its identified noise
//   s, tau_r, c          the term's ADEV slope, read-off tau and coefficient (noise_model read_off)
//   J                    the points where the term's slope holds: the longest run of
//                        consecutive points identified alpha 2 or 1 (Q, ADEV slope -1; the run
//                        from the first tau only), 0 (N,
//                        -1/2), -1 (B, 0), -2 (K, +1/2); R (+1): alpha -2 points whose local
//                        ADEV slope exceeds kRampSlope
// A slope holds over a range of tau, so J is one run: noise identification at a low-EDF point
// can call a point of another region white or random walk, and such a stray point far from
// the term's region (MEMS gyro seed 1001 y: the random-walk points at 655 and 1311 s called
// white, read on the -1/2 line) moved N by +50-65 % in about half the MEMS channels
// (bench_fit_accuracy, exploration seeds 1001-1030).
// Line with fixed slope in log-log (AVLR, THEORY.md section 7), each point weighted by its EDF
// (var(log dev_j) ~ 1/(2 nu_j)):
//   log(c value) = sum_J w_j [log dev_j - s log(tau_j / tau_r)],  w_j = nu_j / sum_J nu
// B is the IEEE flat minimum: min_j dev_j / 0.664, reported with the tau where it occurs.
// Uncertainty: adjacent octave points are strongly correlated, so the line's log-sd is taken as
// the weighted mean of the points' log-sds sqrt(1 / (2 nu_j)) (full correlation: conservative).
// Absent terms: each term's AVAR is at most the total, so value <= dev_j / line_j(1) at every
// point; the bound is the smallest over j of the points' one-sided upper confidence limits.
#include <boost/math/distributions/normal.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "fit_internal.hpp"
#include "sigmatau/confidence.hpp"

namespace sigmatau::detail {
namespace {

/// Local ADEV slope above which a random-walk-identified point is read as the ramp's +1 line
/// (halfway between +1/2 and +1).
constexpr double kRampSlope = 0.75;

bool on_line(NoiseTerm term, const std::vector<AvarPoint>& p, std::size_t j) {
  const int a = p[j].alpha;
  const auto local_slope = [&] {
    if (p.size() < 2) return 0.0;
    const std::size_t lo = j == 0 ? 0 : j - 1;
    const std::size_t hi = j + 1 < p.size() ? j + 1 : j;
    if (hi == lo) return 0.0;
    return std::log(p[hi].dev / p[lo].dev) / std::log(p[hi].tau_s / p[lo].tau_s);
  };
  switch (term) {
    case NoiseTerm::quantization: return a >= 1;
    case NoiseTerm::white: return a == 0;
    case NoiseTerm::bias_instability: return a == -1;
    case NoiseTerm::rate_random_walk: return a == -2 && local_slope() <= kRampSlope;
    case NoiseTerm::rate_ramp: return a == -2 && local_slope() > kRampSlope;
    default: return false;
  }
}

/// The longest run of consecutive indices in `on` (ascending). On a tie, the run at the end of
/// the curve where the term lives: the last for the large-tau terms (K, R), the first otherwise.
/// Quantization's AVAR (3 Q^2 / tau^2) falls fastest of all terms, so where it dominates
/// anywhere it dominates at the first tau: Q's run is the one that starts there, or none (a
/// lone white-PM point mid-curve read Q 50x too large on a real HiPNUC gyro).
std::vector<std::size_t> longest_run(const std::vector<std::size_t>& on, NoiseTerm term) {
  if (term == NoiseTerm::quantization) {
    std::size_t end = 0;
    while (end < on.size() && on[end] == end) ++end;
    return {on.begin(), on.begin() + static_cast<std::ptrdiff_t>(end)};
  }
  const bool prefer_last = term == NoiseTerm::rate_random_walk || term == NoiseTerm::rate_ramp;
  std::size_t best_start = 0, best_length = 0;
  for (std::size_t start = 0; start < on.size();) {
    std::size_t end = start + 1;
    while (end < on.size() && on[end] == on[end - 1] + 1) ++end;
    if (end - start > best_length || (prefer_last && end - start == best_length)) {
      best_start = start;
      best_length = end - start;
    }
    start = end;
  }
  return {on.begin() + static_cast<std::ptrdiff_t>(best_start),
          on.begin() + static_cast<std::ptrdiff_t>(best_start + best_length)};
}

}  // namespace

ChannelFit fit_slopes(const std::vector<AvarPoint>& points, const CurveSource& /*source*/,
                      const FitOptions& options, std::size_t j_min) {
  const double level = options.confidence_level;
  const double z = boost::math::quantile(boost::math::normal_distribution<double>(), (1 + level) / 2);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const bool forced = !options.terms.empty();

  ChannelFit out;
  out.method = FitMethod::slopes;
  out.points = static_cast<int>(points.size());
  out.chi_squared = nan;
  out.bic = nan;
  for (const NoiseTerm term : kFitTerms) {
    ParameterEstimate p;
    p.term = term;
    p.edf = nan;
    std::vector<std::size_t> on;
    for (std::size_t j = 0; j < points.size(); ++j) {
      if (on_line(term, points, j)) on.push_back(j);
    }
    on = longest_run(on, term);
    const bool wanted = forced ? std::find(options.terms.begin(), options.terms.end(), term) !=
                                     options.terms.end()
                               : !on.empty();
    // Upper bound from every point (valid whatever the model).
    double bound = std::numeric_limits<double>::infinity();
    for (const auto& q : points) {
      const double high = chi_squared_interval(q.dev, q.edf, std::max(2 * level - 1, 1e-6)).high;
      bound = std::min(bound, high / adev_line(term, 1.0, q.tau_s));
    }
    p.upper_bound = bound;
    if (wanted && term == NoiseTerm::bias_instability) {
      const auto& q = points[j_min];
      const Interval ci = chi_squared_interval(q.dev, q.edf, level);
      p.in_model = true;
      p.value = q.dev / kFlickerFloorFactor;
      p.ci_low = ci.low / kFlickerFloorFactor;
      p.ci_high = ci.high / kFlickerFloorFactor;
      p.edf = q.edf;
      p.leading_points = 1;
    } else if (wanted && !on.empty()) {
      const ReadOff r = read_off(term);
      double mean_log = 0, mean_sd = 0, edf = 0;
      for (const auto j : on) {
        const double w = points[j].edf;
        mean_log += w * (std::log(points[j].dev) - r.slope * std::log(points[j].tau_s / r.tau_read_s));
        mean_sd += w * std::sqrt(1 / (2 * points[j].edf));
        edf += w;
      }
      mean_log /= edf;
      mean_sd /= edf;
      p.in_model = true;
      p.value = std::exp(mean_log) / r.coefficient;
      p.ci_low = p.value * std::exp(-z * mean_sd);
      p.ci_high = p.value * std::exp(z * mean_sd);
      p.edf = edf;
      p.leading_points = static_cast<int>(on.size());
    } else if (wanted) {
      // Forced but no point shows the slope: nothing to read; report the bound only.
      p.in_model = false;
    }
    if (p.in_model) {
      out.model_terms.push_back(term);
      p.upper_bound = p.ci_high;
    }
    out.parameters.push_back(p);
  }
  return out;
}

}  // namespace sigmatau::detail
