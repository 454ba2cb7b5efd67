// `sigmatau fit`: noise terms (Q, N, B, K, R) with confidence intervals from a log or from a
// saved `sigmatau adev --format json` result (detected by content).
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <cstdlib>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>

#include "channel_units.hpp"
#include "json_text.hpp"
#include "log_options.hpp"
#include "memory_budget.hpp"
#include "sigmatau/allan_curve.hpp"
#include "sigmatau/allan_out_of_core.hpp"
#include "sigmatau/channel_names.hpp"
#include "sigmatau/data_checks.hpp"
#include "sigmatau/display_units.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/fit.hpp"
#include "sigmatau/output_file.hpp"
#include "sigmatau/saved_adev.hpp"
#include "verbs.hpp"

namespace sigmatau::cli {
namespace {

struct FitArguments {
  LogArguments log;
  std::string method = "joint";
  std::string terms;
  double ci = 0.95;
  double tau_min_s = 0;
  double tau_max_s = std::numeric_limits<double>::infinity();
  bool ieee_terms_only = false;
  std::string format = "table";
  std::string output;
  bool force = false;
  unsigned threads = 0;
  std::string memory = "4GiB";
  /// The log options given on the command line (a saved adev result refuses them).
  std::string log_options_given;
};

/// Bytes read from the start of INPUT to tell a saved JSON result from a log.
constexpr std::size_t kSniffBytes = 4096;

struct Channel {
  std::string name;
  Sensor sensor = Sensor::gyro;
  NoiseFit fit;
  AllanCurve curve;    ///< the curve fitted (SI)
  CurveSource source;  ///< the log behind it
};

/// The fitted curve with the model beside each point: "model_dev" (the reported model) and,
/// where the curve's read-outs stand in for the joint fit, "joint_model_dev".
nlohmann::json curve_with_model_json(const Channel& c, const FitOptions& options) {
  const auto model = model_deviation(c.fit.reported(), c.curve, c.source, options);
  std::vector<double> joint_model;
  if (c.fit.readings) joint_model = model_deviation(*c.fit.joint, c.curve, c.source, options);
  nlohmann::json points = nlohmann::json::array();
  for (std::size_t j = 0; j < c.curve.points.size(); ++j) {
    if (!std::isfinite(model[j])) continue;
    const auto& p = c.curve.points[j];
    nlohmann::json point = {{"tau", p.value.tau_s},
                            {"m", p.value.m},
                            {"dev", p.value.dev},
                            {"model_dev", model[j]}};
    if (!joint_model.empty()) point["joint_model_dev"] = joint_model[j];
    points.push_back(point);
  }
  return {{"statistic", "oadev"}, {"confidence", c.curve.confidence_level}, {"points", points}};
}

/// SI unit (JSON, si_unit) and data-sheet unit (table, display_unit) of each term, per sensor.
struct TermUnits {
  std::string_view si;
  std::string_view sheet;
};
TermUnits units_of(NoiseTerm term, Sensor sensor) {
  return {si_unit(term, sensor), display_unit(term, sensor)};
}

std::string_view term_name(NoiseTerm term, Sensor sensor) {
  switch (term) {
    case NoiseTerm::quantization: return "quantization";
    case NoiseTerm::white: return sensor == Sensor::gyro ? "angle random walk" : "velocity random walk";
    case NoiseTerm::bias_instability: return "bias instability";
    // IEEE 1293 names an accelerometer's K and R after acceleration, not rate.
    case NoiseTerm::rate_random_walk:
      return sensor == Sensor::gyro ? "rate random walk" : "acceleration random walk";
    default: return sensor == Sensor::gyro ? "rate ramp" : "acceleration ramp";
  }
}

std::optional<Sensor> sensor_from_name(const std::string& name) {
  if (name.empty()) return std::nullopt;
  const char c = static_cast<char>(std::tolower(static_cast<unsigned char>(name[0])));
  if (c == 'g' || c == 'w') return Sensor::gyro;
  if (c == 'a') return Sensor::accel;
  return std::nullopt;
}

Sensor sensor_of(const std::string& name, std::optional<Sensor> from_unit) {
  if (from_unit) return *from_unit;
  if (const auto role = classify_channel(name)) return role->sensor;
  if (auto s = sensor_from_name(name)) return *s;
  throw Error("cannot tell whether channel \"" + name +
              "\" is a gyro or an accelerometer: give --unit (e.g. deg/s or m/s^2) or name it "
              "g.. / a..");
}

nlohmann::json parameters_json(const ChannelFit& fit, Sensor sensor) {
  nlohmann::json params = nlohmann::json::object();
  for (const auto& p : fit.parameters) {
    nlohmann::json j;
    if (p.from_model_floor) {
      // Added terms: B read from the model's ADEV floor (the flicker coefficient beside it).
      j["value"] = p.value;
      j["ci_low"] = p.ci_low;
      j["ci_high"] = p.ci_high;
      j["from_model_floor"] = true;
      if (std::isfinite(p.flicker)) j["flicker"] = p.flicker;
    } else if (p.in_model) {
      j["value"] = p.value;
      j["ci_low"] = p.ci_low;
      j["ci_high"] = p.ci_high;
      j["leading_points"] = p.leading_points;
      if (p.lowered_to_curve < 1) j["lowered_to_curve"] = p.lowered_to_curve;
    } else {
      j["upper_bound"] = p.upper_bound;
    }
    j["unit"] = std::string(units_of(p.term, sensor).si);
    if (p.term == NoiseTerm::bias_instability && std::isfinite(p.tau_min_s)) {
      // The curve's own smallest ADEV and its tau (not the model's floor 0.664 B).
      j["tau_min_s"] = p.tau_min_s;
      j["adev_min"] = p.adev_min;
    }
    params[std::string(term_symbol(p.term))] = j;
  }
  return params;
}

nlohmann::json gauss_markov_json(const ChannelFit& fit, Sensor sensor) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& g : fit.gauss_markov) {
    nlohmann::json j = {{"sigma", g.sigma}, {"ci_low", g.ci_low}, {"ci_high", g.ci_high},
                        {"tau_c_s", g.tau_c_s}, {"tau_c_ci_low_s", g.tau_c_ci_low_s},
                        {"tau_c_ci_high_s", g.tau_c_ci_high_s},
                        {"leading_points", g.leading_points},
                        {"unit", std::string(units_of(NoiseTerm::gauss_markov, sensor).si)}};
    if (std::isfinite(g.edf)) j["edf"] = g.edf;
    out.push_back(j);
  }
  return out;
}

nlohmann::json sinusoid_json(const ChannelFit& fit, Sensor sensor) {
  if (!fit.sinusoid) return nullptr;
  const auto& s = *fit.sinusoid;
  nlohmann::json j = {{"amplitude", s.amplitude}, {"ci_low", s.ci_low}, {"ci_high", s.ci_high},
                      {"frequency_hz", s.frequency_hz},
                      {"frequency_ci_low_hz", s.frequency_ci_low_hz},
                      {"frequency_ci_high_hz", s.frequency_ci_high_hz},
                      {"leading_points", s.leading_points},
                      {"unit", std::string(units_of(NoiseTerm::sinusoid, sensor).si)}};
  if (std::isfinite(s.edf)) j["edf"] = s.edf;
  return j;
}

nlohmann::json terms_json(const ChannelFit& fit) {
  nlohmann::json t = nlohmann::json::array();
  for (const auto term : fit.model_terms) t.push_back(std::string(term_symbol(term)));
  return t;
}

nlohmann::json contradictions_json(const ChannelFit& fit, Sensor sensor) {
  nlohmann::json out = nlohmann::json::array();
  for (const auto& c : fit.contradictions) out.push_back(describe(c, sensor));
  return out;
}

/// The joint fit's warnings on a channel: the misfit, the short-log K or R, what the curve
/// contradicts, and the read-outs standing in for it.
std::vector<std::string> channel_warnings(const Channel& c) {
  std::vector<std::string> out;
  if (!c.fit.joint) return out;
  for (const std::string& w : {misfit_warning(*c.fit.joint, c.name), left_out_warning(*c.fit.joint, c.name),
                               short_log_warning(*c.fit.joint, c.name),
                               readings_warning(c.fit, c.name, c.sensor)}) {
    if (!w.empty()) out.push_back(w);
  }
  return out;
}

/// `log_rate_hz`: the sample rate [Hz] of the log behind the curves, written as "input":
/// {"rate_hz"} as adev and analyze write it, so that `convert --fit` can say when a filter rate
/// is above it (rate_above_log_note, convert.hpp); left out when unknown.
std::string render_json(const std::string& input, std::optional<double> log_rate_hz,
                        const std::vector<Channel>& channels,
                        const std::vector<TriadSummary>& triads, const FitOptions& options) {
  const double ci = options.confidence_level;
  nlohmann::json doc;
  doc["tool"] = "sigmatau";
  doc["version"] = SIGMATAU_VERSION;
  doc["input"] = {{"path", input}};
  if (log_rate_hz) doc["input"]["rate_hz"] = *log_rate_hz;
  doc["confidence"] = ci;
  doc["channels"] = nlohmann::json::array();
  for (const auto& c : channels) {
    const ChannelFit& primary = c.fit.reported();
    nlohmann::json j;
    j["name"] = c.name;
    j["quantity"] = c.sensor == Sensor::gyro ? "angular_rate" : "specific_force";
    j["model_terms"] = terms_json(primary);
    j["parameters"] = parameters_json(primary, c.sensor);
    j["gauss_markov"] = gauss_markov_json(primary, c.sensor);
    j["sinusoid"] = sinusoid_json(primary, c.sensor);
    j["method"] = std::string(to_string(primary.method));
    j["points"] = primary.points;
    j["warnings"] = channel_warnings(c);
    j["contradictions"] = contradictions_json(primary, c.sensor);
    j["curve"] = curve_with_model_json(c, options);
    if (c.fit.readings) {
      // The curve's read-outs are reported; the joint fit they stand in for is kept beside them.
      j["reported_from"] = "curve_readings";
      j["readings_reason"] = c.fit.readings_reason;
      const ChannelFit& joint = *c.fit.joint;
      j["joint"] = {{"model_terms", terms_json(joint)},
                    {"parameters", parameters_json(joint, c.sensor)},
                    {"gauss_markov", gauss_markov_json(joint, c.sensor)},
                    {"sinusoid", sinusoid_json(joint, c.sensor)},
                    {"method", "joint"},
                    {"chi_squared", joint.chi_squared},
                    {"bic", joint.bic},
                    {"dof", joint.dof},
                    {"p_value", joint.p_value},
                    {"model_error", joint.model_error},
                    {"left_out_taus_s", joint.left_out_taus_s},
                    {"misfit_tau_s", joint.misfit_tau_s},
                    {"contradictions", contradictions_json(joint, c.sensor)}};
    } else if (c.fit.joint) {
      j["chi_squared"] = primary.chi_squared;
      j["bic"] = primary.bic;
      j["dof"] = primary.dof;
      j["p_value"] = primary.p_value;
      j["model_error"] = primary.model_error;
      j["left_out_taus_s"] = primary.left_out_taus_s;
      j["misfit_tau_s"] = primary.misfit_tau_s;
    }
    if (c.fit.joint && c.fit.slopes) {
      j["slopes"] = {{"model_terms", terms_json(*c.fit.slopes)},
                     {"parameters", parameters_json(*c.fit.slopes, c.sensor)},
                     {"method", "slopes"}};
    }
    doc["channels"].push_back(j);
  }
  doc["triads"] = nlohmann::json::array();
  for (const auto& t : triads) {
    nlohmann::json j;
    j["sensor"] = std::string(to_string(t.sensor));
    j["channels"] = t.channels;
    j["parameters"] = nlohmann::json::object();
    for (const auto& e : t.entries) {
      j["parameters"][std::string(term_symbol(e.term))] = {
          {"mean", e.mean}, {"worst", e.worst}, {"worst_channel", e.worst_channel},
          {"channels_in_model", e.channels_in_model},
          {"unit", std::string(units_of(e.term, t.sensor).si)}};
    }
    doc["triads"].push_back(j);
  }
  return json_text(doc, 1) + "\n";
}

void table_for(std::ostringstream& out, const std::string& name, Sensor sensor,
               const ChannelFit& fit, double ci) {
  out << "\n# " << name << "  " << to_string(fit.method) << "  model ";
  for (std::size_t i = 0; i < fit.model_terms.size(); ++i) {
    out << (i ? "," : "") << term_symbol(fit.model_terms[i]);
  }
  for (std::size_t g = 0; g < fit.gauss_markov.size(); ++g) {
    out << (fit.model_terms.empty() && g == 0 ? "" : ",") << "GM" << g + 1;
  }
  if (fit.sinusoid) out << (fit.model_terms.empty() && fit.gauss_markov.empty() ? "" : ",") << "SIN";
  out << "  (" << ci * 100 << "% intervals)\n";
  char line[200];
  std::snprintf(line, sizeof line, "%-2s %-24s %13s %13s %13s  %s\n", "", "term", "ci_low", "value",
                "ci_high", "unit");
  out << line;
  for (const auto& p : fit.parameters) {
    const TermUnits u = units_of(p.term, sensor);
    const std::string sheet(u.sheet);
    const double f = convert(1.0, u.si, sheet);
    const std::string sym(term_symbol(p.term));
    const std::string nm(term_name(p.term, sensor));
    if (p.in_model || p.from_model_floor) {
      std::snprintf(line, sizeof line, "%-2s %-24s %13.5g %13.5g %13.5g  %s%s", sym.c_str(), nm.c_str(),
                    p.ci_low * f, p.value * f, p.ci_high * f, sheet.c_str(),
                    p.from_model_floor ? " (the model's ADEV floor / 0.664, added terms included)" : "");
    if (p.from_model_floor && std::isfinite(p.flicker)) {
      char flicker[80];
      std::snprintf(flicker, sizeof flicker, "; flicker term alone B = %.5g %s", p.flicker * f, sheet.c_str());
      std::strncat(line, flicker, sizeof line - std::strlen(line) - 1);
    }
    } else {
      std::snprintf(line, sizeof line, "%-2s %-24s %13s %13s %13.5g  %s (not supported by the data: upper bound)",
                    sym.c_str(), nm.c_str(), "", "<", p.upper_bound * f, sheet.c_str());
    }
    out << line;
    if (p.term == NoiseTerm::bias_instability) {
      // Data sheets print the Allan floor 0.664 B as the bias stability, not B: said beside it,
      // or a STIM300 at its typical 0.5 deg/h reads as 0.75 deg/h here, 50 % over.
      // The curve's own minimum is printed with its value: beside the model's floor, its tau
      // alone read as "the curve's minimum is the floor", 5-7x off when the model misfits.
      char floor[80];
      const bool value = p.in_model || p.from_model_floor;
      std::snprintf(floor, sizeof floor, "%.5g %s", kFlickerFloorFactor * (value ? p.value : p.upper_bound) * f,
                    sheet.c_str());
      out << "  (ADEV floor 0.664 B " << (value ? "= " : "< ") << floor
          << ", as data sheets print bias stability";
      if (std::isfinite(p.tau_min_s) && std::isfinite(p.adev_min)) {
        char minimum[120];
        std::snprintf(minimum, sizeof minimum, "; curve minimum %.4g %s at tau = %.5g s",
                      p.adev_min * f, sheet.c_str(), p.tau_min_s);
        out << minimum;
      }
      out << ")";
    }
    out << "\n";
  }
  for (std::size_t g = 0; g < fit.gauss_markov.size(); ++g) {
    const auto& e = fit.gauss_markov[g];
    const TermUnits u = units_of(NoiseTerm::gauss_markov, sensor);
    const std::string sheet(u.sheet);
    const double f = convert(1.0, u.si, sheet);
    const std::string sym = "GM" + std::to_string(g + 1);
    std::snprintf(line, sizeof line,
                  "%-3s %-23s %13.5g %13.5g %13.5g  %s, T_c = %.4g s [%.4g, %.4g]\n", sym.c_str(),
                  "Gauss-Markov sigma", e.ci_low * f, e.sigma * f, e.ci_high * f, sheet.c_str(),
                  e.tau_c_s, e.tau_c_ci_low_s, e.tau_c_ci_high_s);
    out << line;
  }
  if (fit.sinusoid) {
    const auto& e = *fit.sinusoid;
    const TermUnits u = units_of(NoiseTerm::sinusoid, sensor);
    const std::string sheet(u.sheet);
    const double f = convert(1.0, u.si, sheet);
    std::snprintf(line, sizeof line,
                  "%-3s %-23s %13.5g %13.5g %13.5g  %s, f = %.6g Hz [%.6g, %.6g]\n", "SIN",
                  "sinusoid amplitude", e.ci_low * f, e.amplitude * f, e.ci_high * f, sheet.c_str(),
                  e.frequency_hz, e.frequency_ci_low_hz, e.frequency_ci_high_hz);
    out << line;
  }
  if (fit.model_error > 0) {
    std::snprintf(line, sizeof line, "   weights include a relative model error of %.3g (the intervals carry the scatter the model leaves)\n",
                  fit.model_error);
    out << line;
  }
  for (const auto& c : fit.contradictions) out << "   contradicted by the curve: " << describe(c, sensor) << "\n";
  if (fit.method == FitMethod::joint) {
    std::snprintf(line, sizeof line, "   goodness of fit: chi-squared %.4g for %d degrees of freedom, p = %.2g%s\n",
                  fit.chi_squared, fit.dof, fit.p_value,
                  fit.p_value < kMisfitPValue ? " (the model does not describe the curve)" : "");
    out << line;
    const std::string short_log = short_log_warning(fit, name);
    if (!short_log.empty()) out << "   warning: " << short_log << "\n";
  }
}

std::string render_table(const std::string& input, const std::vector<Channel>& channels,
                         const std::vector<TriadSummary>& triads, double ci) {
  std::ostringstream out;
  out << "# " << input << ": noise terms from the OADEV curve\n";
  for (const auto& c : channels) {
    if (c.fit.joint) table_for(out, c.name, c.sensor, *c.fit.joint, ci);
    if (c.fit.slopes) table_for(out, c.name, c.sensor, *c.fit.slopes, ci);
    if (c.fit.readings) {
      out << "\n# " << c.name << ": the joint fit is " << c.fit.readings_reason
          << "; reported instead: the curve's own read-outs (IEEE 952: B from the minimum, N "
             "from the -1/2 line; a line that crosses the curve lowered to touch it)";
      table_for(out, c.name, c.sensor, *c.fit.readings, ci);
    }
  }
  for (const auto& t : triads) {
    out << "\n# " << to_string(t.sensor) << " triad (";
    for (std::size_t i = 0; i < t.channels.size(); ++i) out << (i ? "," : "") << t.channels[i];
    out << "): mean and worst axis\n";
    for (const auto& e : t.entries) {
      const TermUnits u = units_of(e.term, t.sensor);
      const std::string sheet(u.sheet);
      const double f = convert(1.0, u.si, sheet);
      char line[200];
      std::snprintf(line, sizeof line, "%-2s %-24s mean %12.5g  worst %12.5g (%s)  %s",
                    std::string(term_symbol(e.term)).c_str(),
                    std::string(term_name(e.term, t.sensor)).c_str(), e.mean * f, e.worst * f,
                    e.worst_channel.c_str(), sheet.c_str());
      out << line;
      if (e.channels_in_model < static_cast<int>(t.channels.size())) {
        out << "  (over the " << e.channels_in_model << " of " << t.channels.size()
            << " channels that have it)";
      }
      out << "\n";
    }
  }
  return out.str();
}

std::string sniff(const std::string& path) {
  if (path == "-") return {};
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  std::string head(kSniffBytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return head;
}

/// Refuses, before the log is read, a --unit that names neither sensor (fit needs to know
/// which terms a channel has: rate random walk or acceleration random walk, ...).
void check_unit_names_a_sensor(const LogArguments& args) {
  LoadedChannels unit;
  set_input_unit(args, unit);
  if (unit.unit.empty()) return;
  const ChannelUnit given{unit.unit, unit.dimension, unit.to_si, 1.0, "--unit"};
  if (sensor_of_unit(given, unit.kind)) return;
  throw Error("--unit " + unit.unit + " (--kind " + std::string(to_string(unit.kind)) +
              ") is neither an angular rate nor an acceleration");
}

void warn_constant(const std::string& input, const std::string& channel) {
  std::cerr << "sigmatau: warning: " << input << ": "
            << constant_channel_text(channel, "every OADEV value is 0") << "; left out of the fit\n";
}

void scale_curve(AllanCurve& curve, double factor) {
  for (auto& point : curve.points) {
    point.value.dev *= factor;
    point.confidence.interval.low *= factor;
    point.confidence.interval.high *= factor;
  }
}

/// The OADEV curve (octave taus, 68.3 % intervals) of every channel of a log, and what the fit
/// needs to know of the series behind it.
struct LogCurves {
  std::vector<std::string> channel_names;
  /// Each channel's unit (resolve_channel_units): its sensor, and the factor its curve is
  /// scaled by (result_to_si: 1 when the samples were scaled to SI as they were read).
  std::vector<ChannelUnit> channel_units;
  DataKind kind = DataKind::rate;
  std::vector<AllanCurve> curves;
  CurveSource source;
  double rate_hz = 0;  ///< the log's sample rate [Hz] (given or from its time stamps)
};

LogCurves oadev_in_memory(const LogArguments& log_args, unsigned threads) {
  LoadedChannels loaded = load_channels(log_args);
  std::vector<PhaseSeries> series;
  for (auto& channel : loaded.log.channels) {
    series.push_back(PhaseSeries::from_samples(channel, loaded.kind, 1.0 / loaded.rate_hz));
    std::vector<double>().swap(channel);
  }
  LogCurves out;
  out.channel_names = std::move(loaded.log.channel_names);
  out.channel_units = std::move(loaded.channel_units);
  out.kind = loaded.kind;
  for (auto& curve : compute_allan_curves(series, {Statistic::oadev}, TauSpec{}, 0.683, threads)) {
    out.curves.push_back(std::move(curve.front()));
  }
  out.source = CurveSource{series.front().tau0_s(), series.front().size(), 0};
  out.rate_hz = loaded.rate_hz;
  return out;
}

/// The same curves, bit for bit, from a file larger than --memory: exact out of core (the phase
/// in temporary files, the file read twice per group of --threads channels), as `adev` does.
LogCurves oadev_out_of_core(const LogArguments& log_args, unsigned threads) {
  std::cerr << "sigmatau: " << log_args.input
            << " needs more than --memory in memory; computing the OADEV curves exactly out of "
               "core (temporary files in "
            << (std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") << ")\n";
  const LogOptions options = log_options_from(log_args);
  LoadedChannels unit;
  set_input_unit(log_args, unit);
  Progress progress;
  OutOfCoreSettings settings;
  settings.threads = threads;
  settings.progress = [&](std::int64_t done, std::int64_t total) { progress.update(done, total); };
  settings.stage = [&](const std::string& label) { progress.stage(label); };
  OutOfCoreResult result = compute_allan_curves_out_of_core(
      options, unit.kind, unit.to_si,
      [&](const TimingReport& timing) {
        return resolve_rate_hz(log_args.rate_hz, timing, log_args.input);
      },
      {Statistic::oadev}, TauSpec{}, 0.683, settings);
  progress.finish();
  note_reading(log_args, options, result.timing);
  LogCurves out;
  unit.log.channel_names = std::move(result.channel_names);
  resolve_channel_units(log_args, unit);
  out.channel_names = std::move(unit.log.channel_names);
  out.channel_units = std::move(unit.channel_units);
  out.kind = unit.kind;
  for (auto& curve : result.curves) out.curves.push_back(std::move(curve.front()));
  // N phase points: one more than the samples for rate and increment input.
  const std::int64_t points = unit.kind == DataKind::phase ? result.samples : result.samples + 1;
  out.source = CurveSource{1.0 / result.rate_hz, points, 0};
  out.rate_hz = result.rate_hz;
  return out;
}

void run_fit(const FitArguments& args) {
  FitOptions options;
  options.method = parse_fit_method(args.method);
  if (!args.terms.empty()) options.terms = parse_fit_terms(args.terms);
  if (!(args.ci > 0 && args.ci < 1)) {
    throw Error("--ci: confidence level must be in (0, 1), got " + std::to_string(args.ci));
  }
  options.confidence_level = args.ci;
  check_tau_range(args.tau_min_s, args.tau_max_s);
  options.tau_min_s = args.tau_min_s;
  options.tau_max_s = args.tau_max_s;
  options.added_terms = !args.ieee_terms_only;
  if (args.format != "table" && args.format != "json") {
    throw Error("--format must be table or json, got \"" + args.format + "\"");
  }
  if (!args.output.empty()) check_can_write(args.output, args.force);

  std::vector<Channel> channels;
  std::optional<double> log_rate_hz;
  if (looks_like_json(sniff(args.log.input))) {
    const SavedAdev saved_adev = read_adev_json(read_text_file(args.log.input), args.log.input);
    log_rate_hz = saved_adev.rate_hz;
    std::string ignored = args.log_options_given;
    for (const auto& [option, value] : {std::pair<const char*, const std::string&>{"--gyro-unit", args.log.gyro_unit},
                                        {"--accel-unit", args.log.accel_unit}}) {
      if (!value.empty()) ignored += (ignored.empty() ? "" : ", ") + std::string(option);
    }
    if (!ignored.empty()) {
      throw Error(args.log.input + " is a saved adev result (its rate, units and channels are in "
                  "it): " + ignored + " would be ignored; leave them out, or fit the log itself");
    }
    for (const auto& saved : saved_adev.curves) {
      if (all_deviations_zero(saved.curve)) {
        warn_constant(args.log.input, saved.channel);
        continue;
      }
      Channel c;
      c.name = saved.channel;
      c.sensor = sensor_of(saved.channel, saved.sensor);
      c.curve = saved.curve;
      c.source = saved.source;
      try {
        c.fit = fit_noise(saved.curve, saved.source, options);
      } catch (const Error& e) {
        throw Error(args.log.input + ": channel " + saved.channel + ": " + e.what());
      }
      channels.push_back(std::move(c));
    }
  } else {
    // The units are checked before the log is read: --unit names a sensor, and no unit
    // contradicts a column's name or a ROS bag's own (as in adev and psd).
    check_unit_names_a_sensor(args.log);
    early_channel_units(args.log);
    if (args.log.unit.empty() && !per_channel_units(args.log)) {
      std::cerr << "sigmatau: no --unit: the values are taken as SI (rad/s for a gyro, m/s^2 for "
                   "an accelerometer)\n";
    }
    const std::int64_t memory = parse_bytes(args.memory);
    LogCurves log = exact_needs_out_of_core(args.log, memory)
                        ? oadev_out_of_core(args.log, args.threads)
                        : oadev_in_memory(args.log, args.threads);
    log_rate_hz = log.rate_hz;
    for (std::size_t i = 0; i < log.curves.size(); ++i) {
      if (all_deviations_zero(log.curves[i])) {
        warn_constant(args.log.input, log.channel_names[i]);
        continue;
      }
      Channel c;
      c.name = log.channel_names[i];
      const ChannelUnit& unit = log.channel_units[i];
      c.sensor = sensor_of(c.name, sensor_of_unit(unit, log.kind));
      // A deviation and its interval scale with the unit; the noise identification and the EDF
      // do not depend on it.
      if (unit.result_to_si != 1.0) scale_curve(log.curves[i], unit.result_to_si);
      c.curve = log.curves[i];
      c.source = log.source;
      try {
        c.fit = fit_noise(log.curves[i], log.source, options);
      } catch (const Error& e) {
        throw Error(args.log.input + ": channel " + c.name + ": " + e.what());
      }
      channels.push_back(std::move(c));
    }
  }

  if (channels.empty()) {
    throw Error(args.log.input + ": every channel is constant: nothing to fit");
  }
  std::vector<std::string> names;
  std::vector<Sensor> sensors;
  std::vector<const ChannelFit*> fits;
  for (const auto& c : channels) {
    names.push_back(c.name);
    sensors.push_back(c.sensor);
    fits.push_back(&c.fit.reported());
  }
  const auto triads = summarise_triads(names, sensors, fits);
  for (const auto& c : channels) {
    if (!c.fit.joint) continue;
    for (const std::string& w : channel_warnings(c)) std::cerr << "sigmatau: warning: " << w << "\n";
  }
  const std::string text = args.format == "json"
                               ? render_json(args.log.input, log_rate_hz, channels, triads, options)
                               : render_table(args.log.input, channels, triads, args.ci);
  if (args.output.empty()) {
    std::cout << text;
  } else {
    write_file_atomically(args.output, text, args.force);
  }
}

}  // namespace

void add_fit_command(CLI::App& app) {
  auto args = std::make_shared<FitArguments>();
  CLI::App* command = app.add_subcommand(
      "fit", "Noise terms (Q, N, B, K, R) with confidence intervals, from a log or a saved "
             "`adev --format json` result: a joint fit that keeps only the terms the data "
             "supports, and/or the IEEE slope read-outs");
  const std::vector<CLI::Option*> log_options = add_log_options(*command, args->log);
  add_sensor_unit_options(*command, args->log);
  command->add_option("--method", args->method, "joint | slopes | both")->capture_default_str();
  // An explicitly empty --terms used to mean the BIC choice silently; it is an error like --stat "".
  command->add_option("--terms", args->terms,
                      "force the model, e.g. N,B,K (default: chosen by BIC among Q,N,B,K,R)")
      ->check([](const std::string& value) {
        return value.empty() ? std::string("empty list: give terms such as N,B,K, or leave --terms "
                                           "out for the BIC choice")
                             : std::string();
      });
  command->add_option("--ci", args->ci,
                      "two-sided confidence level of the intervals, one-sided of a left-out term's "
                      "bound; 0.95 by default, the level a data-sheet check or a non-detection "
                      "limit is quoted at (adev and analyze default to 0.683, one sigma, as ADEV "
                      "error bars are printed)")
      ->capture_default_str();
  command->add_option("--tau-min", args->tau_min_s,
                      "fit only taus >= this [s] (a sensor that filters its output departs from "
                      "the noise terms at the shortest taus)");
  command->add_option("--tau-max", args->tau_max_s, "fit only taus <= this [s]");
  command->add_flag("--ieee-terms-only", args->ieee_terms_only,
                    "keep to Q, N, B, K, R even where they do not describe the curve (by default "
                    "the joint fit then adds Gauss-Markov terms or a sinusoid, weights with a model "
                    "error and leaves out the shortest taus a sensor's filter bends: docs/fit.md)");
  command->add_option("--format", args->format, "table | json")->capture_default_str();
  command->add_option("-o,--output", args->output, "write to FILE (atomically) instead of stdout");
  command->add_flag("--force", args->force, "overwrite an existing output file");
  command->add_option("--threads", args->threads, "worker threads for the curves (0: one per core)")
      ->capture_default_str();
  command->add_option("--memory", args->memory,
                      "memory for the exact OADEV curves, e.g. 1GiB: larger files are computed "
                      "out of core (the same numbers, as `adev` does)")
      ->capture_default_str();
  command->callback([args, log_options] {
    args->log_options_given = given_option_names(log_options);
    run_fit(*args);
  });
}

}  // namespace sigmatau::cli
