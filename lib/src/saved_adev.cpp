// A saved `sigmatau adev --format json` result read back for `fit` (saved_adev.hpp).
#include "sigmatau/saved_adev.hpp"

#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>

#include "json_fields.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/sampling_limits.hpp"
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
  using detail::NumberRule;
  using nlohmann::json;
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::exception& e) {  // a parse error, or a number too large (1e999)
    throw Error(file + ": not valid JSON (" + e.what() + ")");
  }
  const detail::JsonField top{file, ""};
  const auto need = [&](const json& j, const char* key,
                        const detail::JsonField& where) -> const json& {
    if (!j.is_object() || !j.contains(key)) {
      throw Error(file + ": not a saved `sigmatau adev --format json` result: missing \"" +
                  where.at(key).path + "\"");
    }
    return j[key];
  };
  const json& input = need(doc, "input", top);
  const json& results = need(doc, "results", top);
  need(input, "rate_hz", top.at("input"));
  need(input, "samples", top.at("input"));
  const double rate_hz = checked_rate_hz(
      detail::required_number(input, "rate_hz", top.at("input"), NumberRule::positive),
      file + ": input.rate_hz");
  // A series of fewer than 2 samples has no deviation at all.
  constexpr std::int64_t kFewestSamples = 2;
  const std::int64_t samples =
      *detail::optional_integer(input, "samples", top.at("input"), kFewestSamples,
                                std::numeric_limits<std::int64_t>::max() - 1);
  if (!results.is_array()) {
    throw Error(top.at("results").message("expected an array, got " + detail::json_shown(results)));
  }
  const std::string kind = detail::optional_text(input, "kind", top.at("input")).value_or("rate");
  DataKind data_kind = DataKind::rate;
  try {
    data_kind = parse_data_kind(kind);
  } catch (const Error& e) {
    throw Error(top.at("input").at("kind").message(e.what()));
  }
  CurveSource source;
  source.tau0_s = 1.0 / rate_hz;
  source.n_phase_points = samples + (data_kind == DataKind::phase ? 0 : 1);

  SavedAdev out;
  out.rate_hz = rate_hz;
  for (std::size_t r = 0; r < results.size(); ++r) {
    const json& res = results[r];
    const detail::JsonField where = top.at("results").at(r);
    need(res, "statistic", where);
    const std::optional<std::string> statistic = detail::optional_text(res, "statistic", where);
    if (*statistic != "oadev") continue;
    SavedCurve saved;
    need(res, "channel", where);
    saved.channel = *detail::optional_text(res, "channel", where);
    saved.source = source;
    double to_si = 1;
    const std::string unit = detail::optional_text(res, "unit", where).value_or("");
    if (!unit.empty()) {
      const Unit u = parse_unit(unit);
      to_si = u.factor;
      if (u.dimension == dim::angular_rate) saved.sensor = Sensor::gyro;
      if (u.dimension == dim::acceleration) saved.sensor = Sensor::accel;
    }
    saved.curve.statistic = Statistic::oadev;
    saved.curve.confidence_level =
        detail::optional_number(res, "confidence", where, NumberRule::confidence_level)
            .value_or(0.683);
    const json& pts = need(res, "points", where);
    if (!pts.is_array()) {
      throw Error(where.at("points").message("expected an array, got " + detail::json_shown(pts)));
    }
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const detail::JsonField pw = where.at("points").at(i);
      const json& p = pts[i];
      need(p, "tau", pw);
      need(p, "m", pw);
      need(p, "dev", pw);
      CurvePoint cp;
      cp.value.tau_s = detail::required_number(p, "tau", pw, NumberRule::positive);
      cp.value.m = *detail::optional_integer(p, "m", pw, 1, samples);
      cp.value.n_terms = detail::optional_integer(p, "n", pw, 0, samples).value_or(0);
      // null: adev could not compute the deviation at this tau (too few terms); kept as NaN.
      constexpr double kUndefined = std::numeric_limits<double>::quiet_NaN();
      cp.value.dev = detail::optional_number(p, "dev", pw, NumberRule::non_negative, true)
                         .value_or(kUndefined) *
                     to_si;
      for (const char* bound : {"ci_low", "ci_high"}) {
        detail::optional_number(p, bound, pw, NumberRule::non_negative, true);
      }
      // The noise type's exponent, an integer in [-2, 2] (confidence.hpp).
      cp.confidence.noise.alpha =
          static_cast<int>(detail::optional_integer(p, "alpha", pw, -2, 2).value_or(0));
      cp.confidence.edf =
          detail::optional_number(p, "edf", pw, NumberRule::positive, true).value_or(kUndefined);
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
