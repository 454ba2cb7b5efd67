// The analyze chain in bounded memory (analysis.hpp, run_analysis_bounded): the same stages and
// numbers as run_analysis (analysis.cpp), with every O(samples) array on disk.
//
// Passes: (1) the log, once: data checks (RunChecker, OutlierChecker, unit sums), the count,
// and each selected channel's SI values into a ValueSpill; (2) with --trim auto, each channel's
// warm-up block means (WarmupBlockSums on the rates); (3) per group of --threads channels, the
// trimmed values twice: PhaseSeriesBuilder::scan plus the Welch PSD, then
// PhaseSeriesBuilder::append into spilled storage; the group's curves
// (compute_allan_curve_bounded); its dynamic windows, each built the same way. Every sum runs
// over the same values in the same order as the in-memory path, so results.json is the same to
// the last bit (tests/test_analysis_bounded.cpp, tests/cli/analyze_bounded.cmake,
// tests/cli/analyze_outliers.cmake).
//
// Glossary: n = samples read per channel; trim = samples dropped at the start; rates = the
// series the PSD and the warm-up see (increments x rate, phase differences x rate, rates as is).
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <mutex>
#include <thread>

#include "analysis_results.hpp"
#include "dynamic_windows.hpp"
#include "analysis_spill.hpp"
#include "parallel_items.hpp"
#include "sigmatau/allan_out_of_core.hpp"
#include "sigmatau/analysis.hpp"
#include "sigmatau/data_checks.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/sampling_limits.hpp"
#include "sigmatau/units.hpp"
#include "sigmatau/rate_series.hpp"
#include "sigmatau/warmup.hpp"

namespace sigmatau {
namespace {

using nlohmann::json;

/// Pass 1's data checks, fed block by block; warnings() gives run_analysis's, in its order.
class StreamingChecks {
 public:
  StreamingChecks(const std::vector<BoundedChannel>& plan, DataKind kind) {
    for (std::size_t c = 0; c < plan.size(); ++c) {
      runs_.emplace_back(plan[c].name);
      outliers_.push_back(detail::outlier_checker(plan[c].name, kind, plan[c].input_unit));
      if (!plan[c].role || kind != DataKind::rate) continue;
      const int s = plan[c].role->sensor == Sensor::gyro ? 0 : 1;
      triad_[s].push_back(c);
      triad_names_[s].push_back(plan[c].name);
      triad_unit_[s] = plan[c].input_unit;
    }
    gyro_sums_.assign(triad_[0].size(), 0.0);
  }

  /// values[c]: this block's SI values of plan channel c.
  void add(const std::vector<std::span<const double>>& values) {
    for (std::size_t c = 0; c < values.size(); ++c) {
      runs_[c].add(values[c]);
      outliers_[c].add(values[c]);
    }
    for (std::size_t a = 0; a < triad_[0].size(); ++a) {
      for (const double v : values[triad_[0][a]]) gyro_sums_[a] += v;
    }
    if (triad_[1].size() == 3) {
      const auto& x = values[triad_[1][0]];
      const auto& y = values[triad_[1][1]];
      const auto& z = values[triad_[1][2]];
      for (std::size_t i = 0; i < x.size(); ++i) accel_norm_sum_ += std::hypot(x[i], y[i], z[i]);
    }
    rows_ += values.empty() ? 0 : static_cast<std::int64_t>(values[0].size());
  }

  /// out: every warning, as run_analysis's; unit_out: the unit warnings apart (its
  /// "unit_warnings", read by the filter files' headers).
  void warnings(json& out, json& unit_out) {
    try {
      for (std::size_t c = 0; c < runs_.size(); ++c) {
        for (const auto& w : runs_[c].finish()) out.push_back(w.message);
        if (const auto w = outliers_[c].finish()) out.push_back(w->message);
      }
      for (int s = 0; s < 2; ++s) {
        if (triad_[s].empty()) continue;
        const std::string unit = triad_unit_[s].empty() ? (s == 0 ? "rad/s" : "m/s^2") : triad_unit_[s];
        const double to_si = parse_unit(unit).factor;
        const auto w =
            s == 0 ? check_gyro_unit_sums(gyro_sums_, rows_, triad_names_[s], unit, to_si)
                   : (triad_[s].size() == 3
                          ? check_accel_unit_sums(accel_norm_sum_, rows_, triad_names_[s], unit, to_si)
                          : std::nullopt);
        if (w) {
          out.push_back(w->message);
          unit_out.push_back({{"channels", w->channel}, {"likely_unit", w->likely_unit},
                              {"message", w->message}});
        }
      }
    } catch (const Error& e) {
      out.push_back(std::string("data checks skipped: ") + e.what());
    }
  }

 private:
  std::vector<RunChecker> runs_;
  std::vector<OutlierChecker> outliers_;
  std::array<std::vector<std::size_t>, 2> triad_;  ///< plan indices of each triad's axes
  std::array<std::vector<std::string>, 2> triad_names_;
  std::array<std::string, 2> triad_unit_;
  std::vector<double> gyro_sums_;
  double accel_norm_sum_ = 0;
  std::int64_t rows_ = 0;
};

/// A spilled PhaseSeries of spill values [begin, end), built in two passes over the file;
/// `also` (may be empty) sees the same values during the first pass.
PhaseSeries build_series(const detail::ValueSpill& spill, std::int64_t begin, std::int64_t end,
                         DataKind kind, double rate_hz, const PhaseStorage& storage,
                         const std::function<void(std::span<const double>)>& also = {}) {
  PhaseSeriesBuilder builder(kind, storage);
  spill.for_each(begin, end, [&](std::span<const double> v) {
    builder.scan(v);
    if (also) also(v);
  });
  spill.for_each(begin, end, [&](std::span<const double> v) { builder.append(v); });
  return builder.finish(1.0 / rate_hz);
}

/// What the group stage leaves per channel for the JSON.
struct ChannelWork {
  std::vector<AllanCurve> curves;
  json dynamic;                    ///< null without --dynamic
  std::optional<PsdCurve> psd;
  std::string psd_error;           ///< set when the PSD failed (as run_analysis's warning)
};

}  // namespace

AnalysisOutput run_analysis_bounded(const BoundedAnalysisSource& source, AnalysisInput input,
                                    const AnalysisOptions& options) {
  if (source.log.path == "-") {
    throw Error("the bounded-memory analysis reads a file, not stdin (a pipe is analysed in memory)");
  }
  if (options.statistics.empty()) throw Error("no statistic asked for");
  if (source.log.gaps == GapPolicy::split || source.log.gaps == GapPolicy::fill) {
    throw Error("--gaps split and fill need the whole log in memory (no bounded-memory analysis)");
  }
  const DataKind kind = input.kind;

  // Pass 1: the log, once.
  LogReader reader(source.log);
  const std::vector<BoundedChannel> plan = source.channels(reader.channel_names());
  if (plan.empty()) throw Error(input.path + ": no channel to analyse");
  std::vector<detail::ValueSpill> spills;
  for (std::size_t c = 0; c < plan.size(); ++c) {
    const bool repeated = std::any_of(plan.begin(), plan.begin() + static_cast<std::ptrdiff_t>(c),
                                      [&](const BoundedChannel& p) { return p.column == plan[c].column; });
    if (plan[c].column >= reader.channel_names().size() || repeated) {
      throw Error("internal: bounded analysis channel columns must be distinct and in range");
    }
    spills.emplace_back(source.storage.directory);
  }
  StreamingChecks checks(plan, kind);
  SampleBlock block;
  std::vector<std::span<const double>> views(plan.size());
  while (reader.read_block(block)) {
    for (std::size_t c = 0; c < plan.size(); ++c) {
      std::vector<double>& values = block.values[plan[c].column];
      if (plan[c].to_si != 1) {
        for (double& v : values) v *= plan[c].to_si;
      }
      views[c] = values;
      spills[c].append(values);
    }
    checks.add(views);
    if (source.progress) source.progress(reader.bytes_read(), reader.total_bytes());
  }
  for (auto& s : spills) s.flush();
  const TimingReport& timing = reader.timing();
  if (source.on_read) source.on_read(timing);
  const std::int64_t samples_in = spills.front().size();
  if (samples_in == 0) {
    throw ParseError(input.path, 0, 0, "no samples: the input holds no data rows");
  }
  input.rate_hz = source.rate_hz(timing);
  checked_rate_hz(input.rate_hz, input.path + ": rate_hz");
  if (timing.has_time) input.timing = timing;
  if (timing.segment_starts.size() > 1) {
    throw Error("--gaps split: the bounded-memory analysis does not split segments");
  }
  for (const auto& p : plan) {
    AnalysisChannel channel;
    channel.name = p.name;
    channel.role = p.role;
    input.channels.push_back(std::move(channel));
    input.input_units.push_back(p.input_unit);
  }
  const double rate_hz = input.rate_hz;

  AnalysisOutput output;
  json results = detail::results_header(options);
  json warnings = json::array();
  results["unit_warnings"] = json::array();
  checks.warnings(warnings, results["unit_warnings"]);

  // Pass 2: the warm-up's block means of every channel's rates.
  json trim = detail::trim_mode_json(options);
  std::int64_t trim_samples = 0;
  if (options.trim == TrimMode::automatic) {
    std::vector<WarmupBlocks> blocks(plan.size());
    detail::for_each_item_parallel(plan.size(), options.threads, [&](std::size_t c) {
      WarmupBlockSums sums(rate_count(samples_in, kind));
      RateStream rates(kind, rate_hz);
      spills[c].for_each(0, samples_in, [&](std::span<const double> v) { sums.add(rates.convert(v)); });
      blocks[c] = sums.blocks();
    });
    const WarmupDecision d = decide_warmup(blocks, rate_hz);
    trim_samples = d.trim_samples;
    trim["reason"] = d.reason;
    if (d.channel >= 0) trim["channel"] = plan[static_cast<std::size_t>(d.channel)].name;
  } else {
    trim_samples = detail::requested_trim(options, rate_hz, trim);
  }
  detail::record_trim(trim_samples, samples_in, rate_hz, trim);
  const std::int64_t samples = samples_in - trim_samples;
  results["input"] = detail::input_json(input, samples, samples_in, trim);

  if (options.dynamic_windows > 0) {  // the same for every channel: said once
    const std::string why = detail::plan_dynamic_windows(samples, options.dynamic_windows).warning;
    if (!why.empty()) warnings.push_back(why);
  }
  // Pass 3, per group of channels: phase (scan + PSD, then append), curves, dynamic windows.
  unsigned threads = options.threads;
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<ChannelWork> work(plan.size());
  for (std::size_t group = 0; group < plan.size(); group += threads) {
    const std::size_t group_end = std::min(plan.size(), group + threads);
    std::vector<std::optional<PhaseSeries>> series(group_end - group);
    detail::for_each_item_parallel(group_end - group, threads, [&](std::size_t i) {
      const std::size_t c = group + i;
      std::optional<WelchAccumulator> welch;
      try {
        welch.emplace(rate_hz, options.welch, rate_count(samples, kind));
      } catch (const Error& e) {
        work[c].psd_error = e.what();
      }
      RateStream rates(kind, rate_hz);
      series[i] = build_series(spills[c], trim_samples, samples_in, kind, rate_hz, source.storage,
                               [&](std::span<const double> v) {
                                 if (welch) welch->add(rates.convert(v));
                               });
      if (welch) {
        try {
          work[c].psd = welch->result();
        } catch (const Error& e) {
          work[c].psd_error = e.what();
        }
      }
    });
    const std::size_t stats = options.statistics.size();
    std::mutex mutex;
    for (std::size_t c = group; c < group_end; ++c) work[c].curves.resize(stats);
    detail::for_each_item_parallel((group_end - group) * stats, threads, [&](std::size_t i) {
      const std::size_t c = group + i / stats;
      AllanCurve curve = compute_allan_curve_bounded(*series[i / stats], options.statistics[i % stats],
                                                     options.taus, options.confidence, source.storage,
                                                     options.edf_model);
      std::lock_guard lock(mutex);
      work[c].curves[i % stats] = std::move(curve);
    });
    series.clear();
    if (options.dynamic_windows > 0) {
      const detail::DynamicWindows windows_plan =
          detail::plan_dynamic_windows(samples, options.dynamic_windows);
      const std::int64_t length = windows_plan.length;
      const auto windows = static_cast<std::size_t>(windows_plan.windows);
      std::vector<json> window_json((group_end - group) * windows);
      detail::for_each_item_parallel(window_json.size(), threads, [&](std::size_t i) {
        const std::size_t c = group + i / windows;
        const std::int64_t start = static_cast<std::int64_t>(i % windows) * length / 2;
        const PhaseSeries window = build_series(spills[c], trim_samples + start,
                                                trim_samples + start + length, kind, rate_hz,
                                                source.storage);
        window_json[i] = detail::dynamic_window_json(window, start, length, rate_hz);
      });
      for (std::size_t c = group; c < group_end; ++c) {
        json list = json::array();
        for (std::size_t w = 0; w < windows; ++w) list.push_back(window_json[(c - group) * windows + w]);
        work[c].dynamic = {{"window_s", static_cast<double>(length) / rate_hz}, {"windows", list}};
      }
    }
  }
  spills.clear();

  results["channels"] = json::array();
  std::vector<std::vector<AllanCurve>> curves;
  for (std::size_t c = 0; c < plan.size(); ++c) {
    json entry = detail::channel_json(input.channels[c], plan[c].input_unit, work[c].curves);
    if (options.dynamic_windows > 0) entry["dynamic"] = work[c].dynamic;
    if (!work[c].psd_error.empty()) {
      warnings.push_back(plan[c].name + ": no PSD (" + work[c].psd_error + ")");
    } else {
      try {
        detail::add_psd(entry, *work[c].psd, input.channels[c], options);
      } catch (const Error& e) {
        warnings.push_back(plan[c].name + ": no PSD (" + e.what() + ")");
      }
    }
    results["channels"].push_back(entry);
    curves.push_back(std::move(work[c].curves));
  }
  detail::finish_results(results, warnings, input.channels, curves, samples, kind, rate_hz,
                         options, output);
  return output;
}

}  // namespace sigmatau
