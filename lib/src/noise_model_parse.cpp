// The model-string parser and formatter: "N=0.15 deg/sqrt(h), B=3 deg/h, K=0.02 deg/h/sqrt(h)".
// Units go through units.hpp only (conversion happens here, once, at the boundary).
#include <cstdio>
#include <string>
#include <vector>

#include "sigmatau/display_units.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/noise_model.hpp"
#include "sigmatau/units.hpp"

namespace sigmatau {
namespace {

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

/// The dimensions of one sensor's terms (parse_noise_terms checks each value against them).
struct SensorUnits {
  Dimension q, n, b, k, r;
};

SensorUnits units_for(Sensor sensor) {
  if (sensor == Sensor::gyro) {
    return {dim::angle, dim::angle_random_walk, dim::angular_rate, dim::gyro_rate_random_walk,
            dim::angular_rate_ramp};
  }
  return {dim::velocity, dim::velocity_random_walk, dim::acceleration,
          dim::accel_rate_random_walk, dim::acceleration_ramp};
}

/// parse_quantity_as, re-thrown with the model context, and checked > 0.
double quantity(std::string_view value, const Dimension& d, const std::string& field,
                bool must_be_positive = true) {
  double v = 0;
  try {
    v = parse_quantity_as(trim(value), d, field);
  } catch (const Error& e) {
    throw Error(std::string("model: ") + e.what());
  }
  if (must_be_positive && !(v > 0))
    throw Error("model: " + field + " must be > 0, got '" + std::string(trim(value)) + "'");
  return v;
}

/// Splits "<a> @ <b>"; throws naming the key when the '@' is missing.
std::pair<std::string_view, std::string_view> split_at(std::string_view value,
                                                        const std::string& key,
                                                        const char* expected) {
  const auto at = value.find('@');
  if (at == std::string_view::npos)
    throw Error("model: " + key + "='" + std::string(trim(value)) + "': expected " + expected);
  return {value.substr(0, at), value.substr(at + 1)};
}

std::string number(double v) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%.17g", v);
  return buffer;
}

}  // namespace

NoiseTerms parse_noise_terms(std::string_view text, Sensor sensor) {
  const SensorUnits u = units_for(sensor);
  NoiseTerms terms;
  std::vector<std::string> seen;
  std::size_t start = 0;
  bool any = false;
  while (start <= text.size()) {
    const auto comma = text.find(',', start);
    const auto end = comma == std::string_view::npos ? text.size() : comma;
    const std::string_view item = trim(text.substr(start, end - start));
    start = end + 1;
    if (item.empty()) {
      throw Error("model '" + std::string(text) +
                  "': empty term; expected KEY=VALUE UNIT, e.g. 'N=0.15 deg/sqrt(h)'");
    }
    any = true;
    const auto eq = item.find('=');
    if (eq == std::string_view::npos)
      throw Error("model: '" + std::string(item) + "': expected KEY=VALUE UNIT (keys Q, N, B, K, R, GM, SIN)");
    const std::string key(trim(item.substr(0, eq)));
    const std::string_view value = item.substr(eq + 1);
    if (key == "GM") {
      // GM may repeat: a sum of Gauss-Markov processes, up to kMaxGaussMarkov of them.
      if (terms.gauss_markov.size() >= kMaxGaussMarkov)
        throw Error("model: '" + std::string(item) + "' is Gauss-Markov term number " +
                    std::to_string(terms.gauss_markov.size() + 1) + "; at most " +
                    std::to_string(kMaxGaussMarkov) + " GM terms are supported");
    } else {
      for (const auto& k : seen)
        if (k == key) throw Error("model: term " + key + " is given twice");
      seen.push_back(key);
    }
    if (key == "Q") {
      terms.quantization = quantity(value, u.q, "Q");
    } else if (key == "N") {
      terms.white = quantity(value, u.n, "N");
    } else if (key == "B") {
      terms.bias_instability = quantity(value, u.b, "B");
    } else if (key == "K") {
      terms.rate_random_walk = quantity(value, u.k, "K");
    } else if (key == "R") {
      terms.rate_ramp = quantity(value, u.r, "R", false);
    } else if (key == "GM") {
      const auto [sigma, tau] = split_at(value, key, "GM=<sigma> @ <correlation time>");
      terms.gauss_markov.push_back(GaussMarkov{quantity(sigma, u.b, "GM sigma"),
                                               quantity(tau, dim::time, "GM correlation time")});
    } else if (key == "SIN") {
      const auto [amplitude, frequency] = split_at(value, key, "SIN=<amplitude> @ <frequency>");
      terms.sinusoid = Sinusoid{quantity(amplitude, u.b, "SIN amplitude"),
                                quantity(frequency, dim::frequency, "SIN frequency"), 0.0};
    } else {
      throw Error("model: unknown term '" + key + "'; expected one of Q, N, B, K, R, GM, SIN");
    }
    if (comma == std::string_view::npos) break;
  }
  if (!any) throw Error("model is empty; expected e.g. 'N=0.15 deg/sqrt(h), B=3 deg/h'");
  return terms;
}

std::string format_noise_terms(const NoiseTerms& t, Sensor sensor) {
  std::string out;
  const auto add = [&](const char* symbol, double value, NoiseTerm term) {
    out += (out.empty() ? "" : ", ") + std::string(symbol) + "=" + number(value) + " " +
           std::string(si_unit(term, sensor));
  };
  if (t.quantization) add("Q", *t.quantization, NoiseTerm::quantization);
  if (t.white) add("N", *t.white, NoiseTerm::white);
  if (t.bias_instability) add("B", *t.bias_instability, NoiseTerm::bias_instability);
  if (t.rate_random_walk) add("K", *t.rate_random_walk, NoiseTerm::rate_random_walk);
  if (t.rate_ramp) add("R", *t.rate_ramp, NoiseTerm::rate_ramp);
  for (const GaussMarkov& gm : t.gauss_markov) {  // one GM key per entry, in order
    add("GM", gm.sigma, NoiseTerm::gauss_markov);
    out += " @ " + number(gm.tau_c_s) + " s";
  }
  if (t.sinusoid) {
    add("SIN", t.sinusoid->amplitude, NoiseTerm::sinusoid);
    out += " @ " + number(t.sinusoid->frequency_hz) + " Hz";
  }
  return out;
}

}  // namespace sigmatau
