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
#include <optional>
#include <string>
#include <vector>

#include "analysis_results.hpp"
#include "dynamic_windows.hpp"
#include "parallel_items.hpp"
#include "sigmatau/allan_curve.hpp"
#include "sigmatau/allan_segments.hpp"
#include "sigmatau/data_checks.hpp"
#include "sigmatau/sampling_limits.hpp"
#include "sigmatau/units.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/rate_series.hpp"
#include "sigmatau/warmup.hpp"

namespace sigmatau {
namespace {

using nlohmann::json;

}  // namespace

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
  checked_rate_hz(input.rate_hz, input.path + ": rate_hz");
  if (options.statistics.empty()) throw Error("no statistic asked for");
  AnalysisOutput output;
  json results = detail::results_header(options);
  json warnings = json::array();
  results["unit_warnings"] = json::array();

  // Data checks on the log as read: saturation and stuck runs and outliers per channel, and
  // whether each triad's magnitude is plausible for its declared unit (a static log is assumed).
  try {
    std::array<std::vector<std::span<const double>>, 2> triad_axes;
    std::array<std::vector<std::string>, 2> triad_names;
    std::array<std::string, 2> triad_unit;
    // The run and outlier checks channel-parallel, their warnings joined in channel order.
    std::vector<std::vector<std::string>> found(input.channels.size());
    detail::for_each_item_parallel(input.channels.size(), options.threads, [&](std::size_t c) {
      const auto& channel = input.channels[c];
      for (const auto& w : check_runs(channel.values, channel.name)) found[c].push_back(w.message);
      OutlierChecker outliers = detail::outlier_checker(
          channel.name, input.kind, c < input.input_units.size() ? input.input_units[c] : "");
      outliers.add(channel.values);
      if (const auto w = outliers.finish()) found[c].push_back(w->message);
    });
    for (std::size_t c = 0; c < input.channels.size(); ++c) {
      const auto& channel = input.channels[c];
      for (std::string& w : found[c]) warnings.push_back(std::move(w));
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
      if (w) {
        warnings.push_back(w->message);
        // Also apart, for the filter files' headers (convert_fit.cpp).
        results["unit_warnings"].push_back({{"channels", w->channel}, {"likely_unit", w->likely_unit},
                                            {"message", w->message}});
      }
    }
  } catch (const Error& e) {
    warnings.push_back(std::string("data checks skipped: ") + e.what());
  }

  // Trim the warm-up.
  const std::int64_t samples_in = static_cast<std::int64_t>(input.channels.front().values.size());
  json trim = detail::trim_mode_json(options);
  std::int64_t trim_samples = 0;
  if (options.trim == TrimMode::automatic) {
    // detect_warmup, its channels' block means computed in parallel.
    std::vector<WarmupBlocks> blocks(input.channels.size());
    detail::for_each_item_parallel(input.channels.size(), options.threads, [&](std::size_t c) {
      blocks[c] = warmup_blocks(to_rate_series(input.channels[c].values, input.kind, input.rate_hz));
    });
    const WarmupDecision d = decide_warmup(blocks, input.rate_hz);
    trim_samples = d.trim_samples;
    trim["reason"] = d.reason;
    if (d.channel >= 0) trim["channel"] = input.channels[d.channel].name;
  } else {
    trim_samples = detail::requested_trim(options, input.rate_hz, trim);
  }
  detail::record_trim(trim_samples, samples_in, input.rate_hz, trim);
  for (auto& c : input.channels) c.values.erase(c.values.begin(), c.values.begin() + trim_samples);
  const std::int64_t samples = samples_in - trim_samples;
  results["input"] = detail::input_json(input, samples, samples_in, trim);

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
                                            options.confidence, options.threads,
                                            options.edf_model);
    if (options.dynamic_windows > 0) {
      warnings.push_back("--gaps split: the dynamic Allan windows are taken over the segments "
                         "joined end to end, so a window may span a gap");
    }
  } else {
    std::vector<std::optional<PhaseSeries>> built(input.channels.size());
    detail::for_each_item_parallel(input.channels.size(), options.threads, [&](std::size_t c) {
      built[c] = PhaseSeries::from_samples(input.channels[c].values, input.kind, 1.0 / input.rate_hz);
    });
    std::vector<PhaseSeries> series;
    for (auto& b : built) series.push_back(std::move(*b));
    curves = compute_allan_curves(series, options.statistics, options.taus, options.confidence,
                                  options.threads, options.edf_model);
  }

  // PSD and noise density per channel, channel-parallel (each channel's entry and warnings
  // kept apart, then joined in channel order: the same document as one after the other).
  std::vector<json> entries(input.channels.size());
  std::vector<std::vector<std::string>> channel_warnings(input.channels.size());
  detail::for_each_item_parallel(input.channels.size(), options.threads, [&](std::size_t c) {
    std::vector<std::string>& notes = channel_warnings[c];
    const auto& channel = input.channels[c];
    json entry = detail::channel_json(channel, c < input.input_units.size() ? input.input_units[c] : "",
                                      curves[c]);
    if (options.dynamic_windows > 0) {
      const auto total = static_cast<std::int64_t>(channel.values.size());
      const detail::DynamicWindows plan = detail::plan_dynamic_windows(total, options.dynamic_windows);
      const std::int64_t length = plan.length;
      if (c == 0 && !plan.warning.empty()) notes.push_back(plan.warning);
      json windows = json::array();
      for (int w = 0; w < plan.windows; ++w) {
        const std::int64_t start = w * length / 2;
        const std::span<const double> part(channel.values.data() + start, static_cast<std::size_t>(length));
        const PhaseSeries window = PhaseSeries::from_samples(part, input.kind, 1.0 / input.rate_hz);
        windows.push_back(detail::dynamic_window_json(window, start, length, input.rate_hz));
      }
      entry["dynamic"] = {{"window_s", static_cast<double>(length) / input.rate_hz}, {"windows", windows}};
    }
    // Rates per contiguous segment (one segment unless split): Welch windows stay inside one.
    std::vector<std::vector<double>> rates;
    if (split) {
      for (const auto& r : segments) {
        std::vector<double> part(channel.values.begin() + r.begin,
                                 channel.values.begin() + r.end);
        rates.push_back(to_rate_series(std::move(part), input.kind, input.rate_hz));
      }
    } else {
      rates.push_back(to_rate_series(channel.values, input.kind, input.rate_hz));
    }
    try {
      const std::vector<std::span<const double>> stretches(rates.begin(), rates.end());
      const PsdCurve psd = split ? welch_psd_stretches(stretches, input.rate_hz, options.welch)
                                 : welch_psd(rates.front(), input.rate_hz, options.welch);
      detail::add_psd(entry, psd, channel, options);
    } catch (const Error& e) {
      notes.push_back(channel.name + ": no PSD (" + e.what() + ")");
    }
    entries[c] = std::move(entry);
  });
  results["channels"] = json::array();
  for (std::size_t c = 0; c < entries.size(); ++c) {
    for (std::string& w : channel_warnings[c]) warnings.push_back(std::move(w));
    results["channels"].push_back(std::move(entries[c]));
  }

  detail::finish_results(results, warnings, input.channels, curves, samples, input.kind,
                         input.rate_hz, options, output);
  return output;
}

}  // namespace sigmatau
