// Continuous-time noise terms -> discrete-time covariances at a filter rate, with the arithmetic.
//
// Glossary (SI, "unit" = rad/s for a gyro, m/s^2 for an accelerometer):
//   f_s   filter / sample rate [Hz], T_s = 1/f_s [s]
//   ND    printed noise density [unit/sqrt(Hz)]; N white-noise density (Allan / Kalibr) [same]
//   B     flicker coefficient (NoiseTerms::bias_instability) [unit]; B_ds = 0.664 B the printed
//         in-run bias stability (ADEV floor)
//   K     rate random walk [unit/s/sqrt(Hz) = unit/sqrt(s)]
//   T_ref time after which a random walk reaches B_ds [s]; tau_min the tau of the ADEV minimum
//   phi   GM transition exp(-T_s/T_c); q GM per-step variance sigma^2 (1 - phi^2)
//   F     inflation factor (densities and sigmas x F, variances x F^2)
#include "sigmatau/convert.hpp"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

#include "sigmatau/display_units.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/sampling_limits.hpp"
#include "sigmatau/units.hpp"

namespace sigmatau {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;
/// Tolerance for "symmetric with unit diagonal" of a correlation matrix (round-off of values
/// typed with a few digits is far larger than this is strict).
constexpr double kCorrelationTolerance = 1e-9;

std::string num(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

/// The sensor's sample unit (the glossary's "unit"), in which sigmas and variances per sample
/// are printed.
std::string rate_unit(Sensor s) { return s == Sensor::gyro ? "rad/s" : "m/s^2"; }
/// SI units of N and K (display_units.hpp).
std::string density_unit(Sensor s) { return std::string(si_unit(NoiseTerm::white, s)); }
std::string rw_unit(Sensor s) { return std::string(si_unit(NoiseTerm::rate_random_walk, s)); }

/// " (= X deg/s)" for gyro values, "" for accelerometers: the numbers users know.
std::string in_deg(Sensor s, double value_si, const char* unit, int power = 1) {
  if (s != Sensor::gyro) return "";
  return " (= " + num(value_si * std::pow(kRadToDeg, power)) + " " + unit + ")";
}

void check_correlation(const Eigen::Matrix3d& c, const char* what) {
  for (int i = 0; i < 3; ++i) {
    if (!(std::abs(c(i, i) - 1) <= kCorrelationTolerance)) {
      throw Error(std::string(what) + " correlation: found diagonal " + num(c(i, i)) +
                  ", expected 1");
    }
    for (int j = 0; j < 3; ++j) {
      if (!(std::abs(c(i, j) - c(j, i)) <= kCorrelationTolerance) || !(std::abs(c(i, j)) <= 1)) {
        throw Error(std::string(what) +
                    " correlation: expected a symmetric matrix with entries in [-1, 1]");
      }
    }
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(c);
  if (!(solver.eigenvalues().minCoeff() >= -kCorrelationTolerance)) {
    throw Error(std::string(what) + " correlation: expected a positive semi-definite matrix");
  }
}

void check_options(const ConvertOptions& o) {
  checked_rate_hz(o.rate_hz, "rate_hz");
  checked_time_s(o.t_ref_s, "t_ref_s");
  if (o.tau_min_s) checked_time_s(*o.tau_min_s, "tau_min_s");
  if (!(o.inflate > 0) || !std::isfinite(o.inflate)) {
    throw Error("inflation factor: found " + num(o.inflate) + ", expected a factor > 0");
  }
}

Eigen::Matrix3d scaled(const Eigen::Vector3d& sigma, const Eigen::Matrix3d& correlation) {
  return sigma.asDiagonal() * correlation * sigma.asDiagonal();
}

bool uniform(const Eigen::Vector3d& v) { return v(0) == v(1) && v(1) == v(2); }

/// "95 %", "68.3 %" for a level in (0, 1); "" when unknown (0).
std::string level_text(double confidence) {
  if (!(confidence > 0 && confidence < 1)) return "";
  char text[32];
  std::snprintf(text, sizeof text, "%.4g %% ", 100 * confidence);
  return text;
}

/// "axis y" / "axes x, z" for the flagged axes; "" when none.
std::string axes_text(const std::array<bool, 3>& flagged) {
  std::string list;
  int count = 0;
  for (int a = 0; a < 3; ++a) {
    if (!flagged[static_cast<std::size_t>(a)]) continue;
    list += std::string(count++ ? ", " : "") + static_cast<char>('x' + a);
  }
  return count == 0 ? "" : (count == 1 ? "axis " : "axes ") + list;
}

/// What the bias written rests on when a fit's upper bound stands in for a term it did not
/// detect: only the term the bias is made from (K for a random walk from K, B for one from a
/// bias stability or a Gauss-Markov), at its level. "" when that term is measured everywhere.
std::string bound_text(const TriadNoise& triad, BiasSource source) {
  if (source == BiasSource::gauss_markov) return "";
  const bool k = source == BiasSource::rate_random_walk;
  const std::string term = k ? "K" : "B";
  const std::string level = level_text(triad.bound_confidence);
  if (triad.no_bias_term_detected) {
    return std::string("neither B nor K detected on any axis: ") + term + "'s " + level +
           "upper bound used on every axis" +
           (k ? " (B's bound plays no part in a random walk from K)"
              : " (K's bound plays no part here)");
  }
  const std::string axes =
      axes_text(k ? triad.rate_random_walk_is_bound : triad.bias_instability_is_bound);
  if (axes.empty()) return "";
  return term + " on " + axes + ": not detected, its " + level + "upper bound used";
}

/// sum over the entries of 2 sigma_i^2 / T_c_i: the short-term (tau << T_c) random-walk K^2 of
/// a sum of independent Gauss-Markov processes.
double gauss_markov_random_walk_k2(const std::vector<GaussMarkov>& gms) {
  double k2 = 0;
  for (const GaussMarkov& gm : gms) k2 += 2 * gm.sigma * gm.sigma / gm.tau_c_s;
  return k2;
}

/// The entry a one-state Gauss-Markov bias carries: the largest sigma, i.e. the largest ADEV
/// peak 0.6174 sigma (the bump that sets the curve's bias-stability region); a tie goes to the
/// longer T_c (the slower drift the bias state is there to track).
std::size_t dominant_gauss_markov(const std::vector<GaussMarkov>& gms) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < gms.size(); ++i) {
    if (gms[i].sigma > gms[best].sigma ||
        (gms[i].sigma == gms[best].sigma && gms[i].tau_c_s > gms[best].tau_c_s))
      best = i;
  }
  return best;
}

/// "sigma 1e-4 rad/s, T_c 100 s; sigma 3e-5 rad/s, T_c 2000 s"
std::string gauss_markov_list(const std::vector<GaussMarkov>& gms, const std::string& unit) {
  std::string out;
  for (const GaussMarkov& gm : gms)
    out += (out.empty() ? "" : "; ") + std::string("sigma ") + num(gm.sigma) + " " + unit +
           ", T_c " + num(gm.tau_c_s) + " s";
  return out;
}

/// TriadDiscrete::gauss_markov_note for a bias from Gauss-Markov entries ("" when every axis
/// has one entry). Axes with the same entries share one sentence.
std::string gauss_markov_sum_note(const TriadNoise& triad, BiasModel model) {
  const std::string sensor(to_string(triad.sensor));
  const std::string u = rate_unit(triad.sensor);
  std::string note;
  for (int i = 0; i < 3; ++i) {
    const auto& gms = triad.axes[static_cast<std::size_t>(i)].gauss_markov;
    if (gms.size() < 2) continue;
    bool seen = false;
    for (int j = 0; j < i; ++j)
      seen = seen || triad.axes[static_cast<std::size_t>(j)].gauss_markov == gms;
    if (seen) continue;
    std::string axes;
    for (int j = i; j < 3; ++j)
      if (triad.axes[static_cast<std::size_t>(j)].gauss_markov == gms)
        axes += std::string(axes.empty() ? "" : ",") + static_cast<char>('x' + j);
    std::string text = sensor + " bias on " + axes + ": a sum of " + std::to_string(gms.size()) +
                       " Gauss-Markov processes (" + gauss_markov_list(gms, u) + "); ";
    if (model == BiasModel::gauss_markov) {
      const std::size_t d = dominant_gauss_markov(gms);
      double left_out = 0, total = 0;
      for (std::size_t e = 0; e < gms.size(); ++e) {
        total += gms[e].sigma * gms[e].sigma;
        if (e != d) left_out += gms[e].sigma * gms[e].sigma;
      }
      char share[32];
      std::snprintf(share, sizeof share, "%.3g", 100 * left_out / total);
      text += "one filter bias state carries one process: the entry with the largest sigma "
              "(largest ADEV peak 0.6174 sigma at 1.892 T_c) is written (sigma " +
              num(gms[d].sigma) + " " + u + ", T_c " + num(gms[d].tau_c_s) +
              " s); the others are left out (" + share +
              " % of the stationary bias variance): add a state per process to carry them";
    } else {
      text += "the random walk written has K^2 = sum 2 sigma_i^2/T_c_i (the entries' short-term "
              "slopes add), which holds for tau well below the shortest T_c and overstates the "
              "drift beyond it";
    }
    note += (note.empty() ? "" : "; ") + text;
  }
  return note;
}

}  // namespace

std::string_view to_string(DensityConvention convention) {
  return convention == DensityConvention::two_sided ? "two-sided" : "one-sided";
}

DensityConvention parse_density_convention(std::string_view text) {
  if (text == "two-sided") return DensityConvention::two_sided;
  if (text == "one-sided") return DensityConvention::one_sided;
  throw Error("density convention: found \"" + std::string(text) +
              "\", expected two-sided or one-sided");
}

std::string_view to_string(BiasModel model) {
  return model == BiasModel::random_walk ? "rw" : "gm";
}

BiasModel parse_bias_model(std::string_view text) {
  if (text == "rw" || text == "random-walk") return BiasModel::random_walk;
  if (text == "gm" || text == "gauss-markov") return BiasModel::gauss_markov;
  throw Error("bias model: found \"" + std::string(text) + "\", expected rw or gm");
}

std::string_view to_string(BiasSource source) {
  switch (source) {
    case BiasSource::rate_random_walk: return "rate_random_walk";
    case BiasSource::bias_stability: return "bias_stability";
    case BiasSource::gauss_markov: return "gauss_markov";
  }
  return "?";
}

const TriadDiscrete* DiscreteNoise::triad(Sensor sensor) const {
  const auto& t = sensor == Sensor::gyro ? gyro : accel;
  return t ? &*t : nullptr;
}

TriadNoise uniform_triad(Sensor sensor, const NoiseTerms& terms) {
  TriadNoise t;
  t.sensor = sensor;
  t.axes = {terms, terms, terms};
  return t;
}

void replace_with_typed_terms(std::vector<TriadNoise>& triads, Sensor sensor,
                              const NoiseTerms& typed, const std::string& white_origin,
                              const std::string& bias_origin) {
  auto it = std::find_if(triads.begin(), triads.end(),
                         [&](const TriadNoise& t) { return t.sensor == sensor; });
  if (it == triads.end()) {
    triads.push_back(uniform_triad(sensor, NoiseTerms{}));
    it = triads.end() - 1;
  }
  TriadNoise& t = *it;
  if (typed.white) {
    const bool had = t.axes[0].white.has_value();
    for (auto& a : t.axes) a.white = typed.white;
    t.white_origin = white_origin + (had ? " (typed; replaces the source's)" : " (typed)");
  }
  if (typed.bias_instability || typed.rate_random_walk) {
    bool had = false;
    for (auto& a : t.axes) {
      had = had || a.bias_instability || a.rate_random_walk || !a.gauss_markov.empty();
      a.bias_instability = typed.bias_instability;
      a.rate_random_walk = typed.rate_random_walk;
      a.gauss_markov.clear();
    }
    // The fit's upper bounds stood in for terms it did not detect: the typed terms replace them.
    t.bias_from_upper_bound = false;
    t.bias_instability_is_bound = {};
    t.rate_random_walk_is_bound = {};
    t.no_bias_term_detected = false;
    t.rate_random_walk_bound.reset();
    t.bias_origin = bias_origin + (had ? " (typed; replaces the source's bias)" : " (typed)");
  }
}

TriadNoise triad_from_data_sheet(const DataSheet& sheet, Sensor sensor,
                                 DensityConvention convention) {
  const SensorSheet* section = sheet.sensor(sensor);
  if (!section) {
    throw Error("data sheet " + sheet.name + " has no " + std::string(to_string(sensor)) +
                " section");
  }
  TriadNoise triad;
  triad.sensor = sensor;
  const auto describe = [](const SpecValue& v) {
    const PrintedValue* p = v.nominal();
    std::string which = v.typ && p == &*v.typ ? "typ" : (v.max && p == &*v.max ? "max" : "min");
    return p->text + " (" + which + ")";
  };
  // "160 µg/√Hz (typ), 190 µg/√Hz (typ) on z" where the sheet prints an axis apart.
  const auto describe_axes = [&](const SpecValue& v) {
    std::string text = describe(v);
    for (const AxisValue& a : v.axes) {
      const SpecValue on_axis = v.for_axis(a.axis);
      if (on_axis.nominal()) text += ", " + describe(on_axis) + " on " + a.axis;
    }
    return text;
  };
  const SpecValue* arw = section->find(SpecField::random_walk);
  const SpecValue* nd = section->find(SpecField::noise_density);
  const SpecValue* bi = section->find(SpecField::bias_instability);
  const SpecValue* rrw = section->find(SpecField::rate_random_walk);
  // The value a filter model takes for one axis (the axis's own where the sheet prints it
  // apart), in SI; nullopt when the entry is absent or has none.
  const auto on_axis = [](const SpecValue* v, std::string_view axis) -> std::optional<double> {
    if (!v) return std::nullopt;
    const SpecValue value = v->for_axis(axis);
    if (!value.nominal()) return std::nullopt;
    return value.nominal()->value_si;
  };
  static constexpr std::array<std::string_view, 3> kAxes = {"x", "y", "z"};
  for (std::size_t i = 0; i < kAxes.size(); ++i) {
    NoiseTerms& terms = triad.axes[i];
    if (const auto n = on_axis(arw, kAxes[i])) {
      terms.white = *n;
    } else if (const auto density = on_axis(nd, kAxes[i])) {
      terms.white = white_from_noise_density(*density, convention);
    }
    if (const auto b = on_axis(bi, kAxes[i])) terms.bias_instability = *b / kFlickerFloorFactor;
    if (const auto k = on_axis(rrw, kAxes[i])) terms.rate_random_walk = *k;
  }
  // Where the terms came from, as printed (every axis's value where they differ).
  if (on_axis(arw, "x")) {
    triad.white_origin = std::string(sensor == Sensor::gyro ? "angle" : "velocity") +
                         " random walk " + describe_axes(*arw) +
                         " is the Allan N itself (the density convention does not apply)";
  } else if (on_axis(nd, "x")) {
    triad.white_origin = "noise density " + describe_axes(*nd) + " " +
                         std::string(noise_density_reading(convention));
  }
  std::string bias;
  if (on_axis(bi, "x")) {
    bias = "in-run bias stability " + describe_axes(*bi) + " read as the ADEV floor 0.664 B";
  }
  if (on_axis(rrw, "x")) {
    bias += std::string(bias.empty() ? "" : "; ") + "rate random walk " + describe_axes(*rrw);
  }
  triad.bias_origin = bias;
  return triad;
}

TriadDiscrete discretize(const TriadNoise& triad, const ConvertOptions& options) {
  check_options(options);
  check_correlation(triad.white_correlation, "white noise");
  check_correlation(triad.bias_correlation, "bias");
  const double fs = options.rate_hz;
  const double ts = 1.0 / fs;
  const double f = options.inflate;
  const std::string sensor(to_string(triad.sensor));
  TriadDiscrete out;
  out.bias_origin = triad.bias_origin;
  out.sensor = triad.sensor;

  bool any_white = false;
  for (const auto& a : triad.axes) any_white = any_white || a.white.has_value();
  if (any_white) {
    WhiteDiscrete w;
    for (int i = 0; i < 3; ++i) {
      const auto& n = triad.axes[static_cast<std::size_t>(i)].white;
      if (!n) throw Error(sensor + ": white noise N is given on some axes but not on all");
      w.density(i) = f * *n;
      w.variance_per_sample(i) = w.density(i) * w.density(i) * fs;  // Q = N^2 f_s
      w.sigma_per_sample(i) = w.density(i) * std::sqrt(fs);         // sigma = N sqrt(f_s)
    }
    w.q = scaled(w.sigma_per_sample, triad.white_correlation);
    out.white = w;
  }

  // Bias: the same source on every axis (the first axis decides, the others must agree).
  const NoiseTerms& a0 = triad.axes[0];
  std::optional<BiasSource> source;
  if (options.bias_model == BiasModel::random_walk) {
    if (a0.rate_random_walk) source = BiasSource::rate_random_walk;
    else if (a0.bias_instability) source = BiasSource::bias_stability;
    else if (!a0.gauss_markov.empty()) source = BiasSource::gauss_markov;
  } else {
    if (!a0.gauss_markov.empty()) source = BiasSource::gauss_markov;
    else if (a0.bias_instability) source = BiasSource::bias_stability;
    else if (a0.rate_random_walk) {
      throw Error(sensor + ": a Gauss-Markov bias needs a bias stability (or sigma and T_c); "
                           "only a rate random walk K is given: use --bias-model rw");
    }
  }
  if (source) {
    BiasDiscrete b;
    b.model = options.bias_model;
    b.source = *source;
    b.phi.setOnes();
    b.tau_c_s.setZero();
    b.sigma.setZero();
    if (const std::string bound = bound_text(triad, *source); !bound.empty()) {
      out.bias_origin += (out.bias_origin.empty() ? "" : "; ") + bound;
      out.bias_from_upper_bound = true;
    }
    // Gauss-Markov from B: tau_min given for all axes, else each axis's measured ADEV minimum
    // (an axis without one takes the shortest measured: the larger per-step drive), else T_ref.
    std::optional<double> shortest_measured;
    std::string unmeasured;
    for (int i = 0; i < 3; ++i) {
      const auto& m = triad.adev_minimum_tau_s[static_cast<std::size_t>(i)];
      if (m && *m > 0 && std::isfinite(*m)) {
        shortest_measured = std::min(shortest_measured.value_or(*m), *m);
      } else {
        unmeasured += std::string(unmeasured.empty() ? "" : ", ") + static_cast<char>('x' + i);
      }
    }
    const auto tau_min_of = [&](int i) {
      if (options.tau_min_s) return *options.tau_min_s;
      const auto& m = triad.adev_minimum_tau_s[static_cast<std::size_t>(i)];
      if (m && *m > 0 && std::isfinite(*m)) return *m;
      return shortest_measured.value_or(options.t_ref_s);
    };
    for (int i = 0; i < 3; ++i) {
      const NoiseTerms& t = triad.axes[static_cast<std::size_t>(i)];
      const auto missing = [&](const char* what) {
        throw Error(sensor + ": " + what + " is given on some axes but not on all");
      };
      if (options.bias_model == BiasModel::random_walk) {
        double k = 0;  // continuous random-walk density K
        if (*source == BiasSource::rate_random_walk) {
          if (!t.rate_random_walk) missing("rate random walk K");
          k = *t.rate_random_walk;
        } else if (*source == BiasSource::bias_stability) {
          if (!t.bias_instability) missing("bias instability B");
          k = kFlickerFloorFactor * *t.bias_instability / std::sqrt(options.t_ref_s);
          b.t_ref_s = options.t_ref_s;
        } else {
          if (t.gauss_markov.empty()) missing("Gauss-Markov {sigma, T_c}");
          // Short-term slope of a GM: K = q_c = sqrt(2 sigma^2 / T_c) (THEORY.md section 2):
          // for tau << T_c its AVAR is 2 sigma^2 tau / (3 T_c) = K^2 tau / 3. Independent
          // processes' AVARs add, so a sum's short-term K^2 is the sum of the entries' K^2.
          k = std::sqrt(gauss_markov_random_walk_k2(t.gauss_markov));
        }
        k *= f;
        b.random_walk_density(i) = k;
        b.variance_per_step(i) = k * k * ts;  // Q_bb = K^2 T_s
      } else {
        double sigma = 0, tau_c = 0;
        if (*source == BiasSource::gauss_markov) {
          if (t.gauss_markov.empty()) missing("Gauss-Markov {sigma, T_c}");
          // One filter state carries one process: the dominant entry (dominant_gauss_markov).
          const GaussMarkov& gm = t.gauss_markov[dominant_gauss_markov(t.gauss_markov)];
          sigma = gm.sigma;
          tau_c = gm.tau_c_s;
        } else {
          if (!t.bias_instability) missing("bias instability B");
          const double tau_min = tau_min_of(i);
          sigma = kFlickerFloorFactor * *t.bias_instability / kGaussMarkovPeakFactor;
          tau_c = tau_min / kGaussMarkovPeakTau;
          b.tau_min_s(i) = tau_min;
        }
        if (!(sigma > 0) || !(tau_c > 0)) {
          throw Error(sensor + ": Gauss-Markov sigma and T_c must be > 0");
        }
        sigma *= f;
        const double phi = std::exp(-ts / tau_c);
        b.phi(i) = phi;
        b.tau_c_s(i) = tau_c;
        b.sigma(i) = sigma;
        b.variance_per_step(i) = sigma * sigma * (1 - phi * phi);  // q = sigma^2 (1 - phi^2)
        b.random_walk_density(i) = std::sqrt(b.variance_per_step(i) * fs);
      }
      b.sigma_per_step(i) = std::sqrt(b.variance_per_step(i));
    }
    if (b.model == BiasModel::gauss_markov && b.source == BiasSource::bias_stability) {
      if (options.tau_min_s) {
        b.tau_min_origin = "given (convert --tau-min)";
      } else if (shortest_measured) {
        b.tau_min_origin = "the tau of the ADEV minimum the fit measured";
        if (!unmeasured.empty()) {
          b.tau_min_origin += " (none on " + unmeasured + ": the shortest measured used there)";
        }
      } else {
        b.tau_min_origin = "T_ref (convert --tref): no tau of the ADEV minimum measured or given";
      }
    }
    if (*source == BiasSource::gauss_markov)
      out.gauss_markov_note = gauss_markov_sum_note(triad, options.bias_model);
    b.q = scaled(b.sigma_per_step, triad.bias_correlation);
    if (b.model == BiasModel::random_walk && b.source == BiasSource::bias_stability &&
        triad.rate_random_walk_bound && *triad.rate_random_walk_bound > 0) {
      const double bound = f * *triad.rate_random_walk_bound;
      const double ratio = b.random_walk_density.maxCoeff() / bound;
      if (ratio > 1) {
        char text[300];
        std::snprintf(text, sizeof text,
                      "the fit bounds K below %.4g %s (largest axis), and this rule-of-thumb K is "
                      "%.3g times that: conservative (a longer T_ref, convert --tref, lowers it)",
                      bound, rw_unit(triad.sensor).c_str(), ratio);
        out.bias_note = text;
      }
    }
    out.bias = b;
  }
  return out;
}

std::string explain(const TriadNoise& triad, const TriadDiscrete& r,
                    const ConvertOptions& options) {
  const Sensor s = triad.sensor;
  const double fs = options.rate_hz;
  const double ts = 1.0 / fs;
  const double f = options.inflate;
  const std::string u = rate_unit(s);
  std::ostringstream o;
  o << to_string(s) << ": f_s = " << num(fs) << " Hz (T_s = " << num(ts)
    << " s), density convention " << to_string(options.convention)
    << (options.convention == DensityConvention::two_sided ? " (N = ND)" : " (N = ND/sqrt(2))")
    << ", inflation F = " << num(f) << (f == 1 ? "" : " (densities and sigmas x F, variances x F^2)")
    << "\n";
  const auto axes_of = [](const Eigen::Vector3d& v) {
    return uniform(v) ? std::vector<int>{0} : std::vector<int>{0, 1, 2};
  };
  const auto label = [](const Eigen::Vector3d& v, int i) {
    static const char* names[] = {"x", "y", "z"};
    return uniform(v) ? std::string() : std::string(names[i]) + ": ";
  };
  if (r.white) {
    const auto& w = *r.white;
    o << "  white noise: " << (triad.white_origin.empty() ? "N given" : triad.white_origin)
      << "\n";
    for (int i : axes_of(w.density)) {
      const double n0 = w.density(i) / f;
      o << "    " << label(w.density, i) << "N = " << num(n0) << " " << density_unit(s)
        << in_deg(s, n0, "deg/s/sqrt(Hz)");
      if (f != 1) o << "; x F = " << num(w.density(i));
      o << "\n    " << label(w.density, i) << "Q = N^2 f_s = (" << num(w.density(i)) << ")^2 x "
        << num(fs) << " = " << num(w.variance_per_sample(i)) << " (" << u << ")^2"
        << in_deg(s, w.variance_per_sample(i), "(deg/s)^2", 2) << "\n";
      o << "    " << label(w.density, i) << "sigma = N sqrt(f_s) = " << num(w.density(i))
        << " x sqrt(" << num(fs) << ") = " << num(w.sigma_per_sample(i)) << " " << u
        << in_deg(s, w.sigma_per_sample(i), "deg/s") << "\n";
    }
  } else {
    o << "  white noise: not given\n";
  }
  if (r.bias) {
    const auto& b = *r.bias;
    if (!r.bias_origin.empty()) o << "  bias: " << r.bias_origin << "\n";
    if (!r.bias_note.empty()) o << "  bias: " << r.bias_note << "\n";
    for (int i : axes_of(b.variance_per_step)) {
      const NoiseTerms& t = triad.axes[static_cast<std::size_t>(i)];
      const std::string p = "    " + label(b.variance_per_step, i);
      if (b.model == BiasModel::random_walk) {
        if (b.source == BiasSource::rate_random_walk) {
          o << p << "random walk from K = " << num(*t.rate_random_walk) << " " << rw_unit(s)
            << in_deg(s, *t.rate_random_walk * 3600 * 60, "deg/h/sqrt(h)") << "\n";
        } else if (b.source == BiasSource::bias_stability) {
          const double bds = kFlickerFloorFactor * *t.bias_instability;
          o << p << "random walk reaching B_ds = " << num(bds) << " " << u
            << in_deg(s, bds * 3600, "deg/h") << " after T_ref = " << num(b.t_ref_s) << " s\n"
            << p << "K = B_ds / sqrt(T_ref) = " << num(bds) << " / sqrt(" << num(b.t_ref_s)
            << ") = " << num(bds / std::sqrt(b.t_ref_s)) << " " << rw_unit(s) << "\n";
        } else if (t.gauss_markov.size() == 1) {
          o << p << "random walk with the short-term slope of the GM (sigma = "
            << num(t.gauss_markov[0].sigma) << " " << u << ", T_c = "
            << num(t.gauss_markov[0].tau_c_s) << " s): K = sigma sqrt(2/T_c) = "
            << num(b.random_walk_density(i) / f) << " " << rw_unit(s) << "\n";
        } else {
          o << p << "random walk with the short-term slope of the sum of "
            << t.gauss_markov.size() << " GMs (" << gauss_markov_list(t.gauss_markov, u)
            << "): K = sqrt(sum 2 sigma_i^2/T_c_i) = " << num(b.random_walk_density(i) / f)
            << " " << rw_unit(s) << "\n";
        }
        if (f != 1) o << p << "x F: K = " << num(b.random_walk_density(i)) << "\n";
        o << p << "Q_bb = K^2 T_s = (" << num(b.random_walk_density(i)) << ")^2 x " << num(ts)
          << " = " << num(b.variance_per_step(i)) << " (" << u << ")^2"
          << in_deg(s, b.variance_per_step(i), "(deg/s)^2", 2) << " per step\n";
      } else {
        if (b.source == BiasSource::bias_stability) {
          const double bds = kFlickerFloorFactor * *t.bias_instability;
          o << p << "Gauss-Markov matched at its ADEV peak (0.6174 sigma at 1.892 T_c) to the "
                    "floor B_ds = "
            << num(bds) << " " << u << in_deg(s, bds * 3600, "deg/h")
            << " at tau_min = " << num(b.tau_min_s(i)) << " s (" << b.tau_min_origin << ")\n"
            << p << "sigma = B_ds / 0.6174 = " << num(b.sigma(i) / f) << " " << u
            << ", T_c = tau_min / 1.892 = " << num(b.tau_c_s(i)) << " s\n";
        } else {
          if (t.gauss_markov.size() > 1)
            o << p << "Gauss-Markov sum of " << t.gauss_markov.size() << " ("
              << gauss_markov_list(t.gauss_markov, u)
              << "): one filter state, the entry with the largest sigma (largest ADEV peak "
                 "0.6174 sigma) is used\n";
          o << p << "Gauss-Markov sigma = " << num(b.sigma(i) / f) << " " << u
            << ", T_c = " << num(b.tau_c_s(i)) << " s\n";
        }
        if (f != 1) o << p << "x F: sigma = " << num(b.sigma(i)) << "\n";
        o << p << "phi = exp(-T_s/T_c) = exp(-" << num(ts) << "/" << num(b.tau_c_s(i))
          << ") = " << num(b.phi(i)) << "\n"
          << p << "q = sigma^2 (1 - phi^2) = (" << num(b.sigma(i)) << ")^2 x (1 - "
          << num(b.phi(i)) << "^2) = " << num(b.variance_per_step(i)) << " (" << u << ")^2"
          << in_deg(s, b.variance_per_step(i), "(deg/s)^2", 2) << " per step\n";
      }
    }
  } else {
    o << "  bias: not given (no bias stability, rate random walk or Gauss-Markov term)\n";
  }
  const auto& axes = triad.axes[0];
  if (axes.quantization || axes.rate_ramp || axes.sinusoid) {
    o << "  not converted: quantization, rate ramp and sinusoid terms have no filter "
         "covariance here\n";
  }
  return o.str();
}

namespace {

/// Throws Error when a number of `triad` a filter file would carry is not finite: a value so
/// large (1e308) that its square at f_s overflows was written as "inf" (PX4) or null (JSON).
void check_finite(const TriadDiscrete& triad, const ConvertOptions& options,
                  const std::string& source) {
  const auto finite = [](const auto& m) { return m.allFinite(); };
  const std::string sensor(to_string(triad.sensor));
  const std::string at = " at " + num(options.rate_hz) + " Hz (inflation " + num(options.inflate) +
                         ", from " + source + ")";
  if (triad.white && !(finite(triad.white->density) && finite(triad.white->variance_per_sample) &&
                       finite(triad.white->sigma_per_sample) && finite(triad.white->q))) {
    throw Error(sensor + " white noise: N = " + num(triad.white->density.maxCoeff()) + " " +
                density_unit(triad.sensor) + " gives a variance per sample that is not finite" +
                at + "; no filter can use it: check the value and its unit");
  }
  const auto& b = triad.bias;
  if (b && !(finite(b->variance_per_step) && finite(b->sigma_per_step) &&
             finite(b->random_walk_density) && finite(b->phi) && finite(b->tau_c_s) &&
             finite(b->sigma) && finite(b->q))) {
    throw Error(sensor + " bias (" + std::string(to_string(b->source)) +
                "): its variance per step is not finite" + at +
                "; no filter can use it: check the value and its unit");
  }
}

}  // namespace

DiscreteNoise convert_noise(const std::vector<TriadNoise>& triads, const ConvertOptions& options,
                            std::string source) {
  check_options(options);
  DiscreteNoise out;
  out.options = options;
  out.source = std::move(source);
  for (const auto& t : triads) {
    auto& slot = t.sensor == Sensor::gyro ? out.gyro : out.accel;
    if (slot) throw Error("two " + std::string(to_string(t.sensor)) + " triads to convert");
    slot = discretize(t, options);
    check_finite(*slot, options, out.source);  // every exporter writes from these numbers
    if (!slot->gauss_markov_note.empty()) out.notes.push_back(slot->gauss_markov_note);
    out.explain += explain(t, *slot, options);
  }
  return out;
}

}  // namespace sigmatau
