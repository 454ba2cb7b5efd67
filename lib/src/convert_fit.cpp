// Triads for the conversion from a noise-term fit result (JSON), shared by `convert --fit` and
// the analyze chain, with what every filter file written from the fit must say about it: a fit
// rejected by its goodness of fit, implausible units, the method used, the level of the bounds,
// terms left out (R, Q), a filter rate above the log's.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "json_fields.hpp"
#include "sigmatau/channel_names.hpp"
#include "sigmatau/convert.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/fit.hpp"

namespace sigmatau {
namespace {

using nlohmann::json;

/// A filter rate this much above the log's rate gets the extrapolation note: a log's rate from
/// its time stamps is off its nominal value by a fraction of a percent, which is no extrapolation.
constexpr double kRateAboveLogTolerance = 0.01;

struct AxisFit {
  NoiseTerms kept;          // terms in the model
  NoiseTerms upper_bounds;  // terms not in the model, as their upper bound
  std::optional<double> adev_minimum_tau_s;
};

std::string text_of(const json& parent, const char* key) {
  return parent.contains(key) && parent[key].is_string() ? parent[key].get<std::string>() : "";
}

std::string fmt(const char* format, double v) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}

/// Sensor and axis of a fit channel: its "quantity" first where there is one, with its "axis"
/// (x, y or z) where there is one, then the column-name rule every verb uses
/// (classify_channel); with a quantity and a name the rule does not know, the name's last letter
/// x / y / z is the axis.
std::optional<ChannelRole> channel_role(const std::string& name, const std::string& quantity,
                                        const std::string& axis) {
  const std::optional<ChannelRole> by_name = classify_channel(name);
  std::optional<Sensor> sensor;
  if (quantity == "angular_rate") sensor = Sensor::gyro;
  if (quantity == "specific_force" || quantity == "acceleration") sensor = Sensor::accel;
  if (!sensor) return by_name;
  ChannelRole role;
  role.sensor = *sensor;
  if (axis == "x" || axis == "y" || axis == "z") {  // as analysed (analyze's results.json)
    role.axis = axis[0] - 'x';
    return role;
  }
  if (by_name) {
    role.axis = by_name->axis;
    return role;
  }
  const char last =
      name.empty() ? '?' : static_cast<char>(std::tolower(static_cast<unsigned char>(name.back())));
  if (last != 'x' && last != 'y' && last != 'z') return std::nullopt;
  role.axis = last - 'x';
  return role;
}

/// What to do about a rejected fit, by where its furthest point lies (fit.hpp,
/// ChannelFit::misfit_at_shortest_taus; unknown when the result does not record it).
std::string misfit_advice(const json& channel) {
  if (channel.contains("misfit_at_shortest_taus") && channel["misfit_at_shortest_taus"].is_boolean()) {
    if (channel["misfit_at_shortest_taus"].get<bool>()) {
      return "if the sensor filters its output, fit from longer taus (fit / analyze --tau-min)";
    }
    return "something outside the Q, N, B, K, R model shapes the curve there (look at the plot): "
           "fit a tau range without it (fit / analyze --tau-min / --tau-max)";
  }
  return "if the sensor filters its output, fit from longer taus (fit / analyze --tau-min), "
         "else fit a tau range without what the model misses (--tau-min / --tau-max)";
}

/// "rate ramp R kept by the fit, left out ...: accel_x 9.77e-06 m/s^3, ..." for one term.
void add_left_out_note(std::vector<std::string>& notes, const std::string& what,
                       const std::vector<std::string>& values) {
  if (values.empty()) return;
  std::string list;
  for (const auto& v : values) list += (list.empty() ? "" : ", ") + v;
  notes.push_back(what + ": " + list);
}

}  // namespace

FitForFilter read_fit_for_filter(std::string_view json_text, const std::string& file) {
  json doc;
  try {
    doc = json::parse(json_text);
  } catch (const json::exception& e) {  // a parse error, or a number too large (1e999)
    throw Error(file + ": not valid JSON (" + e.what() + ")");
  }
  // An analyze results.json has its fit under "fit" (its top-level "channels" are the curves).
  // Every number read is checked (json_fields.hpp): before, a value of the wrong type was taken
  // as absent and a negative one used.
  using detail::NumberRule;
  const detail::JsonField top{file, ""};
  const json* channels = nullptr;
  detail::JsonField channels_field = top.at("channels");
  double confidence = 0;
  if (doc.is_object() && doc.contains("fit") && doc["fit"].is_object() &&
      doc["fit"].contains("channels")) {
    channels = &doc["fit"]["channels"];
    channels_field = top.at("fit").at("channels");
    confidence = detail::optional_number(doc["fit"], "confidence", top.at("fit"),
                                         NumberRule::confidence_level)
                     .value_or(0);
  }
  if (!channels && doc.is_object() && doc.contains("channels") && doc["channels"].is_array()) {
    channels = &doc["channels"];
  }
  if (!channels || !channels->is_array()) {
    throw Error(file + ": not a sigmatau fit result (expected \"channels\" or \"fit\": {\"channels\"})");
  }
  if (confidence == 0) {
    confidence =
        detail::optional_number(doc, "confidence", top, NumberRule::confidence_level).value_or(0);
  }
  FitForFilter out;
  std::array<std::array<std::optional<AxisFit>, 3>, 2> axes;  // [gyro, accel][x, y, z]
  std::map<std::string, std::string> rejected;  // advice -> "gyro_x (p = 0, ...), ..."
  std::set<std::string> methods;
  bool slopes_also = false;
  std::vector<std::string> ramps, quantizations, readings;
  for (std::size_t index = 0; index < channels->size(); ++index) {
    const json& channel = (*channels)[index];
    const detail::JsonField here = channels_field.at(index);
    if (!channel.is_object()) {
      throw Error(here.message("expected an object, got " + detail::json_shown(channel)));
    }
    const std::string name = detail::optional_text(channel, "name", here).value_or("");
    const detail::JsonField named = here.named(name);
    const std::string quantity = detail::optional_text(channel, "quantity", named).value_or("");
    const std::string axis = detail::optional_text(channel, "axis", named).value_or("");
    detail::optional_text(channel, "method", named);
    const std::optional<double> p_value =
        detail::optional_number(channel, "p_value", named, NumberRule::probability, true);
    const std::optional<double> misfit_tau_s =
        detail::optional_number(channel, "misfit_tau_s", named, NumberRule::positive, true);
    const std::optional<ChannelRole> role = channel_role(name, quantity, axis);
    if (!role) {
      throw Error(file + ": channel \"" + name +
                  "\": cannot tell its sensor and axis (expected a \"quantity\" and \"axis\", "
                  "or a name such as gx / gyro_x / angular_velocity_x, ax / accel_x / "
                  "linear_acceleration_x)");
    }
    if (!channel.contains("parameters")) continue;
    const json& p = channel["parameters"];
    const auto term = [&](const char* key) {
      return detail::fit_term_fields(p, key, named.at("parameters"))
          .value_or(detail::FitTermFields{});
    };
    const detail::FitTermFields n = term("N"), b = term("B"), k = term("K");
    AxisFit fit;
    fit.kept.white = n.value;
    fit.kept.bias_instability = b.value;
    fit.kept.rate_random_walk = k.value;
    fit.upper_bounds.white = n.upper_bound;
    fit.upper_bounds.bias_instability = b.upper_bound;
    fit.upper_bounds.rate_random_walk = k.upper_bound;
    fit.adev_minimum_tau_s = b.tau_min_s;
    axes[role->sensor == Sensor::gyro ? 0 : 1][static_cast<std::size_t>(role->axis)] = fit;

    if (text_of(channel, "reported_from") == "curve_readings") {
      // The curve's read-outs standing in for a joint fit that was rejected or contradicted
      // the curve (fit.hpp, NoiseFit::readings): said on their own, not as a slopes fit.
      const std::string reason = text_of(channel, "readings_reason");
      readings.push_back(name + (reason.empty() ? "" : " (joint fit " + reason + ")"));
    } else if (const std::string method = text_of(channel, "method"); !method.empty()) {
      methods.insert(method);
    }
    slopes_also = slopes_also || channel.contains("slopes");
    if (p_value) {
      if (*p_value < kMisfitPValue) {
        std::string entry = name + " (p = " + fmt("%.2g", *p_value);
        if (misfit_tau_s) entry += ", worst at tau = " + fmt("%.4g", *misfit_tau_s) + " s";
        std::string& list = rejected[misfit_advice(channel)];
        list += (list.empty() ? "" : ", ") + entry + ")";
      }
    }
    for (const auto& [key, values] :
         {std::pair<const char*, std::vector<std::string>*>{"R", &ramps}, {"Q", &quantizations}}) {
      if (const auto v = term(key).value) {
        values->push_back(name + " " + fmt("%.4g", *v) + " " + text_of(p[key], "unit"));
      }
    }
  }

  for (int s = 0; s < 2; ++s) {
    bool present = false;
    for (const auto& a : axes[s]) present = present || a.has_value();
    if (!present) continue;
    TriadNoise triad;
    triad.sensor = s == 0 ? Sensor::gyro : Sensor::accel;
    triad.white_origin = "N from the noise-term fit (" + file + ")";
    triad.bias_origin = "from the noise-term fit";
    triad.bound_confidence = confidence;
    for (int a = 0; a < 3; ++a) {
      if (!axes[s][a]) continue;
      triad.axes[a] = axes[s][a]->kept;
      triad.adev_minimum_tau_s[a] = axes[s][a]->adev_minimum_tau_s;
    }
    // A bias term kept on some axes is completed on the others by its upper bound. When no axis
    // kept B or K (a short log shows white noise only), both are their upper bounds: a filter
    // needs a bias model, and the bound is what the log says of it. Which bound the files then
    // rest on depends on the bias model: discretize names it (TriadDiscrete::bias_origin).
    const auto kept_on_any_axis = [&](std::optional<double> NoiseTerms::*member) {
      bool any = false;
      for (const auto& a : axes[s]) any = any || (a && (a->kept.*member).has_value());
      return any;
    };
    const bool no_bias_term = !kept_on_any_axis(&NoiseTerms::bias_instability) &&
                              !kept_on_any_axis(&NoiseTerms::rate_random_walk);
    for (auto member : {&NoiseTerms::bias_instability, &NoiseTerms::rate_random_walk}) {
      if (!kept_on_any_axis(member) && !no_bias_term) continue;
      auto& is_bound = member == &NoiseTerms::bias_instability ? triad.bias_instability_is_bound
                                                               : triad.rate_random_walk_is_bound;
      for (int a = 0; a < 3; ++a) {
        if (!axes[s][a] || (axes[s][a]->kept.*member) || !(axes[s][a]->upper_bounds.*member)) continue;
        triad.axes[a].*member = *(axes[s][a]->upper_bounds.*member);
        triad.bias_from_upper_bound = true;
        is_bound[static_cast<std::size_t>(a)] = true;
      }
    }
    triad.no_bias_term_detected = no_bias_term && triad.bias_from_upper_bound;
    if (!kept_on_any_axis(&NoiseTerms::rate_random_walk) && !no_bias_term) {
      for (const auto& a : axes[s]) {
        if (!a || !a->upper_bounds.rate_random_walk) continue;
        triad.rate_random_walk_bound =
            std::max(triad.rate_random_walk_bound.value_or(0.0), *a->upper_bounds.rate_random_walk);
      }
    }
    // Axes the result has no channel for (a single-axis test) get the largest measured value of
    // each term: a filter needs all three, and the worst axis is the safe stand-in (a bound
    // stays a bound).
    std::string missing;
    for (int a = 0; a < 3; ++a) {
      if (axes[s][a]) continue;
      missing += static_cast<char>('x' + a);
      for (auto member : {&NoiseTerms::white, &NoiseTerms::bias_instability, &NoiseTerms::rate_random_walk}) {
        for (int b = 0; b < 3; ++b) {
          if (!axes[s][b] || !(triad.axes[b].*member)) continue;
          if (!(triad.axes[a].*member) || *(triad.axes[b].*member) > *(triad.axes[a].*member)) {
            triad.axes[a].*member = *(triad.axes[b].*member);
            if (member == &NoiseTerms::bias_instability) {
              triad.bias_instability_is_bound[a] = triad.bias_instability_is_bound[b];
            } else if (member == &NoiseTerms::rate_random_walk) {
              triad.rate_random_walk_is_bound[a] = triad.rate_random_walk_is_bound[b];
            }
          }
        }
      }
    }
    if (!missing.empty()) {
      triad.white_origin += "; axes " + missing + " not in the fit: the largest measured axis used";
    }
    out.triads.push_back(std::move(triad));
  }
  if (out.triads.empty()) throw Error(file + ": the fit result holds no gyro or accelerometer channel");

  // Warnings: what makes every value written from this fit untrustworthy.
  for (const auto& [advice, list] : rejected) {
    out.warnings.push_back("the noise-term fit is rejected by its goodness of fit (p < " +
                           fmt("%g", kMisfitPValue) + ") on " + list +
                           ": no model of the noise terms describes the ADEV curve, so the "
                           "values written from it are not to be trusted; " + advice);
  }
  if (doc.contains("unit_warnings") && doc["unit_warnings"].is_array()) {
    for (const auto& w : doc["unit_warnings"]) {
      const std::string message = w.is_string() ? w.get<std::string>() : text_of(w, "message");
      if (message.empty()) continue;
      out.warnings.push_back(message +
                             "; if the declared unit is wrong, every value written from this log "
                             "is wrong by the same factor: give the log's unit (--gyro-unit / "
                             "--accel-unit) and run again");
    }
  }

  // Notes: the method whose terms are used, and terms kept that no filter file carries.
  const std::string level =
      confidence > 0 && confidence < 1 ? ", bounds and intervals at " + fmt("%.4g", 100 * confidence) + " %" : "";
  if (methods == std::set<std::string>{"joint"}) {
    out.notes.push_back("terms from the joint noise-term fit" + level +
                        (slopes_also
                             ? "; the slopes results beside it (fit --method both) are not used: "
                               "the joint fit weighs every tau by the curve's covariance and tests "
                               "its goodness of fit, the slopes fit does neither"
                             : ""));
  } else if (methods == std::set<std::string>{"slopes"}) {
    out.notes.push_back("terms from the slopes fit (fit --method slopes)" + level +
                        ": it has no goodness-of-fit test and can keep a term the joint fit would "
                        "drop (a K on a log without one); fit --method joint is the better base "
                        "for a filter");
  } else if (!methods.empty()) {
    std::string list;
    for (const auto& m : methods) list += (list.empty() ? "" : " / ") + m;
    out.notes.push_back("terms from the " + list + " noise-term fits (per channel)" + level);
  }
  if (!readings.empty()) {
    std::string list;
    for (const auto& r : readings) list += (list.empty() ? "" : ", ") + r;
    out.notes.push_back("terms of " + list +
                        " read from the ADEV curve itself (IEEE 952: bias stability from the "
                        "curve's minimum, N from the -1/2 line at 1 s, K from the +1/2 line at 3 "
                        "s): the joint fit there describes no curve or contradicts its own");
  }
  add_left_out_note(out.notes,
                    "rate ramp R kept by the fit, left out of this file (a filter has no ramp term)",
                    ramps);
  add_left_out_note(out.notes,
                    "quantization Q kept by the fit, left out of this file (a filter has no "
                    "quantization term)",
                    quantizations);

  if (doc.contains("input") && doc["input"].is_object()) {
    out.log_rate_hz =
        detail::optional_number(doc["input"], "rate_hz", top.at("input"), NumberRule::positive);
  }
  return out;
}

std::vector<TriadNoise> triads_from_fit_json(std::string_view json_text, const std::string& file) {
  return read_fit_for_filter(json_text, file).triads;
}

std::string rate_above_log_note(double filter_rate_hz, double log_rate_hz) {
  if (!(log_rate_hz > 0) || !(filter_rate_hz > log_rate_hz * (1 + kRateAboveLogTolerance))) {
    return "";
  }
  return "the filter rate " + fmt("%g", filter_rate_hz) + " Hz is above the log's sample rate " +
         fmt("%g", log_rate_hz) + " Hz: the white-noise level was measured only up to " +
         fmt("%g", log_rate_hz / 2) + " Hz (the log's Nyquist frequency) and is extrapolated, as " +
         "flat, to " + fmt("%g", filter_rate_hz / 2) +
         " Hz; a filter's rate should be the IMU's own (Kalibr's update_rate)";
}

DiscreteNoise convert_fit(const FitForFilter& fit, const ConvertOptions& options,
                          std::string source) {
  DiscreteNoise noise = convert_noise(fit.triads, options, std::move(source));
  noise.warnings = fit.warnings;
  // The fit's notes first, then convert_noise's own (a Gauss-Markov sum's note).
  noise.notes.insert(noise.notes.begin(), fit.notes.begin(), fit.notes.end());
  if (fit.log_rate_hz) noise.rate_note = rate_above_log_note(options.rate_hz, *fit.log_rate_hz);
  return noise;
}

}  // namespace sigmatau
