// Noise fit: input checks, method dispatch and triad summaries.
// The numerics live in fit_joint.cpp (joint fit, selection), fit_slopes.cpp (read-outs) and
// fit_covariance.cpp (covariance of the OAVAR estimates).
#include "sigmatau/fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include "fit_internal.hpp"
#include "phase_store.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/sampling_limits.hpp"
#include "sigmatau/units.hpp"

namespace sigmatau {
namespace detail {

int term_index(NoiseTerm term) {
  for (std::size_t k = 0; k < kFitTerms.size(); ++k) {
    if (kFitTerms[k] == term) return static_cast<int>(k);
  }
  throw Error(std::string(to_string(term)) + " is not a term the fit models (Q, N, B, K, R)");
}

}  // namespace detail

std::string_view term_symbol(NoiseTerm term) {
  if (term == NoiseTerm::gauss_markov) return "GM";
  if (term == NoiseTerm::sinusoid) return "SIN";
  static constexpr std::string_view kSymbols[] = {"Q", "N", "B", "K", "R"};
  return kSymbols[detail::term_index(term)];
}

std::vector<NoiseTerm> parse_fit_terms(std::string_view text) {
  std::vector<NoiseTerm> terms;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t end = std::min(text.find(',', start), text.size());
    std::string_view item = text.substr(start, end - start);
    while (!item.empty() && item.front() == ' ') item.remove_prefix(1);
    while (!item.empty() && item.back() == ' ') item.remove_suffix(1);
    const auto it = std::find_if(kFitTerms.begin(), kFitTerms.end(),
                                 [&](NoiseTerm t) { return term_symbol(t) == item; });
    if (it == kFitTerms.end()) {
      throw Error("--terms \"" + std::string(text) + "\": unknown term \"" + std::string(item) +
                  "\" (expected a comma-separated list of Q, N, B, K, R)");
    }
    if (std::find(terms.begin(), terms.end(), *it) != terms.end()) {
      throw Error("--terms \"" + std::string(text) + "\": " + std::string(item) + " is repeated");
    }
    terms.push_back(*it);
    start = end + 1;
  }
  std::sort(terms.begin(), terms.end(),
            [](NoiseTerm a, NoiseTerm b) { return detail::term_index(a) < detail::term_index(b); });
  return terms;
}

FitMethod parse_fit_method(std::string_view text) {
  if (text == "joint") return FitMethod::joint;
  if (text == "slopes") return FitMethod::slopes;
  if (text == "both") return FitMethod::both;
  throw Error("--method must be joint, slopes or both, got \"" + std::string(text) + "\"");
}

std::string_view to_string(FitMethod method) {
  switch (method) {
    case FitMethod::joint: return "joint";
    case FitMethod::slopes: return "slopes";
    case FitMethod::both: return "both";
  }
  return "?";
}

const ParameterEstimate& ChannelFit::parameter(NoiseTerm term) const {
  for (const auto& p : parameters) {
    if (p.term == term) return p;
  }
  throw Error("fit has no parameter " + std::string(to_string(term)));
}

NoiseTerms ChannelFit::noise_terms() const {
  NoiseTerms t;
  for (const auto& p : parameters) {
    if (!p.in_model) continue;
    switch (p.term) {
      case NoiseTerm::quantization: t.quantization = p.value; break;
      case NoiseTerm::white: t.white = p.value; break;
      case NoiseTerm::bias_instability:
        t.bias_instability = p.from_model_floor ? p.flicker : p.value;
        break;
      case NoiseTerm::rate_random_walk: t.rate_random_walk = p.value; break;
      case NoiseTerm::rate_ramp: t.rate_ramp = p.value; break;
      default: break;
    }
  }
  for (const auto& g : gauss_markov) t.gauss_markov.push_back(GaussMarkov{g.sigma, g.tau_c_s});
  if (sinusoid) t.sinusoid = Sinusoid{sinusoid->amplitude, sinusoid->frequency_hz, 0.0};
  return t;
}

namespace {

/// The fit works with AVAR values and their covariances, fourth powers of the deviations: it
/// keeps every digit while the largest deviation is within about 1e-50..1e50 (measured: the
/// same chi-squared, p value and relative terms to 1e-15 from 1e-60 to 1e60; at 1e-100 the
/// covariance underflows, at 1e100 a wrong model is kept). Beyond, the curve is fitted divided by
/// a power of two (exact) and the terms multiplied back: every term is linear in the deviation.
constexpr double kFitUnscaledMin = 0x1p-166;
constexpr double kFitUnscaledMax = 0x1p166;

/// 1, or the power of two 2^floor(log2 d) of the largest usable deviation d beyond the range.
double fit_unit(const AllanCurve& curve) {
  double largest = 0.0;
  for (const auto& p : curve.points) {
    if (p.value.dev > 0 && std::isfinite(p.value.dev)) largest = std::max(largest, p.value.dev);
  }
  return detail::value_scale_for(largest, kFitUnscaledMin, kFitUnscaledMax);
}

/// The shortest-tau points a sensor's own filter bends (fit_noise). When the joint fit is
/// rejected and the point furthest from it in standard deviations is among the shortest fifth
/// of the taus, the
/// fit is repeated without the k shortest points, k = 1 .. a fifth of the points (at least 80 %
/// of the taus stay fitted), and the k whose relative model error (ChannelFit::model_error) is
/// smallest is kept if it is below kLeaveOutGain times the error with all points: leaving a
/// point out must describe the rest clearly better, not just drop a point. `fit` becomes the
/// fit of the points kept, which are returned.
constexpr double kLeaveOutGain = 0.8;

std::vector<detail::AvarPoint> leave_out_filtered_taus(ChannelFit& fit, const std::vector<detail::AvarPoint>& points,
                                                       const CurveSource& source, const FitOptions& options) {
  const std::size_t most = points.size() / 5;
  if (most == 0 || !(fit.p_value < kMisfitPValue) || !(fit.model_error > 0)) return points;
  // The point furthest from the model in its own standard deviations (ChannelFit::misfit_tau_s).
  if (!(fit.misfit_tau_s <= points[most - 1].tau_s * (1 + 1e-9))) return points;
  std::size_t best_k = 0;
  double best_error = fit.model_error;
  std::optional<ChannelFit> best_fit;
  for (std::size_t k = 1; k <= most && points.size() - k >= static_cast<std::size_t>(kMinFitPoints); ++k) {
    const std::vector<detail::AvarPoint> fewer(points.begin() + static_cast<std::ptrdiff_t>(k), points.end());
    ChannelFit next = detail::fit_joint(fewer, source, options);
    if (next.model_error < kLeaveOutGain * best_error) {
      best_k = k;
      best_error = next.model_error;
      best_fit = std::move(next);
    }
  }
  if (best_k == 0) return points;
  fit = std::move(*best_fit);
  for (std::size_t k = 0; k < best_k; ++k) fit.left_out_taus_s.push_back(points[k].tau_s);
  return {points.begin() + static_cast<std::ptrdiff_t>(best_k), points.end()};
}

void multiply_terms(std::optional<ChannelFit>& fit, double unit) {
  if (!fit) return;
  for (ParameterEstimate& p : fit->parameters) {
    p.value *= unit;
    p.ci_low *= unit;
    p.ci_high *= unit;
    p.upper_bound *= unit;
    p.adev_min *= unit;
    p.flicker *= unit;
  }
  for (GaussMarkovEstimate& g : fit->gauss_markov) {
    g.sigma *= unit;
    g.ci_low *= unit;
    g.ci_high *= unit;
  }
  if (fit->sinusoid) {
    fit->sinusoid->amplitude *= unit;
    fit->sinusoid->ci_low *= unit;
    fit->sinusoid->ci_high *= unit;
  }
  for (Contradiction& c : fit->contradictions) {  // deviations, as the terms
    c.reported *= unit;
    c.curve *= unit;
    c.curve_limit *= unit;
  }
}

}  // namespace

NoiseFit fit_noise(const AllanCurve& curve, const CurveSource& source, const FitOptions& options) {
  if (const double unit = fit_unit(curve); unit != 1.0) {
    AllanCurve divided = curve;
    for (auto& p : divided.points) {
      p.value.dev /= unit;
      p.confidence.interval.low /= unit;
      p.confidence.interval.high /= unit;
    }
    NoiseFit fit = fit_noise(divided, source, options);
    multiply_terms(fit.joint, unit);
    multiply_terms(fit.slopes, unit);
    multiply_terms(fit.readings, unit);
    return fit;
  }
  if (curve.statistic != Statistic::oadev) {
    throw Error("fit needs an OADEV curve, got " + std::string(to_string(curve.statistic)) +
                " (rerun adev with --stat oadev)");
  }
  checked_interval_s(source.tau0_s, "fit: sample interval tau0_s");
  if (!(source.n_phase_points >= 3)) throw Error("fit: the log has fewer than 2 samples");
  if (!(options.confidence_level > 0 && options.confidence_level < 1)) {
    throw Error("--ci: confidence level must be in (0, 1), got " +
                std::to_string(options.confidence_level));
  }
  check_tau_range(options.tau_min_s, options.tau_max_s);
  for (const auto t : options.terms) detail::term_index(t);
  for (const auto t : options.candidates) detail::term_index(t);
  if (options.terms.empty() && options.candidates.empty()) throw Error("fit: no candidate terms");

  std::vector<detail::AvarPoint> points;
  for (const auto& p : curve.points) {
    const double dev = p.value.dev;
    if (!(dev > 0) || !std::isfinite(dev)) continue;
    if (!(p.value.m >= 1) || source.n_phase_points - 2 * p.value.m < 1) continue;
    const double tau = static_cast<double>(p.value.m) * source.tau0_s;
    if (!(std::abs(p.value.tau_s - tau) <= 1e-6 * tau)) {
      throw Error("fit: point tau = " + std::to_string(p.value.tau_s) + " s is not m tau0 = " +
                  std::to_string(tau) + " s (is the sample rate right?)");
    }
    if (tau < options.tau_min_s * (1 - 1e-9) || tau > options.tau_max_s * (1 + 1e-9)) continue;
    detail::AvarPoint q;
    q.m = p.value.m;
    q.tau_s = tau;
    q.dev = dev;
    q.avar = dev * dev;
    q.alpha = p.confidence.noise.alpha;
    q.edf = p.confidence.edf;
    if (!(q.edf > 0) || !std::isfinite(q.edf)) {
      // IEEE 952 rule of thumb: relative error 1/sqrt(2 (N/m - 1)), i.e. nu = N/m - 1.
      q.edf = std::max(1.0, static_cast<double>(source.n_phase_points) / static_cast<double>(q.m) - 1);
    }
    points.push_back(q);
  }
  const int needed = std::max<int>(kMinFitPoints, static_cast<int>(options.terms.size()) + 1);
  if (static_cast<int>(points.size()) < needed) {
    throw Error("fit: " + std::to_string(points.size()) + " usable OADEV points" +
                (options.tau_min_s > 0 || std::isfinite(options.tau_max_s) ? " in the tau range" : "") +
                ", need at least " + std::to_string(needed) +
                " (a longer log, a wider tau range, or a tau grid with more points)");
  }
  std::sort(points.begin(), points.end(),
            [](const detail::AvarPoint& a, const detail::AvarPoint& b) { return a.m < b.m; });
  points.erase(std::unique(points.begin(), points.end(),
                           [](const detail::AvarPoint& a, const detail::AvarPoint& b) { return a.m == b.m; }),
               points.end());

  // The curve's smallest ADEV: its tau and value are reported with B by both methods, and the
  // slope read-outs take B from it.
  std::size_t j_min = 0;
  for (std::size_t j = 1; j < points.size(); ++j) {
    if (points[j].dev < points[j_min].dev) j_min = j;
  }
  NoiseFit fit;
  // The points the joint fit describes: all, or all but the shortest taus a sensor's own
  // filter bends away from every noise term (leave_out_filtered_taus).
  std::vector<detail::AvarPoint> joint_points = points;
  if (options.method != FitMethod::slopes) {
    fit.joint = detail::fit_joint(points, source, options);
    if (options.terms.empty() && options.added_terms) {
      joint_points = leave_out_filtered_taus(*fit.joint, points, source, options);
    }
  }
  if (options.method != FitMethod::joint) {
    fit.slopes = detail::fit_slopes(points, source, options, j_min);
  }
  // A joint fit that is rejected or contradicts its curve is kept, but the curve's own
  // read-outs stand in for it in what is reported (NoiseFit::reported).
  if (fit.joint) {
    std::size_t j_min_joint = 0;
    for (std::size_t j = 1; j < joint_points.size(); ++j) {
      if (joint_points[j].dev < joint_points[j_min_joint].dev) j_min_joint = j;
    }
    fit.joint->contradictions = detail::check_against_curve(*fit.joint, joint_points, j_min_joint, source);
    const bool rejected = fit.joint->p_value < kMisfitPValue;
    if (rejected || !fit.joint->contradictions.empty()) {
      fit.readings = detail::fit_slopes(points, source, options, j_min);
      detail::lower_to_curve(*fit.readings, points, source);
      char p_text[64];
      std::snprintf(p_text, sizeof p_text, "rejected (p = %.2g)", fit.joint->p_value);
      if (rejected) fit.readings_reason = p_text;
      if (!fit.joint->contradictions.empty()) {
        fit.readings_reason += std::string(rejected ? " and " : "") + "contradicted by the curve";
      }
    }
  }
  for (auto* method : {&fit.joint, &fit.slopes, &fit.readings}) {
    if (!*method) continue;
    for (auto& p : (*method)->parameters) {
      if (p.term != NoiseTerm::bias_instability) continue;
      p.tau_min_s = points[j_min].tau_s;
      p.adev_min = points[j_min].dev;
    }
  }
  for (auto* method : {&fit.slopes, &fit.readings}) {
    if (*method) (*method)->contradictions = detail::check_against_curve(**method, points, j_min, source);
  }
  return fit;
}

const ChannelFit& NoiseFit::reported() const {
  if (readings) return *readings;
  if (joint) return *joint;
  if (slopes) return *slopes;
  throw Error("noise fit holds no result");
}

std::vector<double> model_deviation(const ChannelFit& fit, const AllanCurve& curve,
                                    const CurveSource& source, const FitOptions& options) {
  const Sampling sampling{source.tau0_s, source.flicker_taps, false};
  const NoiseTerms model = fit.noise_terms();  // added terms included
  std::vector<double> out;
  out.reserve(curve.points.size());
  for (const auto& p : curve.points) {
    // The same selection as fit_noise's.
    const double tau = static_cast<double>(p.value.m) * source.tau0_s;
    const bool left_out = std::any_of(fit.left_out_taus_s.begin(), fit.left_out_taus_s.end(),
                                      [&](double t) { return std::abs(t - tau) <= 1e-9 * tau; });
    const bool used = p.value.dev > 0 && std::isfinite(p.value.dev) && p.value.m >= 1 &&
                      source.n_phase_points - 2 * p.value.m >= 1 && !left_out &&
                      tau >= options.tau_min_s * (1 - 1e-9) && tau <= options.tau_max_s * (1 + 1e-9);
    if (!used) {
      out.push_back(std::numeric_limits<double>::quiet_NaN());
      continue;
    }
    out.push_back(std::sqrt(sampled_avar(model, p.value.m, sampling)));
  }
  return out;
}

void check_tau_range(double tau_min_s, double tau_max_s) {
  if (!(tau_min_s >= 0) || !(tau_max_s > tau_min_s)) {
    throw Error("--tau-min / --tau-max: expected 0 <= tau-min < tau-max [s], got " +
                std::to_string(tau_min_s) + " and " + std::to_string(tau_max_s));
  }
}

std::string misfit_warning(const ChannelFit& fit, const std::string& channel) {
  if (!(fit.p_value < kMisfitPValue)) return "";
  char text[500];
  std::snprintf(text, sizeof text,
                "%s: no model of these noise terms describes the curve (chi-squared %.4g for %d "
                "degrees of freedom, p = %.2g), furthest at tau = %.4g s: the terms, their "
                "intervals and any verdict from them are not to be trusted. %s",
                channel.c_str(), fit.chi_squared, fit.dof, fit.p_value, fit.misfit_tau_s,
                fit.misfit_at_shortest_taus
                    ? "If the sensor filters its output, fit from longer taus (--tau-min)"
                    : "Something outside Q, N, B, K, R (a Gauss-Markov bump, a sinusoid, "
                      "outliers, a temperature drift) shapes the curve there: look at the plot, "
                      "and fit a tau range without it (--tau-min / --tau-max)");
  return text;
}

std::string left_out_warning(const ChannelFit& fit, const std::string& channel) {
  if (fit.left_out_taus_s.empty()) return "";
  std::string taus;
  for (const double t : fit.left_out_taus_s) {
    char one[40];
    std::snprintf(one, sizeof one, "%s%.4g", taus.empty() ? "" : ", ", t);
    taus += one;
  }
  return channel + ": the joint fit leaves out the shortest taus (" + taus +
         " s): the sensor's own filter (or its sampling) bends them away from every noise term, "
         "and the model describes the other taus better without them";
}

std::string readings_warning(const NoiseFit& fit, const std::string& channel, Sensor sensor) {
  if (!fit.readings || !fit.joint) return "";
  std::string text = channel + ": the joint fit is " + fit.readings_reason;
  for (std::size_t i = 0; i < fit.joint->contradictions.size(); ++i) {
    text += (i == 0 ? ": " : "; ") + describe(fit.joint->contradictions[i], sensor);
  }
  text += ". Reported instead (values, verdicts, filter files): the curve's own read-outs, IEEE 952: "
          "bias stability from the curve's minimum, N from the -1/2 line at 1 s, K from the +1/2 "
          "line at 3 s";
  for (const auto& p : fit.readings->parameters) {
    if (!p.in_model || !(p.lowered_to_curve < 1)) continue;
    char lowered[200];
    std::snprintf(lowered, sizeof lowered,
                  "; %s lowered to %.3g times its fitted line, to the line that touches the curve "
                  "(the fitted line crossed it)",
                  std::string(term_symbol(p.term)).c_str(), p.lowered_to_curve);
    text += lowered;
  }
  for (const auto& c : fit.readings->contradictions) text += "; the read-outs too: " + describe(c, sensor);
  return text;
}

bool rise_without_floor(const ChannelFit& fit) {
  if (fit.method != FitMethod::joint) return false;
  bool rise = false;
  for (const auto& p : fit.parameters) {
    if (p.term == NoiseTerm::bias_instability && p.in_model && p.leading_points > 0) return false;
    if ((p.term == NoiseTerm::rate_random_walk || p.term == NoiseTerm::rate_ramp) && p.in_model &&
        p.leading_points <= kShortLogRisePoints) {
      rise = true;
    }
  }
  return rise;
}

std::string short_log_warning(const ChannelFit& fit, const std::string& channel) {
  if (!rise_without_floor(fit)) return "";
  std::string kept;
  for (const auto t : fit.model_terms) {
    if (t == NoiseTerm::rate_random_walk || t == NoiseTerm::rate_ramp) {
      kept += (kept.empty() ? "" : " and ") + std::string(term_symbol(t));
    }
  }
  char text[800];
  std::snprintf(text, sizeof text,
                "%s: %s is kept where the curve shows no bias-instability floor before it rises, "
                "as on a log too short to show both: the rise is not told apart from B, so %s is "
                "likely too large and its interval too narrow (simulated N = 0.2 deg/sqrt(h), B = 4 "
                "deg/h, K = 20 deg/h/sqrt(h): such a K was a median %.1fx the truth on 5-minute logs "
                "and its 95 %% interval held the truth in %.0f %% of them; on 30-minute logs %.1fx "
                "and %.0f %%; bench/results_fit_short_logs.md). A longer log tells them apart",
                channel.c_str(), kept.c_str(), kept.c_str(), kRiseWithoutFloorRatio5min,
                100 * kRiseWithoutFloorCoverage5min, kRiseWithoutFloorRatio30min,
                100 * kRiseWithoutFloorCoverage30min);
  return text;
}

std::vector<TriadSummary> summarise_triads(const std::vector<std::string>& names,
                                           const std::vector<Sensor>& sensors,
                                           const std::vector<const ChannelFit*>& fits) {
  std::vector<TriadSummary> out;
  for (const Sensor sensor : {Sensor::gyro, Sensor::accel}) {
    TriadSummary s;
    s.sensor = sensor;
    std::vector<std::size_t> members;
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (sensors[i] == sensor && fits[i] != nullptr) members.push_back(i);
    }
    if (members.size() < 2) continue;
    for (const auto i : members) s.channels.push_back(names[i]);
    for (const NoiseTerm term : kFitTerms) {
      TriadSummary::Entry e{term, 0, 0, 0, {}};
      double sum = 0;
      for (const auto i : members) {
        const auto& p = fits[i]->parameter(term);
        if (!p.in_model) continue;
        ++e.channels_in_model;
        sum += p.value;
        if (e.worst_channel.empty() || p.value > e.worst) {
          e.worst = p.value;
          e.worst_channel = names[i];
        }
      }
      if (e.channels_in_model == 0) continue;
      e.mean = sum / e.channels_in_model;
      s.entries.push_back(e);
    }
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace sigmatau
