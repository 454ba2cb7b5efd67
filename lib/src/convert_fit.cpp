// Triads for the conversion from a noise-term fit result (JSON), shared by `convert --fit` and
// the analyze chain.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>

#include "sigmatau/convert.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau {
namespace {

using nlohmann::json;

struct AxisFit {
  NoiseTerms kept;           // terms in the model
  NoiseTerms upper_bounds;   // terms not in the model, as their upper bound
};

std::optional<double> read(const json& parameters, const char* key, const char* field) {
  if (!parameters.contains(key) || !parameters[key].contains(field)) return std::nullopt;
  const json& v = parameters[key][field];
  if (!v.is_number()) return std::nullopt;
  return v.get<double>();
}

}  // namespace

std::vector<TriadNoise> triads_from_fit_json(std::string_view json_text, const std::string& file) {
  json doc;
  try {
    doc = json::parse(json_text);
  } catch (const json::parse_error& e) {
    throw Error(file + ": not valid JSON (" + e.what() + ")");
  }
  // An analyze results.json has its fit under "fit" (its top-level "channels" are the curves).
  const json* channels = nullptr;
  if (doc.contains("fit") && doc["fit"].contains("channels")) channels = &doc["fit"]["channels"];
  if (!channels && doc.contains("channels") && doc["channels"].is_array()) channels = &doc["channels"];
  if (!channels) {
    throw Error(file + ": not a sigmatau fit result (expected \"channels\" or \"fit\": {\"channels\"})");
  }
  std::array<std::array<std::optional<AxisFit>, 3>, 2> axes;  // [gyro, accel][x, y, z]
  for (const auto& channel : *channels) {
    const std::string name = channel.value("name", "");
    const std::string quantity = channel.value("quantity", "");
    int sensor = -1;
    if (quantity == "angular_rate" || (!name.empty() && (name[0] == 'g' || name[0] == 'w'))) sensor = 0;
    if (quantity == "specific_force" || quantity == "acceleration" || (!name.empty() && name[0] == 'a')) sensor = 1;
    const char last = name.empty() ? '?' : static_cast<char>(std::tolower(static_cast<unsigned char>(name.back())));
    if (sensor < 0 || (last != 'x' && last != 'y' && last != 'z')) {
      throw Error(file + ": channel \"" + name + "\": cannot tell its sensor and axis (expected gx..gz / ax..az)");
    }
    if (!channel.contains("parameters")) continue;
    const json& p = channel["parameters"];
    AxisFit fit;
    fit.kept.white = read(p, "N", "value");
    fit.kept.bias_instability = read(p, "B", "value");
    fit.kept.rate_random_walk = read(p, "K", "value");
    fit.upper_bounds.white = read(p, "N", "upper_bound");
    fit.upper_bounds.bias_instability = read(p, "B", "upper_bound");
    fit.upper_bounds.rate_random_walk = read(p, "K", "upper_bound");
    axes[sensor][last - 'x'] = fit;
  }
  std::vector<TriadNoise> triads;
  for (int s = 0; s < 2; ++s) {
    bool present = false;
    for (const auto& a : axes[s]) present = present || a.has_value();
    if (!present) continue;
    TriadNoise triad;
    triad.sensor = s == 0 ? Sensor::gyro : Sensor::accel;
    triad.white_origin = "N from the noise-term fit (" + file + ")";
    triad.bias_origin = "B / K from the noise-term fit";
    for (int a = 0; a < 3; ++a) {
      if (axes[s][a]) triad.axes[a] = axes[s][a]->kept;
    }
    // A bias term kept on some axes is completed on the others by its upper bound. When no axis
    // kept B or K (a short log shows white noise only), both are their upper bounds: a filter
    // needs a bias model, and the bound is what the log says of it (the file says so).
    const auto kept_on_any_axis = [&](std::optional<double> NoiseTerms::*member) {
      bool any = false;
      for (const auto& a : axes[s]) any = any || (a && (a->kept.*member).has_value());
      return any;
    };
    const bool no_bias_term = !kept_on_any_axis(&NoiseTerms::bias_instability) &&
                              !kept_on_any_axis(&NoiseTerms::rate_random_walk);
    for (auto member : {&NoiseTerms::bias_instability, &NoiseTerms::rate_random_walk}) {
      if (!kept_on_any_axis(member) && !no_bias_term) continue;
      for (int a = 0; a < 3; ++a) {
        if (!axes[s][a] || (axes[s][a]->kept.*member) || !(axes[s][a]->upper_bounds.*member)) continue;
        triad.axes[a].*member = *(axes[s][a]->upper_bounds.*member);
        triad.bias_from_upper_bound = true;
        if (no_bias_term) continue;  // said once for the triad, below
        triad.bias_origin += std::string("; ") + (member == &NoiseTerms::bias_instability ? "B" : "K") +
                             " on axis " + static_cast<char>('x' + a) +
                             ": not detected, its upper bound used";
      }
    }
    if (!kept_on_any_axis(&NoiseTerms::rate_random_walk) && !no_bias_term) {
      for (const auto& a : axes[s]) {
        if (!a || !a->upper_bounds.rate_random_walk) continue;
        triad.rate_random_walk_bound =
            std::max(triad.rate_random_walk_bound.value_or(0.0), *a->upper_bounds.rate_random_walk);
      }
    }
    if (no_bias_term && triad.bias_from_upper_bound) {
      triad.bias_origin += "; neither B nor K detected on any axis: their upper bounds used";
    }
    // Axes the result has no channel for (a single-axis test) get the largest measured value of
    // each term: a filter needs all three, and the worst axis is the safe stand-in.
    std::string missing;
    for (int a = 0; a < 3; ++a) {
      if (axes[s][a]) continue;
      missing += static_cast<char>('x' + a);
      for (auto member : {&NoiseTerms::white, &NoiseTerms::bias_instability, &NoiseTerms::rate_random_walk}) {
        for (int b = 0; b < 3; ++b) {
          if (!axes[s][b] || !(triad.axes[b].*member)) continue;
          if (!(triad.axes[a].*member) || *(triad.axes[b].*member) > *(triad.axes[a].*member)) {
            triad.axes[a].*member = *(triad.axes[b].*member);
          }
        }
      }
    }
    if (!missing.empty()) {
      triad.white_origin += "; axes " + missing + " not in the fit: the largest measured axis used";
    }
    triads.push_back(std::move(triad));
  }
  if (triads.empty()) throw Error(file + ": the fit result holds no gyro or accelerometer channel");
  return triads;
}

}  // namespace sigmatau
