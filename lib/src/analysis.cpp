// The analyze chain: trim -> curves -> PSD -> fit -> filter covariances -> compliance ->
// results.json. Each stage reads only what the previous ones produced.
#include "sigmatau/analysis.hpp"

#include <nlohmann/json.hpp>
#include <zlib.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>

#include "sigmatau/allan_curve.hpp"
#include "sigmatau/allan_segments.hpp"
#include "sigmatau/data_checks.hpp"
#include "sigmatau/units.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/filter_export.hpp"
#include "sigmatau/fit.hpp"
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

/// SI units of the fitted parameters (noise_model.hpp), per sensor.
std::string parameter_unit(NoiseTerm term, Sensor sensor) {
  const bool gyro = sensor == Sensor::gyro;
  switch (term) {
    case NoiseTerm::quantization: return gyro ? "rad" : "m/s";
    case NoiseTerm::white: return gyro ? "rad/s/sqrt(Hz)" : "m/s^2/sqrt(Hz)";
    case NoiseTerm::bias_instability: return gyro ? "rad/s" : "m/s^2";
    case NoiseTerm::rate_random_walk: return gyro ? "rad/s^2/sqrt(Hz)" : "m/s^3/sqrt(Hz)";
    case NoiseTerm::rate_ramp: return gyro ? "rad/s^2" : "m/s^3";
    default: return "";
  }
}

/// Points of the model drawn over the curve: the fitted total and each term's asymptote.
constexpr int kModelPoints = 60;

/// The fit of one channel in the JSON shape, plus what the plots draw.
json fit_json(const std::string& name, Sensor sensor, const ChannelFit& fit, double tau_lo,
              double tau_hi) {
  json parameters = json::object();
  json model_terms = json::array();
  for (NoiseTerm term : fit.model_terms) model_terms.push_back(std::string(term_symbol(term)));
  for (const auto& p : fit.parameters) {
    const std::string key(term_symbol(p.term));
    json entry = {{"unit", parameter_unit(p.term, sensor)}};
    if (p.in_model) {
      entry["value"] = p.value;
      entry["ci_low"] = p.ci_low;
      entry["ci_high"] = p.ci_high;
      if (std::isfinite(p.edf)) entry["edf"] = p.edf;
      if (p.term == NoiseTerm::bias_instability && std::isfinite(p.tau_min_s)) entry["tau_min_s"] = p.tau_min_s;
    } else {
      entry["upper_bound"] = p.upper_bound;
    }
    parameters[key] = entry;
  }
  // The fitted model and each term's IEEE asymptote on a log grid over the curve's taus.
  const NoiseTerms terms = fit.noise_terms();
  std::vector<double> taus, total;
  json per_term = json::object();
  for (int i = 0; i < kModelPoints; ++i) {
    const double tau = tau_lo * std::pow(tau_hi / tau_lo, static_cast<double>(i) / (kModelPoints - 1));
    taus.push_back(tau);
    total.push_back(std::sqrt(continuous_avar(terms, tau)));
  }
  json readouts = json::array();
  for (NoiseTerm term : fit.model_terms) {
    const auto& p = fit.parameter(term);
    std::vector<double> line;
    for (double tau : taus) line.push_back(adev_line(term, p.value, tau));
    per_term[std::string(term_symbol(term))] = line;
    const ReadOff r = read_off(term);
    double tau_read = r.tau_read_s;
    if (term == NoiseTerm::bias_instability && std::isfinite(p.tau_min_s) && p.tau_min_s > 0) tau_read = p.tau_min_s;
    if (tau_read >= tau_lo && tau_read <= tau_hi) {
      readouts.push_back({{"term", std::string(term_symbol(term))}, {"tau", tau_read},
                          {"adev", adev_line(term, p.value, tau_read)}});
    }
  }
  return {{"name", name},
          {"quantity", sensor == Sensor::gyro ? "angular_rate" : "specific_force"},
          {"model_terms", model_terms},
          {"parameters", parameters},
          {"method", std::string(to_string(fit.method))},
          {"chi_squared", number_or_null(fit.chi_squared)},
          {"bic", number_or_null(fit.bic)},
          {"model_adev", {{"tau", taus}, {"adev", total}}},
          {"terms_adev", per_term},
          {"readouts", readouts}};
}

std::string rate_label(double rate_hz) {
  char text[32];
  std::snprintf(text, sizeof text, "%gHz", rate_hz);
  return text;
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

  // Data checks on the log as read: saturation and stuck runs per channel, and whether each
  // triad's magnitude is plausible for its declared unit (a static log is assumed).
  try {
    std::array<std::vector<std::span<const double>>, 2> triad_axes;
    std::array<std::vector<std::string>, 2> triad_names;
    std::array<std::string, 2> triad_unit;
    for (std::size_t c = 0; c < input.channels.size(); ++c) {
      const auto& channel = input.channels[c];
      for (const auto& w : check_runs(channel.values, channel.name)) warnings.push_back(w.message);
      if (!channel.role || input.kind != DataKind::rate) continue;
      const int s = channel.role->sensor == Sensor::gyro ? 0 : 1;
      triad_axes[s].emplace_back(channel.values);
      triad_names[s].push_back(channel.name);
      triad_unit[s] = c < input.input_units.size() ? input.input_units[c] : "";
    }
    for (int s = 0; s < 2; ++s) {
      if (triad_axes[s].empty()) continue;
      const std::string unit = triad_unit[s].empty() ? (s == 0 ? "rad/s" : "m/s^2") : triad_unit[s];
      const double to_si = parse_unit(unit).factor;
      const auto w = s == 0 ? check_gyro_unit(triad_axes[s], triad_names[s], unit, to_si)
                            : (triad_axes[s].size() == 3
                                   ? check_accel_unit(triad_axes[s], triad_names[s], unit, to_si)
                                   : std::nullopt);
      if (w) warnings.push_back(w->message);
    }
  } catch (const Error& e) {
    warnings.push_back(std::string("data checks skipped: ") + e.what());
  }

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

  // --gaps split: the contiguous segments left after the trim. Curves and PSD are computed per
  // segment and pooled (allan_segments.hpp), so no difference or PSD window spans a gap.
  std::vector<SegmentRange> segments;
  if (input.timing && input.timing->segment_starts.size() > 1) {
    segments = segment_ranges(input.timing->segment_starts, samples_in, trim_samples);
    json list = json::array();
    for (const auto& r : segments) {
      list.push_back({{"first_sample", r.begin}, {"samples", r.size()},
                      {"duration_s", static_cast<double>(r.size()) / input.rate_hz}});
    }
    results["input"]["segments"] = list;
  }
  const bool split = segments.size() > 1;

  // Allan curves, channel-parallel.
  std::vector<std::vector<AllanCurve>> curves;
  if (split) {
    std::vector<std::vector<PhaseSeries>> channel_segments;
    for (const auto& c : input.channels) {
      channel_segments.push_back(segment_series(c.values, segments, input.kind, 1.0 / input.rate_hz));
    }
    curves = compute_segmented_allan_curves(channel_segments, options.statistics, options.taus,
                                            options.confidence, options.threads);
    if (options.dynamic_windows > 0) {
      warnings.push_back("--gaps split: the dynamic Allan windows are taken over the segments "
                         "joined end to end, so a window may span a gap");
    }
  } else {
    std::vector<PhaseSeries> series;
    for (const auto& c : input.channels) {
      series.push_back(PhaseSeries::from_samples(c.values, input.kind, 1.0 / input.rate_hz));
    }
    curves = compute_allan_curves(series, options.statistics, options.taus, options.confidence,
                                  options.threads);
  }

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
    if (options.dynamic_windows > 0) {
      // Half-overlapping windows: K windows of length 2 M / (K + 1) starting every half window.
      const auto total = static_cast<std::int64_t>(channel.values.size());
      const std::int64_t length = 2 * total / (options.dynamic_windows + 1);
      json windows = json::array();
      if (length >= 16) {
        for (int w = 0; w < options.dynamic_windows; ++w) {
          const std::int64_t start = w * length / 2;
          const std::span<const double> part(channel.values.data() + start, static_cast<std::size_t>(length));
          const PhaseSeries window = PhaseSeries::from_samples(part, input.kind, 1.0 / input.rate_hz);
          const auto m = averaging_factors(TauSpec{}, Statistic::oadev, window.size(), window.tau0_s());
          std::vector<double> taus, devs;
          for (const auto& p : compute_deviation(window, Statistic::oadev, m)) {
            taus.push_back(p.tau_s);
            devs.push_back(p.dev);
          }
          windows.push_back({{"start_s", static_cast<double>(start) / input.rate_hz},
                             {"end_s", static_cast<double>(start + length) / input.rate_hz},
                             {"tau", taus},
                             {"oadev", devs}});
        }
      }
      entry["dynamic"] = {{"window_s", static_cast<double>(length) / input.rate_hz}, {"windows", windows}};
    }
    // Rates per contiguous segment (one segment unless split): Welch windows stay inside one.
    std::vector<std::vector<double>> rates;
    if (split) {
      for (const auto& r : segments) {
        const std::vector<double> part(channel.values.begin() + r.begin,
                                       channel.values.begin() + r.end);
        rates.push_back(as_rate(part, input.kind, input.rate_hz));
      }
    } else {
      rates.push_back(as_rate(channel.values, input.kind, input.rate_hz));
    }
    try {
      const std::vector<std::span<const double>> stretches(rates.begin(), rates.end());
      const PsdCurve psd = split ? welch_psd_stretches(stretches, input.rate_hz, options.welch)
                                 : welch_psd(rates.front(), input.rate_hz, options.welch);
      const NoiseDensity nd = noise_density(psd, std::nullopt, options.confidence);
      entry["psd"] = psd_json(log_binned(psd, options.psd_bins_per_decade), nd, si_rate_unit(channel.role));
    } catch (const Error& e) {
      warnings.push_back(channel.name + ": no PSD (" + e.what() + ")");
    }
    results["channels"].push_back(entry);
  }

  // Noise-term fit of every sensor channel (joint fit, model chosen by BIC) on the first curve,
  // which must be OADEV for the fit.
  std::vector<MeasuredParameter> measured;
  json fits = json::array();
  const bool first_is_oadev = options.statistics.front() == Statistic::oadev;
  for (std::size_t c = 0; c < input.channels.size(); ++c) {
    const auto& channel = input.channels[c];
    if (!channel.role) continue;
    if (!first_is_oadev) {
      warnings.push_back("noise terms are fitted from OADEV: put oadev first in --stat to fit them");
      break;
    }
    FitOptions fit_options;
    fit_options.confidence_level = options.confidence;
    CurveSource source;
    source.tau0_s = 1.0 / input.rate_hz;
    // Split: the segments' samples counted as one record (the fit's OAVAR covariance assumes
    // one contiguous series; pooled segments have slightly fewer terms at long tau).
    source.n_phase_points = samples + 1 - (input.kind == DataKind::phase ? 1 : 0);
    source.flicker_taps = options.flicker_taps;
    try {
      const NoiseFit fit = fit_noise(curves[c].front(), source, fit_options);
      const ChannelFit& joint = *fit.joint;
      const auto& points = curves[c].front().points;
      fits.push_back(fit_json(channel.name, channel.role->sensor, joint, points.front().value.tau_s,
                              points.back().value.tau_s));
      const std::string axis(1, static_cast<char>('x' + channel.role->axis));
      const std::pair<NoiseTerm, MeasuredQuantity> kMeasured[] = {
          {NoiseTerm::white, MeasuredQuantity::white_noise},
          {NoiseTerm::bias_instability, MeasuredQuantity::bias_instability},
          {NoiseTerm::rate_random_walk, MeasuredQuantity::rate_random_walk}};
      for (const auto& [term, quantity] : kMeasured) {
        const auto& p = joint.parameter(term);
        if (p.in_model) measured.push_back({channel.role->sensor, quantity, axis, p.value, p.ci_low, p.ci_high});
      }
    } catch (const Error& e) {
      warnings.push_back(channel.name + ": no noise-term fit (" + e.what() + ")");
    }
  }
  results["fit"] = {{"method", "joint"}, {"confidence", options.confidence}, {"channels", fits}};

  // Filter covariances and exports at each rate.
  results["filter"] = json::array();
  // The same conversion as `convert --fit` on this fit (terms kept on some axes only are given
  // their upper bound on the others: convert.hpp, triads_from_fit_json).
  std::vector<TriadNoise> present;
  if (!fits.empty()) present = triads_from_fit_json(results["fit"].dump(), "the fit above");
  if (!present.empty()) {
    std::vector<double> rates = options.filter_rates_hz;
    if (rates.empty()) rates.push_back(input.rate_hz);
    for (double rate : rates) {
      ConvertOptions convert;
      convert.rate_hz = rate;
      convert.bias_model = options.bias_model;
      convert.convention = options.convention;
      try {
        const DiscreteNoise noise = convert_noise(present, convert, "noise terms fitted by sigmatau analyze");
        const std::string label = rate_label(rate);
        const std::pair<ExportFormat, std::string> kFiles[] = {
            {ExportFormat::json, "filter_" + label + ".json"},
            {ExportFormat::kalibr, "kalibr_imu_" + label + ".yaml"},
            {ExportFormat::openvins, "openvins_imu_" + label + ".yaml"},
            {ExportFormat::vins_fusion, "vins_fusion_" + label + ".yaml"},
            {ExportFormat::gtsam, "gtsam_" + label + ".txt"},
            {ExportFormat::px4, "px4_ekf2_" + label + ".params"}};
        json entry = {{"rate_hz", rate}, {"explain", noise.explain}, {"files", json::array()}};
        for (const auto& [format, file] : kFiles) {
          const std::string text = export_filter_config(noise, format);
          output.filter_files[file] = text;
          entry["files"].push_back(file);
          if (format == ExportFormat::json) entry["discrete"] = json::parse(text);
        }
        results["filter"].push_back(entry);
      } catch (const Error& e) {
        warnings.push_back("no filter covariances at " + rate_label(rate) + " (" + e.what() + ")");
      }
    }
  }

  // Data-sheet compliance and the sheet's lines for the plots.
  results["compliance"] = nullptr;
  if (options.spec) {
    const DataSheet& sheet = *options.spec;
    ComplianceOptions compliance_options;
    compliance_options.convention = options.convention;
    const auto items = check_compliance(measured, sheet, compliance_options);
    results["compliance"] = json::parse(compliance_json(items, sheet, compliance_options));
    json lines = json::object();
    for (Sensor sensor : {Sensor::gyro, Sensor::accel}) {
      if (!sheet.sensor(sensor)) continue;
      try {
        const TriadNoise t = triad_from_data_sheet(sheet, sensor, options.convention);
        json l = json::object();
        if (t.axes[0].white) l["white"] = *t.axes[0].white;
        if (t.axes[0].bias_instability) l["bias_floor"] = kFlickerFloorFactor * *t.axes[0].bias_instability;
        if (!l.empty()) lines[std::string(to_string(sensor))] = l;
      } catch (const Error&) {
        // A section without noise figures has no lines to draw.
      }
    }
    results["spec_lines"] = lines;
  }

  results["warnings"] = warnings;
  for (const auto& w : warnings) output.warnings.push_back(w.get<std::string>());
  output.results_json = results.dump(1) + "\n";
  return output;
}

}  // namespace sigmatau
