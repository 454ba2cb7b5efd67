// The analyze chain's shared stages (analysis_results.hpp): JSON of the input, trim, curves,
// PSD and dynamic windows; then fit -> filter covariances -> compliance -> results.json.
#include "analysis_results.hpp"

#include <cmath>
#include <cstdio>

#include "json_text.hpp"
#include "sigmatau/allan.hpp"
#include "sigmatau/display_units.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/filter_export.hpp"
#include "sigmatau/fit.hpp"
#include "sigmatau/sampling_limits.hpp"
#include "sigmatau/taus.hpp"
#include "sigmatau/units.hpp"

namespace sigmatau::detail {
namespace {

using nlohmann::json;

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

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
    json entry = {{"unit", std::string(si_unit(p.term, sensor))}};
    if (p.from_model_floor) {
      // Added terms: B read from the model's ADEV floor (the flicker coefficient beside it).
      entry["value"] = p.value;
      entry["ci_low"] = p.ci_low;
      entry["ci_high"] = p.ci_high;
      entry["from_model_floor"] = true;
      if (std::isfinite(p.flicker)) entry["flicker"] = p.flicker;
      if (std::isfinite(p.tau_min_s)) entry["tau_min_s"] = p.tau_min_s;
      if (std::isfinite(p.adev_min)) entry["adev_min"] = p.adev_min;
    } else if (p.in_model) {
      entry["value"] = p.value;
      entry["ci_low"] = p.ci_low;
      entry["ci_high"] = p.ci_high;
      if (std::isfinite(p.edf)) entry["edf"] = p.edf;
      if (p.lowered_to_curve < 1) entry["lowered_to_curve"] = p.lowered_to_curve;
      if (p.term == NoiseTerm::bias_instability && std::isfinite(p.tau_min_s)) entry["tau_min_s"] = p.tau_min_s;
      if (p.term == NoiseTerm::bias_instability && std::isfinite(p.adev_min)) entry["adev_min"] = p.adev_min;
    } else {
      entry["upper_bound"] = p.upper_bound;
    }
    parameters[key] = entry;
  }
  json gauss_markov = json::array();
  for (const auto& g : fit.gauss_markov) {
    gauss_markov.push_back({{"sigma", g.sigma}, {"ci_low", g.ci_low}, {"ci_high", g.ci_high},
                            {"tau_c_s", g.tau_c_s}, {"tau_c_ci_low_s", g.tau_c_ci_low_s},
                            {"tau_c_ci_high_s", g.tau_c_ci_high_s}, {"edf", number_or_null(g.edf)},
                            {"leading_points", g.leading_points},
                            {"unit", std::string(si_unit(NoiseTerm::gauss_markov, sensor))}});
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
    // Gauss-Markov and sinusoid have no IEEE line (read_off): drawn as curves below.
    if (term == NoiseTerm::gauss_markov || term == NoiseTerm::sinusoid) continue;
    const auto& p = fit.parameter(term);
    std::vector<double> line;
    // B's line is the flicker term's own (its floor 0.664 B): the flicker coefficient when the
    // reported value is the model's floor.
    const double value = p.from_model_floor ? p.flicker : p.value;
    for (double tau : taus) line.push_back(adev_line(term, value, tau));
    per_term[std::string(term_symbol(term))] = line;
    const ReadOff r = read_off(term);
    double tau_read = r.tau_read_s;
    if (term == NoiseTerm::bias_instability && std::isfinite(p.tau_min_s) && p.tau_min_s > 0) tau_read = p.tau_min_s;
    if (tau_read >= tau_lo && tau_read <= tau_hi) {
      readouts.push_back({{"term", std::string(term_symbol(term))}, {"tau", tau_read},
                          {"adev", adev_line(term, value, tau_read)}});
    }
  }
  // One curve per Gauss-Markov entry ("GM1", "GM2", ...): its exact continuous ADEV, a bump
  // with no straight-line asymptote to draw.
  for (std::size_t i = 0; i < terms.gauss_markov.size(); ++i) {
    const NoiseTerms one = only_gauss_markov(terms, i);
    std::vector<double> curve;
    for (double tau : taus) curve.push_back(std::sqrt(continuous_avar(one, tau)));
    per_term["GM" + std::to_string(i + 1)] = curve;
  }
  json sinusoid = nullptr;
  if (fit.sinusoid) {
    const auto& e = *fit.sinusoid;
    sinusoid = {{"amplitude", e.amplitude}, {"ci_low", e.ci_low}, {"ci_high", e.ci_high},
                {"frequency_hz", e.frequency_hz}, {"frequency_ci_low_hz", e.frequency_ci_low_hz},
                {"frequency_ci_high_hz", e.frequency_ci_high_hz}, {"edf", number_or_null(e.edf)},
                {"leading_points", e.leading_points},
                {"unit", std::string(si_unit(NoiseTerm::sinusoid, sensor))}};
    NoiseTerms one;
    one.sinusoid = Sinusoid{e.amplitude, e.frequency_hz, 0.0};
    std::vector<double> line;
    for (double tau : taus) line.push_back(std::sqrt(continuous_avar(one, NoiseTerm::sinusoid, tau)));
    per_term["SIN"] = line;
  }
  return {{"name", name},
          {"quantity", sensor == Sensor::gyro ? "angular_rate" : "specific_force"},
          {"sinusoid", sinusoid},
          {"model_terms", model_terms},
          {"parameters", parameters},
          {"gauss_markov", gauss_markov},
          {"method", std::string(to_string(fit.method))},
          {"chi_squared", number_or_null(fit.chi_squared)},
          {"bic", number_or_null(fit.bic)},
          {"dof", fit.dof},
          {"p_value", number_or_null(fit.p_value)},
          {"model_error", fit.model_error},
          {"left_out_taus_s", fit.left_out_taus_s},
          {"misfit_tau_s", number_or_null(fit.misfit_tau_s)},
          {"misfit_at_shortest_taus", fit.misfit_at_shortest_taus},
          {"model_adev", {{"tau", taus}, {"adev", total}}},
          {"terms_adev", per_term},
          {"readouts", readouts}};
}

json contradictions_json(const ChannelFit& fit, Sensor sensor) {
  json out = json::array();
  for (const auto& c : fit.contradictions) out.push_back(describe(c, sensor));
  return out;
}

/// Data-sheet noise densities are quoted to about 10 %: a smaller gap between the fit's N and
/// the PSD's changes no decision, however narrow the intervals of a long log make it.
constexpr double kWhiteNoiseGap = 1.1;

/// A note when the fit's N and the PSD's noise density (add_psd) differ by more than their
/// intervals allow and by more than kWhiteNoiseGap; "" otherwise or without a PSD.
std::string white_noise_gap(const std::string& name, Sensor sensor, const ParameterEstimate& n,
                            bool from_curve_readings, const json& channel, double confidence) {
  if (!n.in_model || !channel.contains("psd")) return "";
  const json& nd = channel["psd"]["noise_density"];
  const double psd = nd.value("value", 0.0), low = nd.value("ci_low", 0.0), high = nd.value("ci_high", 0.0);
  if (!(psd > 0) || !(n.value > 0)) return "";
  const double ratio = n.value / psd;
  if (std::max(ratio, 1 / ratio) <= kWhiteNoiseGap || (n.ci_low <= high && low <= n.ci_high)) return "";
  const std::string unit(display_unit(NoiseTerm::white, sensor));
  const double f = convert(1.0, si_unit(NoiseTerm::white, sensor), unit);
  const auto band = nd.value("band_hz", json::array({0.0, 0.0}));
  char text[900];
  std::snprintf(text, sizeof text,
                "%s: the white noise %s, N = %.4g %s [%.4g, %.4g], and the PSD's noise "
                "density over %.3g-%.3g Hz, %.4g %s [%.4g, %.4g], differ %.2fx, more than their "
                "%.1f %% intervals allow: the spectrum is not white across the band (%s; see the "
                "PSD plot). The filter files and the data-sheet verdicts use %s, the level "
                "the Allan curve (and a filter at this rate) sees over all frequencies; the PSD's "
                "value is what a data sheet means by noise density in a flat band",
                name.c_str(), from_curve_readings ? "read from the curve's -1/2 line" : "of the fit",
                n.value * f, unit.c_str(), n.ci_low * f, n.ci_high * f,
                band[0].get<double>(), band[1].get<double>(), psd * f, unit.c_str(), low * f,
                high * f, ratio, 100 * confidence,
                ratio > 1 ? "power outside the flat band, e.g. a resonance, adds to the short taus"
                          : "the spectrum falls toward Nyquist, e.g. the sensor filters its output",
                from_curve_readings ? "this read-out" : "the fit's N");
  return text;
}

std::string rate_label(double rate_hz) {
  char text[32];
  std::snprintf(text, sizeof text, "%gHz", rate_hz);
  return text;
}

}  // namespace

OutlierChecker outlier_checker(const std::string& channel, DataKind kind,
                               const std::string& input_unit) {
  OutlierOptions options;
  options.differences = kind == DataKind::phase;
  double to_si = 1;
  std::string unit;
  if (!input_unit.empty()) {
    try {
      to_si = parse_unit(input_unit).factor;
      unit = input_unit;
    } catch (const Error&) {
      to_si = 1;  // not a unit parse_unit knows: the message shows the SI value, unlabelled
    }
  }
  return OutlierChecker(channel, options, unit, to_si);
}

json results_header(const AnalysisOptions& options) {
  json results;
  results["tool"] = "sigmatau";
  results["version"] = SIGMATAU_VERSION;
  results["schema"] = 1;
  results["created_utc"] = options.created_utc;
  results["confidence"] = options.confidence;
  results["edf_model"] = options.edf_model == EdfModel::discrete ? "discrete" : "greenhall";
  return results;
}

json trim_mode_json(const AnalysisOptions& options) {
  return {{"mode", options.trim == TrimMode::automatic ? "auto"
                   : options.trim == TrimMode::none    ? "none"
                                                       : "fixed"}};
}

std::int64_t requested_trim(const AnalysisOptions& options, double rate_hz, json& trim) {
  if (options.trim == TrimMode::fixed) {
    if (!(options.trim_s >= 0)) throw Error("--trim must be >= 0 s");
    trim["reason"] = "trimmed " + std::to_string(options.trim_s) + " s as asked (--trim)";
    return checked_samples(options.trim_s, rate_hz, "trim_s");
  }
  trim["reason"] = "not trimmed (--trim none)";
  return 0;
}

void record_trim(std::int64_t trim_samples, std::int64_t samples_in, double rate_hz, json& trim) {
  if (trim_samples >= samples_in) {
    throw Error("the trim (" + std::to_string(trim_samples) + " samples) leaves nothing of the " +
                std::to_string(samples_in) + "-sample log");
  }
  trim["samples"] = trim_samples;
  trim["seconds"] = static_cast<double>(trim_samples) / rate_hz;
}

json input_json(const AnalysisInput& input, std::int64_t samples, std::int64_t samples_in,
                const json& trim) {
  json j = {{"path", input.path},
            {"samples", samples},
            {"samples_read", samples_in},
            {"rate_hz", input.rate_hz},
            {"duration_s", static_cast<double>(samples) / input.rate_hz},
            {"kind", std::string(to_string(input.kind))},
            {"trim", trim}};
  if (input.bytes >= 0) j["bytes"] = input.bytes;
  if (!input.crc32.empty()) j["crc32"] = input.crc32;
  if (input.timing) {
    const auto& t = *input.timing;
    json gaps = json::array();
    for (const auto& g : t.gaps) gaps.push_back({{"row", g.row}, {"line", g.line}, {"start_s", g.start_s}, {"length_s", g.length_s}});
    j["timing"] = {{"rate_hz", t.rate_hz}, {"mean_interval_s", t.mean_interval_s},
                   {"jitter_s", t.jitter_s}, {"non_increasing", t.non_increasing},
                   {"gaps", gaps}};
    if (t.truncated_at_byte >= 0) {
      // A bag recording cut short and read with --truncated use: where it ends.
      j["timing"]["truncated_at_byte"] = t.truncated_at_byte;
      j["timing"]["truncated_file"] = t.truncated_file;
    }
  } else {
    j["timing"] = nullptr;
  }
  return j;
}

json channel_json(const AnalysisChannel& channel, const std::string& input_unit,
                  const std::vector<AllanCurve>& curves) {
  json entry = {{"name", channel.name},
                {"unit", si_rate_unit(channel.role)},
                {"input_unit", input_unit}};
  if (channel.role) {
    entry["sensor"] = std::string(to_string(channel.role->sensor));
    entry["axis"] = std::string(1, static_cast<char>('x' + channel.role->axis));
  }
  entry["allan"] = json::array();
  for (const auto& curve : curves) entry["allan"].push_back(curve_json(curve));
  return entry;
}

void add_psd(json& entry, const PsdCurve& psd, const AnalysisChannel& channel,
             const AnalysisOptions& options) {
  const NoiseDensity nd = noise_density(psd, std::nullopt, options.confidence);
  entry["psd"] = psd_json(log_binned(psd, options.psd_bins_per_decade), nd, si_rate_unit(channel.role));
}

std::int64_t dynamic_window_length(std::int64_t samples, int windows) {
  return 2 * samples / (windows + 1);
}

json dynamic_window_json(const PhaseSeries& window, std::int64_t start, std::int64_t length,
                         double rate_hz) {
  const auto m = averaging_factors(TauSpec{}, Statistic::oadev, window.size(), window.tau0_s());
  std::vector<double> taus, devs;
  for (const auto& p : compute_deviation(window, Statistic::oadev, m)) {
    taus.push_back(p.tau_s);
    devs.push_back(p.dev);
  }
  return {{"start_s", static_cast<double>(start) / rate_hz},
          {"end_s", static_cast<double>(start + length) / rate_hz},
          {"tau", taus},
          {"oadev", devs}};
}

void finish_results(json& results, json& warnings, const std::vector<AnalysisChannel>& channels,
                    const std::vector<std::vector<AllanCurve>>& curves, std::int64_t samples,
                    DataKind kind, double rate_hz, const AnalysisOptions& options,
                    AnalysisOutput& output) {
  // Noise-term fit of every sensor channel (joint fit, model chosen by BIC) on the first curve,
  // which must be OADEV for the fit.
  std::vector<MeasuredParameter> measured;
  json fits = json::array();
  const bool first_is_oadev = options.statistics.front() == Statistic::oadev;
  for (std::size_t c = 0; c < channels.size(); ++c) {
    const auto& channel = channels[c];
    if (!channel.role) continue;
    if (!first_is_oadev) {
      warnings.push_back("noise terms are fitted from OADEV: put oadev first in --stat to fit them");
      break;
    }
    FitOptions fit_options;
    fit_options.confidence_level = options.confidence;
    fit_options.tau_min_s = options.fit_tau_min_s;
    fit_options.tau_max_s = options.fit_tau_max_s;
    fit_options.added_terms = options.fit_added_terms;
    CurveSource source;
    source.tau0_s = 1.0 / rate_hz;
    // Split: the segments' samples counted as one record (the fit's OAVAR covariance assumes
    // one contiguous series; pooled segments have slightly fewer terms at long tau).
    source.n_phase_points = samples + 1 - (kind == DataKind::phase ? 1 : 0);
    source.flicker_taps = options.flicker_taps;
    try {
      const NoiseFit fit = fit_noise(curves[c].front(), source, fit_options);
      const ChannelFit& joint = *fit.joint;
      // What sheets and filters take: the joint fit, or the curve's read-outs standing in for a
      // joint fit that is rejected or contradicts the curve (consistency guards, fit.hpp).
      const ChannelFit& reported = fit.reported();
      const bool readings = fit.readings.has_value();
      const Sensor sensor = channel.role->sensor;
      if (const std::string w = misfit_warning(joint, channel.name); !w.empty()) warnings.push_back(w);
      if (const std::string w = left_out_warning(joint, channel.name); !w.empty()) warnings.push_back(w);
      if (const std::string w = short_log_warning(joint, channel.name); !w.empty()) warnings.push_back(w);
      if (const std::string w = readings_warning(fit, channel.name, sensor); !w.empty()) warnings.push_back(w);
      if (c < results["channels"].size()) {
        const std::string w = white_noise_gap(channel.name, sensor, reported.parameter(NoiseTerm::white),
                                              readings, results["channels"][c], options.confidence);
        if (!w.empty()) warnings.push_back(w);
      }
      const auto& points = curves[c].front().points;
      json entry = fit_json(channel.name, sensor, reported, points.front().value.tau_s,
                            points.back().value.tau_s);
      // The axis as analysed (--gyro / --accel, or by name): a channel named c0 has none in
      // its name for the filter export to read.
      entry["axis"] = std::string(1, static_cast<char>('x' + channel.role->axis));
      entry["contradictions"] = contradictions_json(reported, sensor);
      if (readings) {
        entry["reported_from"] = "curve_readings";
        entry["readings_reason"] = fit.readings_reason;
        json rejected = fit_json(channel.name, sensor, joint, points.front().value.tau_s,
                                 points.back().value.tau_s);
        rejected["contradictions"] = contradictions_json(joint, sensor);
        entry["joint"] = rejected;
      }
      fits.push_back(entry);
      // The reported model beside every fitted point of the curve (and the joint fit's, when
      // the read-outs stand in for it), so the reader sees where the model departs.
      if (c < results["channels"].size() && !results["channels"][c]["allan"].empty()) {
        json& curve_points = results["channels"][c]["allan"][0]["points"];
        const auto model = model_deviation(reported, curves[c].front(), source, fit_options);
        const auto joint_model = model_deviation(joint, curves[c].front(), source, fit_options);
        for (std::size_t j = 0; j < model.size() && j < curve_points.size(); ++j) {
          if (!std::isfinite(model[j])) continue;
          curve_points[j]["model_dev"] = model[j];
          if (readings) curve_points[j]["joint_model_dev"] = joint_model[j];
        }
      }
      const std::string axis(1, static_cast<char>('x' + channel.role->axis));
      const std::pair<NoiseTerm, MeasuredQuantity> kMeasured[] = {
          {NoiseTerm::white, MeasuredQuantity::white_noise},
          {NoiseTerm::bias_instability, MeasuredQuantity::bias_instability},
          {NoiseTerm::rate_random_walk, MeasuredQuantity::rate_random_walk}};
      const std::size_t first_measured = measured.size();
      for (const auto& [term, quantity] : kMeasured) {
        const auto& p = reported.parameter(term);
        // B read from the model's floor (added terms standing in for flicker) is measured too.
        if (p.in_model || p.from_model_floor) {
          measured.push_back({sensor, quantity, axis, p.value, p.ci_low, p.ci_high});
        } else {
          // Left out by the fit: still checked against the sheet, by its upper bound.
          measured.push_back({.sensor = sensor,
                              .quantity = quantity,
                              .axis = axis,
                              .detected = false,
                              .upper_bound = p.upper_bound});
        }
      }
      // A rejected fit (p below kMisfitPValue) marks the verdicts built on it; the read-outs
      // that stand in for one say so instead.
      for (std::size_t i = first_measured; i < measured.size(); ++i) {
        if (readings) {
          measured[i].from_curve_readings = true;
        } else {
          measured[i].fit_p_value = joint.p_value;
        }
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
  // The files also carry what the fit rests on: rejected fits, implausible units (recorded by
  // the data checks in "unit_warnings"), the method, terms left out, a rate above the log's.
  std::optional<FitForFilter> present;
  if (!fits.empty()) {
    json fit_doc = {{"fit", results["fit"]}, {"input", {{"rate_hz", rate_hz}}}};
    if (results.contains("unit_warnings")) fit_doc["unit_warnings"] = results["unit_warnings"];
    present = read_fit_for_filter(json_text(fit_doc), "the fit above");
  }
  if (present) {
    std::vector<double> rates = options.filter_rates_hz;
    if (rates.empty()) rates.push_back(rate_hz);
    for (double rate : rates) {
      ConvertOptions convert;
      convert.rate_hz = rate;
      convert.bias_model = options.bias_model;
      convert.convention = options.convention;
      try {
        const DiscreteNoise noise = convert_fit(*present, convert, "noise terms fitted by sigmatau analyze");
        // The fit's and the data checks' warnings are already in `warnings`; the rate is new.
        if (!noise.rate_note.empty()) warnings.push_back(noise.rate_note);
        const std::string label = rate_label(rate);
        const std::pair<ExportFormat, std::string> kFiles[] = {
            {ExportFormat::json, "filter_" + label + ".json"},
            {ExportFormat::kalibr, "kalibr_imu_" + label + ".yaml"},
            {ExportFormat::openvins, "openvins_imu_" + label + ".yaml"},
            {ExportFormat::vins_fusion, "vins_fusion_" + label + ".yaml"},
            {ExportFormat::gtsam, "gtsam_" + label + ".txt"},
            {ExportFormat::px4, "px4_ekf2_" + label + ".params"}};
        json entry = {{"rate_hz", rate}, {"explain", noise.explain}, {"files", json::array()}};
        // A file its filter would read with values missing (VINS-Fusion as 0, PX4 and GTSAM as
        // their defaults) is not written: the warning says which and how to write it.
        std::string not_written, lacking;
        for (const auto& [format, file] : kFiles) {
          if (const auto missing = missing_filter_values(noise, format); !missing.empty()) {
            not_written += (not_written.empty() ? "" : ", ") + file;
            lacking = missing_values_text(missing);
            entry["not_written"].push_back(file);
            continue;
          }
          const std::string text = export_filter_config(noise, format);
          output.filter_files[file] = text;
          entry["files"].push_back(file);
          if (format == ExportFormat::json) entry["discrete"] = json::parse(text);
        }
        if (!not_written.empty()) {
          warnings.push_back(
              "not written: " + not_written + ": their filters need the white noise and bias of "
              "both sensors and the log gives no " + lacking + " (Kalibr and OpenVINS " +
              "would stop, VINS-Fusion read 0, PX4 and GTSAM keep their defaults); filter_" +
              label + ".json holds what the log gives, and sigmatau convert on this results.json "
              "with the missing terms typed beside it writes the others");
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
  output.results_json = json_text(results, 1) + "\n";
}

}  // namespace sigmatau::detail
