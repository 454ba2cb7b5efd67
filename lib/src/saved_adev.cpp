// A saved `sigmatau adev --format json` result read back for `fit` (saved_adev.hpp).
#include "sigmatau/saved_adev.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <limits>

#include "sigmatau/error.hpp"
#include "sigmatau/units.hpp"

namespace sigmatau {

bool looks_like_json(std::string_view text) {
  for (const char c : text) {
    if (c == ' ' || c == '\t' || c == '\r' || c == '\n') continue;
    return c == '{';
  }
  return false;
}

SavedAdev read_adev_json(std::string_view text, const std::string& file) {
  using nlohmann::json;
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    throw Error(file + ": not valid JSON (" + e.what() + ")");
  }
  const auto need = [&](const json& j, const char* key, const std::string& where) -> const json& {
    if (!j.is_object() || !j.contains(key)) {
      throw Error(file + ": not a saved `sigmatau adev --format json` result: missing \"" +
                  std::string(where) + key + "\"");
    }
    return j[key];
  };
  const json& input = need(doc, "input", "");
  const json& results = need(doc, "results", "");
  const json& rate = need(input, "rate_hz", "input.");
  const json& samples = need(input, "samples", "input.");
  if (!rate.is_number() || !(rate.get<double>() > 0) || !samples.is_number_integer() ||
      !results.is_array()) {
    throw Error(file + ": input.rate_hz must be a number > 0, input.samples an integer and "
                "results an array");
  }
  const std::string kind = input.value("kind", "rate");
  const DataKind data_kind = parse_data_kind(kind);
  CurveSource source;
  source.tau0_s = 1.0 / rate.get<double>();
  source.n_phase_points = samples.get<std::int64_t>() + (data_kind == DataKind::phase ? 0 : 1);

  SavedAdev out;
  out.rate_hz = rate.get<double>();
  for (std::size_t r = 0; r < results.size(); ++r) {
    const json& res = results[r];
    const std::string where = "results[" + std::to_string(r) + "].";
    if (need(res, "statistic", where) != "oadev") continue;
    SavedCurve saved;
    const json& channel = need(res, "channel", where);
    if (!channel.is_string()) throw Error(file + ": " + where + "channel must be a string");
    saved.channel = channel.get<std::string>();
    saved.source = source;
    double to_si = 1;
    const std::string unit = res.value("unit", "");
    if (!unit.empty()) {
      const Unit u = parse_unit(unit);
      to_si = u.factor;
      if (u.dimension == dim::angular_rate) saved.sensor = Sensor::gyro;
      if (u.dimension == dim::acceleration) saved.sensor = Sensor::accel;
    }
    saved.curve.statistic = Statistic::oadev;
    saved.curve.confidence_level = res.value("confidence", 0.683);
    const json& pts = need(res, "points", where);
    if (!pts.is_array()) throw Error(file + ": " + where + "points must be an array");
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const std::string pw = where + "points[" + std::to_string(i) + "].";
      const json& p = pts[i];
      const json& tau = need(p, "tau", pw);
      const json& m = need(p, "m", pw);
      const json& dev = need(p, "dev", pw);
      if (!tau.is_number() || !m.is_number_integer()) {
        throw Error(file + ": " + pw + "tau and m must be numbers");
      }
      CurvePoint cp;
      cp.value.tau_s = tau.get<double>();
      cp.value.m = m.get<std::int64_t>();
      cp.value.n_terms = p.value("n", std::int64_t{0});
      cp.value.dev = dev.is_number() ? dev.get<double>() * to_si
                                     : std::numeric_limits<double>::quiet_NaN();
      cp.confidence.noise.alpha = p.value("alpha", 0);
      const json edf = p.value("edf", json());
      cp.confidence.edf = edf.is_number() ? edf.get<double>() : std::numeric_limits<double>::quiet_NaN();
      saved.curve.points.push_back(cp);
    }
    out.curves.push_back(std::move(saved));
  }
  if (out.curves.empty()) {
    throw Error(file + ": the saved adev result has no oadev curve (rerun adev with --stat oadev)");
  }
  return out;
}

}  // namespace sigmatau
