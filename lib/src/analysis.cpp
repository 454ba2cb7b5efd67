// The analyze chain: trim -> curves -> PSD -> fit -> filter covariances -> compliance ->
// results.json. Each stage reads only what the previous ones produced.
#include "sigmatau/analysis.hpp"

#include <nlohmann/json.hpp>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "sigmatau/allan_curve.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/filter_export.hpp"
#include "sigmatau/warmup.hpp"

namespace sigmatau {
namespace {

using nlohmann::json;

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

std::string lower(std::string_view s) {
  std::string out;
  for (char c : s) out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

/// The rate series of a channel (PSD and warm-up work on rates).
std::vector<double> as_rate(const std::vector<double>& values, DataKind kind, double rate_hz) {
  std::vector<double> rate = values;
  if (kind == DataKind::increment) {
    for (double& v : rate) v *= rate_hz;
  } else if (kind == DataKind::phase) {
    for (std::size_t i = 0; i + 1 < rate.size(); ++i) rate[i] = (rate[i + 1] - rate[i]) * rate_hz;
    if (!rate.empty()) rate.pop_back();
  }
  return rate;
}

json curve_json(const AllanCurve& curve) {
  json points = json::array();
  for (const auto& p : curve.points) {
    points.push_back({{"tau", p.value.tau_s},
                      {"m", p.value.m},
                      {"n", p.value.n_terms},
                      {"dev", number_or_null(p.value.dev)},
                      {"ci_low", number_or_null(p.confidence.interval.low)},
                      {"ci_high", number_or_null(p.confidence.interval.high)},
                      {"edf", number_or_null(p.confidence.edf)},
                      {"alpha", p.confidence.noise.alpha}});
  }
  return {{"statistic", std::string(to_string(curve.statistic))},
          {"confidence", curve.confidence_level},
          {"points", points}};
}

json psd_json(const PsdCurve& binned, const NoiseDensity& nd, const std::string& unit) {
  return {{"convention", "one-sided"},
          {"unit", "(" + unit + ")^2/Hz"},
          {"window", std::string(to_string(binned.window))},
          {"segment_length", binned.segment_length},
          {"segments", binned.segments},
          {"frequency", binned.frequency_hz},
          {"psd", binned.psd},
          {"edf", binned.edf},
          {"noise_density",
           {{"value", nd.value},
            {"ci_low", nd.ci_low},
            {"ci_high", nd.ci_high},
            {"unit", unit + "/sqrt(Hz)"},
            {"convention", "N = sqrt(two-sided level) (data-sheet / Kalibr / Allan N)"},
            {"band_hz", {nd.band_low_hz, nd.band_high_hz}},
            {"band_detected", nd.band_detected},
            {"edf", nd.edf},
            {"one_sided_asd", nd.one_sided_asd}}}};
}

std::string si_rate_unit(const std::optional<ChannelRole>& role) {
  if (!role) return "";
  return role->sensor == Sensor::gyro ? "rad/s" : "m/s^2";
}

}  // namespace

std::optional<ChannelRole> classify_channel(std::string_view name) {
  const std::string n = lower(name);
  if (n.empty()) return std::nullopt;
  const char last = n.back();
  if (last != 'x' && last != 'y' && last != 'z') return std::nullopt;
  ChannelRole role;
  role.axis = last - 'x';
  const std::string stem = n.substr(0, n.size() - 1);
  auto starts = [&](const char* p) { return stem.rfind(p, 0) == 0; };
  auto has = [&](const char* p) { return stem.find(p) != std::string::npos; };
  if (stem == "g" || stem == "w" || starts("gyr") || starts("omega") || has("angular") ||
      stem == "g_" || stem == "w_" || stem == "wb_" || starts("rate_")) {
    role.sensor = Sensor::gyro;
    return role;
  }
  if (stem == "a" || stem == "a_" || starts("acc") || has("linear_acc") || stem == "f" || stem == "f_") {
    role.sensor = Sensor::accel;
    return role;
  }
  return std::nullopt;
}

std::string file_crc32(const std::string& path) {
  if (path.empty() || path == "-") return "";
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  uLong crc = crc32(0L, Z_NULL, 0);
  std::vector<char> buffer(1 << 20);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    const auto got = in.gcount();
    if (got > 0) crc = crc32(crc, reinterpret_cast<const Bytef*>(buffer.data()), static_cast<uInt>(got));
  }
  char hex[16];
  std::snprintf(hex, sizeof hex, "%08lx", static_cast<unsigned long>(crc));
  return hex;
}

AnalysisOutput run_analysis(AnalysisInput input, const AnalysisOptions& options) {
  if (input.channels.empty()) throw Error(input.path + ": no channel to analyse");
  if (!(input.rate_hz > 0)) throw Error(input.path + ": sample rate must be > 0");
  if (options.statistics.empty()) throw Error("no statistic asked for");
  AnalysisOutput output;
  json results;
  results["tool"] = "sigmatau";
  results["version"] = SIGMATAU_VERSION;
  results["schema"] = 1;
  results["created_utc"] = options.created_utc;
  results["confidence"] = options.confidence;
  json warnings = json::array();

  // Trim the warm-up.
  const std::int64_t samples_in = static_cast<std::int64_t>(input.channels.front().values.size());
  json trim = {{"mode", options.trim == TrimMode::automatic ? "auto"
                        : options.trim == TrimMode::none    ? "none"
                                                            : "fixed"}};
  std::int64_t trim_samples = 0;
  if (options.trim == TrimMode::automatic) {
    std::vector<std::vector<double>> rates;
    std::vector<std::span<const double>> spans;
    for (const auto& c : input.channels) rates.push_back(as_rate(c.values, input.kind, input.rate_hz));
    for (const auto& r : rates) spans.emplace_back(r);
    const WarmupDecision d = detect_warmup(spans, input.rate_hz);
    trim_samples = d.trim_samples;
    trim["reason"] = d.reason;
    if (d.channel >= 0) trim["channel"] = input.channels[d.channel].name;
  } else if (options.trim == TrimMode::fixed) {
    if (!(options.trim_s >= 0)) throw Error("--trim must be >= 0 s");
    trim_samples = static_cast<std::int64_t>(std::llround(options.trim_s * input.rate_hz));
    trim["reason"] = "trimmed " + std::to_string(options.trim_s) + " s as asked (--trim)";
  } else {
    trim["reason"] = "not trimmed (--trim none)";
  }
  if (trim_samples >= samples_in) {
    throw Error("the trim (" + std::to_string(trim_samples) + " samples) leaves nothing of the " +
                std::to_string(samples_in) + "-sample log");
  }
  for (auto& c : input.channels) c.values.erase(c.values.begin(), c.values.begin() + trim_samples);
  trim["samples"] = trim_samples;
  trim["seconds"] = static_cast<double>(trim_samples) / input.rate_hz;
  const std::int64_t samples = samples_in - trim_samples;

  results["input"] = {{"path", input.path},
                      {"samples", samples},
                      {"samples_read", samples_in},
                      {"rate_hz", input.rate_hz},
                      {"duration_s", static_cast<double>(samples) / input.rate_hz},
                      {"kind", std::string(to_string(input.kind))},
                      {"trim", trim}};
  if (input.bytes >= 0) results["input"]["bytes"] = input.bytes;
  if (!input.crc32.empty()) results["input"]["crc32"] = input.crc32;
  if (input.timing) {
    const auto& t = *input.timing;
    json gaps = json::array();
    for (const auto& g : t.gaps) gaps.push_back({{"row", g.row}, {"line", g.line}, {"start_s", g.start_s}, {"length_s", g.length_s}});
    results["input"]["timing"] = {{"rate_hz", t.rate_hz}, {"mean_interval_s", t.mean_interval_s},
                                  {"jitter_s", t.jitter_s}, {"non_increasing", t.non_increasing},
                                  {"gaps", gaps}};
  } else {
    results["input"]["timing"] = nullptr;
  }

  // Allan curves, channel-parallel.
  std::vector<PhaseSeries> series;
  for (const auto& c : input.channels) {
    series.push_back(PhaseSeries::from_samples(c.values, input.kind, 1.0 / input.rate_hz));
  }
  const auto curves = compute_allan_curves(series, options.statistics, options.taus,
                                           options.confidence, options.threads);

  // PSD and noise density per channel.
  results["channels"] = json::array();
  for (std::size_t c = 0; c < input.channels.size(); ++c) {
    const auto& channel = input.channels[c];
    json entry = {{"name", channel.name},
                  {"unit", si_rate_unit(channel.role)},
                  {"input_unit", c < input.input_units.size() ? input.input_units[c] : ""}};
    if (channel.role) {
      entry["sensor"] = std::string(to_string(channel.role->sensor));
      entry["axis"] = std::string(1, static_cast<char>('x' + channel.role->axis));
    }
    entry["allan"] = json::array();
    for (const auto& curve : curves[c]) entry["allan"].push_back(curve_json(curve));
    const auto rate = as_rate(channel.values, input.kind, input.rate_hz);
    try {
      const PsdCurve psd = welch_psd(rate, input.rate_hz, options.welch);
      const NoiseDensity nd = noise_density(psd, std::nullopt, options.confidence);
      entry["psd"] = psd_json(log_binned(psd, options.psd_bins_per_decade), nd, si_rate_unit(channel.role));
    } catch (const Error& e) {
      warnings.push_back(channel.name + ": no PSD (" + e.what() + ")");
    }
    results["channels"].push_back(entry);
  }

  results["warnings"] = warnings;
  for (const auto& w : warnings) output.warnings.push_back(w.get<std::string>());
  output.results_json = results.dump(1) + "\n";
  return output;
}

}  // namespace sigmatau
