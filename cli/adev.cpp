// `sigmatau adev`: Allan-family deviations of every channel of a log, with confidence intervals.
#include <nlohmann/json.hpp>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <future>
#include <iostream>
#include <optional>
#include <sstream>

#include "adev_taus.hpp"
#include "channel_units.hpp"
#include "json_text.hpp"
#include "log_options.hpp"
#include "memory_budget.hpp"
#include "outlier_warnings.hpp"
#include "sigmatau/allan_curve.hpp"
#include "sigmatau/allan_out_of_core.hpp"
#include "sigmatau/allan_segments.hpp"
#include "sigmatau/allan_stream.hpp"
#include "sigmatau/data_checks.hpp"
#include "sigmatau/taus.hpp"
#include "sigmatau/log_reader.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/output_file.hpp"
#include "sigmatau/plot.hpp"
#include "verbs.hpp"

namespace sigmatau::cli {
namespace {

struct AdevArguments {
  LogArguments log;
  std::string statistics = "oadev";
  std::string taus = "octave";
  double ci = 0.683;
  std::string format = "table";
  std::string output;
  std::string out_unit;
  unsigned threads = 0;
  bool force = false;
  std::string plot;
  std::string mode = "auto";
  int density = kDefaultStreamDensity;
  std::string memory = "4GiB";
  bool partial = false;
  std::string edf;  // greenhall|discrete; empty: by the data (edf_model_for)
};

/// --edf greenhall|discrete.
EdfModel parse_edf_model(const std::string& name) {
  if (name == "greenhall") return EdfModel::greenhall;
  if (name == "discrete") return EdfModel::discrete;
  throw Error("--edf must be greenhall or discrete, got \"" + name + "\"");
}

/// Exact curves from a log larger than --memory: the phase goes to temporary files (TMPDIR) and
/// the file is read twice per group of --threads channels (lib: allan_out_of_core.hpp). The
/// first pass's blocks also go through the outlier check (`outliers` receives its warnings).
std::vector<std::vector<AllanCurve>> run_out_of_core(const AdevArguments& args,
                                                     const std::vector<Statistic>& stats,
                                                     const TauSpec& taus, LoadedChannels& loaded,
                                                     std::size_t& samples,
                                                     std::vector<std::string>& outliers) {
  const LogOptions options = log_options_from(args.log);
  set_input_unit(args.log, loaded);
  Progress progress;
  OutOfCoreSettings settings;
  settings.threads = args.threads;
  settings.edf_model = parse_edf_model(args.edf);
  settings.progress = [&](std::int64_t done, std::int64_t total) { progress.update(done, total); };
  settings.stage = [&](const std::string& label) { progress.stage(label); };
  BlockOutliers checks(args.log, loaded.kind, args.threads != 1);
  settings.first_pass_block = [&](const std::vector<std::string>& names, const SampleBlock& block) {
    checks.add(names, block.values);
  };
  OutOfCoreResult result = compute_allan_curves_out_of_core(
      options, loaded.kind, loaded.to_si,
      [&](const TimingReport& timing) {
        return resolve_rate_hz(args.log.rate_hz, timing, args.log.input);
      },
      stats,
      [&](std::int64_t n_phase_points, double tau0_s) {
        return taus_per_statistic(taus, stats, n_phase_points, tau0_s, loaded.kind,
                                  args.log.input);
      },
      args.ci, settings);
  progress.finish();
  loaded.log.path = options.path;
  loaded.log.channel_names = std::move(result.channel_names);
  loaded.log.timing = std::move(result.timing);
  note_reading(args.log, options, loaded.log.timing);
  loaded.rate_hz = result.rate_hz;
  samples = static_cast<std::size_t>(result.samples);
  outliers = checks.finish();
  return std::move(result.curves);
}

/// How a channel's deviations (computed in SI, or in the input's own unit without a unit) are
/// printed.
struct OutputUnit {
  std::string label;   // "" when the input unit is unknown
  double from_si = 1;  // printed = computed * from_si
};

/// The printed unit of every channel: its own (ChannelUnit, as rate_unit gives it), or the
/// --out-unit of the same dimension ("deg/h", or one per sensor: "deg/h,ug").
std::vector<OutputUnit> output_units(const LoadedChannels& loaded, const std::string& out_unit) {
  std::vector<RateUnit> own;
  std::vector<Dimension> dimensions;
  std::vector<bool> known;
  for (const ChannelUnit& u : loaded.channel_units) {
    own.push_back(rate_unit(u, loaded.kind));
    dimensions.push_back(own.back().dimension);
    known.push_back(!own.back().label.empty());
  }
  const std::vector<std::string> outs =
      out_unit.empty() ? std::vector<std::string>{} : split_list(out_unit, "--out-unit");
  const std::vector<int> chosen = match_out_units(outs, dimensions, known, "the deviations are");
  std::vector<OutputUnit> units;
  for (std::size_t c = 0; c < own.size(); ++c) {
    if (chosen[c] < 0) {
      units.push_back({own[c].label, own[c].from_result});
      continue;
    }
    const Unit unit = parse_unit(outs[static_cast<std::size_t>(chosen[c])]);
    units.push_back({outs[static_cast<std::size_t>(chosen[c])],
                     loaded.channel_units[c].result_to_si / unit.factor});
  }
  return units;
}

/// The units and --out-unit checked before the log is read: with the channel names from its
/// header or the bag's channels (early_channel_units), else (stdin) with the --unit given.
void check_out_unit_early(const LogArguments& args, const std::string& out_unit) {
  if (const auto early = early_channel_units(args)) {
    output_units(*early, out_unit);
    return;
  }
  if (out_unit.empty() || per_channel_units(args)) return;
  LoadedChannels unit_only;
  set_input_unit(args, unit_only);
  unit_only.channel_units.push_back({unit_only.unit, unit_only.dimension, unit_only.to_si, 1.0, "--unit"});
  output_units(unit_only, out_unit);
}

/// TDEV is a time deviation: its unit is the deviation unit times seconds.
OutputUnit unit_for(Statistic statistic, const OutputUnit& unit) {
  if (statistic != Statistic::tdev) return unit;
  if (unit.label.empty()) return unit;
  return {unit.label == "1" ? "s" : unit.label + "*s", unit.from_si};
}

std::string format_number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6e", v);
  return buffer;
}

std::string render_table(const LoadedChannels& loaded, std::size_t samples, const std::vector<Statistic>& stats,
                         const std::vector<std::vector<AllanCurve>>& curves,
                         const std::vector<OutputUnit>& units, const std::string& mode) {
  std::ostringstream out;
  out << "# " << loaded.log.path << ": " << samples << " samples at "
      << loaded.rate_hz << " Hz, kind " << to_string(loaded.kind);
  if (loaded.log.timing.segment_starts.size() > 1) {
    out << ", " << loaded.log.timing.segment_starts.size()
        << " contiguous segments pooled (--gaps split)";
  }
  out << "\n# mode: " << mode << "\n";
  for (std::size_t c = 0; c < curves.size(); ++c) {
    for (std::size_t s = 0; s < stats.size(); ++s) {
      const auto& curve = curves[c][s];
      const auto u = unit_for(stats[s], units[c]);
      out << "\n# " << loaded.log.channel_names[c] << "  " << to_string(stats[s]) << "  ["
          << (u.label.empty() ? "input unit" : u.label) << "]  " << curve.confidence_level * 100
          << "% interval\n";
      char line[160];
      std::snprintf(line, sizeof line, "%12s %10s %11s %6s %10s %13s %13s %13s\n", "tau[s]", "m",
                    "n", "alpha", "edf", "ci_low", "dev", "ci_high");
      out << line;
      for (const auto& p : curve.points) {
        std::snprintf(line, sizeof line, "%12.5g %10lld %11lld %6d %10.4g %13.6e %13.6e %13.6e\n",
                      p.value.tau_s, static_cast<long long>(p.value.m),
                      static_cast<long long>(p.value.n_terms), p.confidence.noise.alpha,
                      p.confidence.edf, p.confidence.interval.low * u.from_si,
                      p.value.dev * u.from_si, p.confidence.interval.high * u.from_si);
        out << line;
      }
    }
  }
  return out.str();
}

std::string render_csv(const LoadedChannels& loaded, const std::vector<Statistic>& stats,
                       const std::vector<std::vector<AllanCurve>>& curves,
                       const std::vector<OutputUnit>& units, const std::string& mode) {
  std::ostringstream out;
  // The mode goes in a comment line only for an approximate (stream) result, so that exact CSV
  // stays plain CSV and a stream result is never mistaken for an exact one; "" for exact.
  if (!mode.empty()) out << "# mode: " << mode << "\n";
  out << "channel,statistic,unit,tau_s,m,n,alpha,edf,ci_low,dev,ci_high\n";
  for (std::size_t c = 0; c < curves.size(); ++c) {
    for (std::size_t s = 0; s < stats.size(); ++s) {
      const auto u = unit_for(stats[s], units[c]);
      for (const auto& p : curves[c][s].points) {
        out << loaded.log.channel_names[c] << ',' << to_string(stats[s]) << ',' << u.label << ','
            << format_number(p.value.tau_s) << ',' << p.value.m << ',' << p.value.n_terms << ','
            << p.confidence.noise.alpha << ',' << format_number(p.confidence.edf) << ','
            << format_number(p.confidence.interval.low * u.from_si) << ','
            << format_number(p.value.dev * u.from_si) << ','
            << format_number(p.confidence.interval.high * u.from_si) << '\n';
      }
    }
  }
  return out.str();
}

nlohmann::json json_number(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}

std::string render_json(const LoadedChannels& loaded, std::size_t samples, const std::vector<Statistic>& stats,
                        const std::vector<std::vector<AllanCurve>>& curves,
                        const std::vector<OutputUnit>& units, const std::string& edf_model,
                        const nlohmann::json& mode, const std::vector<std::string>& warnings) {
  nlohmann::json doc;
  doc["tool"] = "sigmatau";
  doc["version"] = SIGMATAU_VERSION;
  doc["edf_model"] = edf_model;
  doc["mode"] = mode;
  doc["warnings"] = warnings;
  doc["input"] = {{"path", loaded.log.path},
                  {"rate_hz", loaded.rate_hz},
                  {"samples", samples},
                  {"kind", std::string(to_string(loaded.kind))},
                  {"unit", loaded.unit}};
  if (loaded.log.timing.has_time) {
    const auto& t = loaded.log.timing;
    nlohmann::json gaps = nlohmann::json::array();
    for (const auto& g : t.gaps) {
      gaps.push_back({{"row", g.row}, {"line", g.line}, {"start_s", g.start_s}, {"length_s", g.length_s}});
    }
    doc["input"]["timing"] = {{"rate_hz", t.rate_hz},
                              {"mean_interval_s", t.mean_interval_s},
                              {"jitter_s", t.jitter_s},
                              {"non_increasing", t.non_increasing},
                              {"gaps", gaps}};
    if (!t.segment_starts.empty()) doc["input"]["timing"]["segment_starts"] = t.segment_starts;
    if (t.truncated_at_byte >= 0) {  // a cut-short bag read with --truncated use
      doc["input"]["timing"]["truncated_at_byte"] = t.truncated_at_byte;
      doc["input"]["timing"]["truncated_file"] = t.truncated_file;
    }
  }
  doc["results"] = nlohmann::json::array();
  for (std::size_t c = 0; c < curves.size(); ++c) {
    for (std::size_t s = 0; s < stats.size(); ++s) {
      const auto u = unit_for(stats[s], units[c]);
      nlohmann::json points = nlohmann::json::array();
      for (const auto& p : curves[c][s].points) {
        points.push_back({{"tau", p.value.tau_s},
                          {"m", p.value.m},
                          {"n", p.value.n_terms},
                          {"dev", json_number(p.value.dev * u.from_si)},
                          {"ci_low", json_number(p.confidence.interval.low * u.from_si)},
                          {"ci_high", json_number(p.confidence.interval.high * u.from_si)},
                          {"edf", json_number(p.confidence.edf)},
                          {"alpha", p.confidence.noise.alpha}});
      }
      doc["results"].push_back({{"channel", loaded.log.channel_names[c]},
                                {"statistic", std::string(to_string(stats[s]))},
                                {"unit", u.label},
                                {"confidence", curves[c][s].confidence_level},
                                {"points", points}});
    }
  }
  return json_text(doc, 1) + "\n";
}

/// One pass over the input with an AllanStream per channel. On a read error after some samples,
/// `partial_error` receives the message and the curves describe what was read (when --partial).
/// The blocks also go through the outlier check (`outliers` receives its warnings).
std::vector<std::vector<AllanCurve>> run_stream(const AdevArguments& args,
                                                const std::vector<Statistic>& stats,
                                                const TauSpec& taus, LoadedChannels& loaded,
                                                std::size_t& samples, std::string& partial_error,
                                                std::vector<std::string>& outliers,
                                                std::vector<std::string>& left_out) {
  const LogOptions options = log_options_from(args.log);
  set_input_unit(args.log, loaded);
  LogReader reader(options);
  loaded.log.path = options.path;
  loaded.log.channel_names = reader.channel_names();
  StreamSettings settings;
  settings.statistics = stats;
  settings.taus = taus;
  settings.density = args.density;
  std::vector<AllanStream> streams;
  SampleBlock block;
  Progress progress;
  BlockOutliers checks(args.log, loaded.kind, args.threads != 1);
  samples = 0;
  const auto take = [&](SampleBlock& rows) {
    if (streams.empty()) {
      // The sample interval is fixed from the first block (the time column's median interval
      // so far, or --rate): a stream cannot wait for the end of the log.
      loaded.rate_hz = resolve_rate_hz(args.log.rate_hz, reader.timing(), args.log.input);
      for (std::size_t c = 0; c < rows.values.size(); ++c) {
        streams.emplace_back(loaded.kind, 1.0 / loaded.rate_hz, settings);
      }
    }
    for (std::size_t c = 0; c < rows.values.size(); ++c) {
      auto& v = rows.values[c];
      if (loaded.to_si != 1.0) {
        for (double& x : v) x *= loaded.to_si;
      }
      streams[c].add(v);
    }
    checks.add(loaded.log.channel_names, rows.values);
    samples += static_cast<std::size_t>(rows.rows());
  };
  try {
    while (reader.read_block(block)) {
      take(block);
      progress.update(reader.bytes_read(), reader.total_bytes());
    }
  } catch (const Error& e) {
    if (!args.partial) throw;
    partial_error = e.what();
    // The reader leaves the whole rows before the one in error in the block: kept too. Taking
    // the first block fixes the sample interval, which can fail (no --rate, too few stamps).
    try {
      if (block.rows() > 0) take(block);
    } catch (const Error& rate) {
      throw Error(partial_error + " (--partial: no results written: " + rate.what() + ")");
    }
  }
  progress.finish();
  loaded.log.timing = reader.timing();
  note_reading(args.log, options, loaded.log.timing);
  std::vector<std::vector<AllanCurve>> curves;
  for (const auto& stream : streams) curves.push_back(stream.curves(args.ci));
  // Decade factors the log reaches but a bounded stream cannot hold (the same on every channel).
  const std::vector<std::int64_t> not_held =
      streams.empty() ? std::vector<std::int64_t>{} : streams.front().factors_left_out();
  if (!not_held.empty()) {
    std::string list;
    for (const std::int64_t m : not_held) {
      char text[64];
      std::snprintf(text, sizeof text, "%s%g s (m = %lld)", list.empty() ? "" : ", ",
                    static_cast<double>(m) / loaded.rate_hz, static_cast<long long>(m));
      list += text;
    }
    // The left-out factors start at a power of ten (1, 2 and 4 x 10^k share the odd part 5^k).
    const std::int64_t first = not_held.front();
    char held[96];
    std::snprintf(held, sizeof held, "m = %lld (%g s)", static_cast<long long>(first / 10 * 4),
                  static_cast<double>(first / 10 * 4) / loaded.rate_hz);
    left_out.push_back("stream mode holds decade taus in bounded memory only up to " +
                       std::string(held) + ": beyond, a stride would need too long a lag; this "
                       "log also reaches " + list + ", left out: --mode exact or --taus octave "
                       "computes them");
  }
  if (!partial_error.empty()) {
    bool any_point = false;
    for (const auto& per_statistic : curves) {
      for (const AllanCurve& curve : per_statistic) any_point = any_point || !curve.points.empty();
    }
    if (!any_point) {
      // Said, not left to guess: --partial was asked for, but there is nothing to write.
      const std::string read = samples == 1 ? "the 1 sample read before it reaches"
                                            : "the " + std::to_string(samples) +
                                                  " samples read before it reach";
      throw Error(partial_error + " (--partial: no results written: " + read + " no tau)");
    }
  }
  if (streams.empty()) {
    throw ParseError(options.path == "-" ? "<stdin>" : options.path, 0, 0,
                     "no samples: the input holds no data rows");
  }
  outliers = checks.finish();
  return curves;
}

/// Exact mode in memory on a log without gaps: every channel's phase, then the curves. The raw
/// samples' memory goes to each channel's phase for its sweep copy as the phase is built.
std::vector<std::vector<AllanCurve>> whole_log_curves(const AdevArguments& args,
                                                      const std::vector<Statistic>& stats,
                                                      const TauSpec& taus, EdfModel edf_model,
                                                      LoadedChannels& loaded,
                                                      const std::function<void()>& checks) {
  // The data checks only read the samples: with more than one thread they run beside the
  // phases' construction (a pass over the log off the critical path) and end before the
  // samples' memory is handed on. Their errors come first, as when they ran before.
  std::future<void> job;
  if (args.threads != 1) {
    job = std::async(std::launch::async, checks);
  } else {
    checks();
  }
  std::vector<PhaseSeries> series;
  series.reserve(loaded.log.channels.size());
  try {
    for (const auto& channel : loaded.log.channels) {
      series.push_back(PhaseSeries::from_samples(channel, loaded.kind, 1.0 / loaded.rate_hz));
    }
  } catch (...) {
    if (job.valid()) job.get();
    throw;
  }
  if (job.valid()) job.get();
  for (std::size_t c = 0; c < series.size(); ++c) {
    // The samples' memory (read_log leaves room for one more point) becomes the sweep copy's.
    series[c].recycle(std::move(loaded.log.channels[c]));
    std::vector<double>().swap(loaded.log.channels[c]);
  }
  return curves_per_statistic(series, stats, taus, args.ci, args.threads, edf_model,
                              args.log.input);
}

/// --gaps split with more than one segment: every contiguous segment of each channel is its own
/// series and their results are pooled (allan_segments.hpp), so no difference spans a gap. The
/// raw samples are released as the series are built.
std::vector<std::vector<AllanCurve>> split_curves(const AdevArguments& args,
                                                  const std::vector<Statistic>& stats,
                                                  const TauSpec& taus, LoadedChannels& loaded) {
  const auto ranges =
      segment_ranges(loaded.log.timing.segment_starts,
                     static_cast<std::int64_t>(loaded.log.channels.front().size()));
  std::vector<std::vector<PhaseSeries>> channels;
  for (auto& channel : loaded.log.channels) {
    channels.push_back(segment_series(channel, ranges, loaded.kind, 1.0 / loaded.rate_hz));
    std::vector<double>().swap(channel);
  }
  // The longest segment bounds the taus (allan_segments.hpp): explicit taus per statistic.
  std::int64_t longest = 0;
  for (const auto& series : channels.front()) {
    longest = std::max<std::int64_t>(longest, static_cast<std::int64_t>(series.size()));
  }
  const std::vector<TauSpec> specs = taus_per_statistic(
      taus, stats, longest, 1.0 / loaded.rate_hz, loaded.kind, args.log.input);
  return curves_for_specs(specs, stats, [&](const std::vector<Statistic>& some, const TauSpec& t) {
    return compute_segmented_allan_curves(channels, some, t, args.ci, args.threads,
                                          parse_edf_model(args.edf));
  });
}

/// The value of each constant channel of a log in memory (whole_run_value of its run checks),
/// in the input unit; nullopt for the others.
std::vector<std::optional<double>> constant_values(const LoadedChannels& loaded) {
  std::vector<std::optional<double>> values;
  for (std::size_t c = 0; c < loaded.log.channels.size(); ++c) {
    const auto& channel = loaded.log.channels[c];
    auto value = whole_run_value(check_runs(channel, loaded.log.channel_names[c]),
                                 static_cast<std::int64_t>(channel.size()));
    if (value) *value /= (loaded.to_si != 0 ? loaded.to_si : 1.0);
    values.push_back(value);
  }
  return values;
}

/// Whether a channel is constant, from its curves when its samples were never in memory
/// (stream and out-of-core paths): some point computed, and every deviation 0.
bool constant_by_curves(const std::vector<AllanCurve>& channel) {
  bool any_point = false;
  for (const AllanCurve& curve : channel) {
    if (!all_deviations_zero(curve)) return false;
    any_point = any_point || !curve.points.empty();
  }
  return any_point;
}

void run_adev(const AdevArguments& args) {
  std::vector<Statistic> stats;
  for (const auto& name : split_list(args.statistics, "--stat")) stats.push_back(parse_statistic(name));
  const TauSpec taus = parse_tau_spec(args.taus);
  if (args.format != "table" && args.format != "csv" && args.format != "json") {
    throw Error("--format must be table, csv or json, got \"" + args.format + "\"");
  }
  if (!args.output.empty()) check_can_write(args.output, args.force);
  if (!args.plot.empty()) {
    plot_format_for(args.plot);
    check_can_write(args.plot, args.force);
  }

  if (args.mode != "exact" && args.mode != "stream" && args.mode != "auto") {
    throw Error("--mode must be exact, stream or auto, got \"" + args.mode + "\"");
  }
  if (!(args.density >= 1)) throw Error("--density must be >= 1, got " + std::to_string(args.density));
  const std::int64_t memory = parse_bytes(args.memory);
  if (args.partial && args.mode == "exact") {
    throw Error("--partial is for --mode stream (exact results need the whole log)");
  }
  const bool stream = args.mode == "stream";
  const EdfModel edf_model = parse_edf_model(args.edf);
  if (stream && edf_model != EdfModel::greenhall) {
    throw Error("--edf discrete is for exact mode; stream mode's strided EDF follows Greenhall's "
                "algorithm");
  }
  // Exact (and auto) mode on a file that would not fit --memory: exact out of core (the phase
  // in temporary files, the file read twice). Not for --gaps split/fill on a log with time
  // stamps (a time column or a ROS bag: they need the whole log in memory); pipes cannot be
  // read twice and stay in memory.
  bool out_of_core = false;
  if (!stream && exact_needs_out_of_core(args.log, memory)) {
    std::cerr << "sigmatau: " << args.log.input << " needs more than --memory " << args.memory
              << " in memory; computing exactly out of core (temporary files in "
              << (std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp") << ")\n";
    out_of_core = true;
  }
  check_out_unit_early(args.log, args.out_unit);
  LoadedChannels loaded;
  std::size_t samples = 0;
  std::string partial_error;
  std::vector<std::vector<AllanCurve>> curves;
  // Constant channels: their value from the samples when they are in memory (else empty, and
  // told from the curves below: every deviation 0).
  std::vector<std::optional<double>> constant_value;
  // Outlier warnings (the check analyze runs), from the samples in memory or block by block.
  std::vector<std::string> outliers;
  std::vector<std::string> stream_left_out;  // decade taus a bounded stream could not hold
  if (out_of_core) {
    curves = run_out_of_core(args, stats, taus, loaded, samples, outliers);
  } else if (stream) {
    curves = run_stream(args, stats, taus, loaded, samples, partial_error, outliers,
                        stream_left_out);
    if (partial_error.empty()) note_stream_skipped(taus, stats, curves, loaded.rate_hz, args.log.input);
    if (loaded.log.timing.segment_starts.size() > 1) {
      throw Error("--gaps split needs --mode exact: stream mode cannot restart its sums at a gap "
                  "(" + std::to_string(loaded.log.timing.segment_starts.size()) + " segments)");
    }
  } else {
    loaded = load_channels(args.log);
    samples = loaded.log.channels.front().size();
    const auto checks = [&] {
      constant_value = constant_values(loaded);
      outliers = outlier_warnings(loaded.log.channels, loaded.log.channel_names,
                                  loaded.channel_units, loaded.kind);
    };
    if (loaded.log.timing.segment_starts.size() > 1) {
      checks();
      curves = split_curves(args, stats, taus, loaded);
    } else {
      curves = whole_log_curves(args, stats, taus, edf_model, loaded, checks);
    }
  }
  std::vector<std::string> warnings;
  for (std::size_t c = 0; c < curves.size(); ++c) {
    std::string how;
    if (c < constant_value.size()) {
      if (!constant_value[c]) continue;
      char text[40];
      std::snprintf(text, sizeof text, "%.9g", *constant_value[c]);
      how = "every value is " + std::string(text);
    } else {
      if (!constant_by_curves(curves[c])) continue;
      how = "every deviation is 0";
    }
    warnings.push_back(constant_channel_text(loaded.log.channel_names[c], how) +
                       "; its deviations are 0 and say nothing about the sensor");
    std::cerr << "sigmatau: warning: " << args.log.input << ": " << warnings.back() << "\n";
  }
  for (const std::string& message : outliers) {
    warnings.push_back(message);  // analyze's text: it says what spikes do to the deviations
    std::cerr << "sigmatau: warning: " << args.log.input << ": " << warnings.back() << "\n";
  }
  for (const std::string& message : stream_left_out) {
    warnings.push_back(message);
    std::cerr << "sigmatau: warning: " << args.log.input << ": " << warnings.back() << "\n";
  }
  // A noise type that jumps at one tau (a spectral line read as another type) sets that
  // point's EDF and interval from the jumped type: said, since the interval looks too good.
  for (std::size_t c = 0; c < curves.size(); ++c) {
    for (const AllanCurve& curve : curves[c]) {
      for (const std::size_t i : isolated_noise_types(curve)) {
        const CurvePoint& p = curve.points[i];
        char text[400];
        std::snprintf(text, sizeof text,
                      "channel %s %s: the noise type at %g s (alpha %d) differs from both "
                      "neighbours (alpha %d), and its EDF (%.4g, against %.4g and %.4g) and "
                      "interval follow it; a periodic component (a line in `psd`) does this",
                      loaded.log.channel_names[c].c_str(),
                      std::string(to_string(curve.statistic)).c_str(), p.value.tau_s,
                      p.confidence.noise.alpha, curve.points[i - 1].confidence.noise.alpha,
                      p.confidence.edf, curve.points[i - 1].confidence.edf,
                      curve.points[i + 1].confidence.edf);
        warnings.push_back(text);
        std::cerr << "sigmatau: warning: " << args.log.input << ": " << warnings.back() << "\n";
      }
    }
  }
  // load_channels resolved the units; the stream and out-of-core paths do it here.
  if (loaded.channel_units.size() != loaded.log.channel_names.size()) resolve_channel_units(args.log, loaded);
  const std::vector<OutputUnit> units = output_units(loaded, args.out_unit);

  // Stream results are approximate at long taus (strided start points): said in every format.
  std::string mode_text = "exact";
  nlohmann::json mode = {{"name", "exact"}};
  if (stream) {
    mode_text = "stream (approximate: " + std::to_string(args.density) +
                " start points per tau at long taus, --density; the EDF is lowered to match)";
    mode = {{"name", "stream"}, {"density", args.density}, {"approximate", true}};
  } else if (out_of_core) {
    mode_text = "exact (out of core)";
    mode = {{"name", "exact"}, {"out_of_core", true}};
  }
  std::string text;
  if (args.format == "table") text = render_table(loaded, samples, stats, curves, units, mode_text);
  if (args.format == "csv") text = render_csv(loaded, stats, curves, units, stream ? mode_text : "");
  if (args.format == "json") text = render_json(loaded, samples, stats, curves, units, args.edf, mode, warnings);
  if (args.output.empty()) {
    std::cout << text;
  } else {
    write_file_atomically(args.output, text, args.force);
  }
  if (!partial_error.empty()) {
    // --partial: the curves above describe the samples read before the error; still exit 2.
    throw Error(partial_error + " (--partial: results written for the " + std::to_string(samples) +
                " samples read before it)");
  }
  if (!args.plot.empty()) {
    // The first statistic asked, every channel, with its confidence band. Channels in
    // different units (a gyro and an accelerometer) carry their unit in their names.
    bool one_unit = true;
    for (const auto& u : units) one_unit = one_unit && u.label == units.front().label;
    DeviationPlot plot;
    plot.title = loaded.log.path;
    std::string name(to_string(stats.front()));
    for (char& ch : name) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    const auto first = unit_for(stats.front(), units.front());
    plot.y_label = name + (one_unit ? " [" + (first.label.empty() ? std::string("input unit") : first.label) + "]"
                                    : std::string(" [unit per channel]"));
    for (std::size_t c = 0; c < curves.size(); ++c) {
      const auto u = unit_for(stats.front(), units[c]);
      PlotCurve curve;
      curve.name = loaded.log.channel_names[c] + (one_unit ? "" : " [" + u.label + "]");
      for (const auto& p : curves[c].front().points) {
        curve.x.push_back(p.value.tau_s);
        curve.y.push_back(p.value.dev * u.from_si);
        curve.low.push_back(p.confidence.interval.low * u.from_si);
        curve.high.push_back(p.confidence.interval.high * u.from_si);
      }
      plot.curves.push_back(std::move(curve));
    }
    render_deviation_plot(plot, args.plot, args.force);
  }
}

}  // namespace

void add_adev_command(CLI::App& app) {
  auto args = std::make_shared<AdevArguments>();
  CLI::App* command = app.add_subcommand(
      "adev", "Allan-family deviations (OADEV, ADEV, MDEV, TDEV, HDEV, OHDEV, TOTDEV) with "
              "confidence intervals");
  add_log_options(*command, args->log);
  add_sensor_unit_options(*command, args->log);
  command->add_option("--stat", args->statistics,
                      "statistics, comma-separated: oadev,adev,mdev,tdev,hdev,ohdev,totdev")
      ->capture_default_str();
  command->add_option("--taus", args->taus,
                      "averaging times: octave | decade | many[:P] | all | times (0.1,1,10 in s, or 100ms,2min)")
      ->capture_default_str();
  command->add_option("--ci", args->ci,
                      "two-sided confidence level of the intervals; 0.683 (one sigma) by default, "
                      "the level of the error bars Stable32 and NIST SP 1065 print, so the bounds "
                      "compare with theirs (fit and calibrate default to 0.95: their intervals "
                      "gate parts)")
      ->capture_default_str();
  command->add_option("--format", args->format, "table | csv | json")->capture_default_str();
  command->add_option("-o,--output", args->output, "write to FILE (atomically) instead of stdout");
  command->add_flag("--force", args->force, "overwrite an existing output file");
  command->add_option("--out-unit", args->out_unit,
                      "unit of the printed deviations, e.g. deg/h (needs --unit, --gyro-unit or "
                      "--accel-unit, or a ROS bag); one per sensor: deg/h,ug");
  command->add_option("--plot", args->plot,
                      "also plot the first statistic to FILE (.svg, .png or .pdf; needs gnuplot)");
  command->add_option("--threads", args->threads, "worker threads (0: one per core)")
      ->capture_default_str();
  command->add_option("--mode", args->mode,
                      "exact (in memory, or out of core in temporary files when a file would "
                      "need more than --memory), stream (one pass, bounded memory, strided "
                      "overlap at long taus, honest EDF; for pipes), auto (= exact)")
      ->capture_default_str();
  command->add_option("--density", args->density,
                      "stream mode: start points per tau K (stride max(1, m/K) samples)")
      ->capture_default_str();
  command->add_option("--memory", args->memory, "memory for exact mode, e.g. 1GiB: larger files are computed out of core")
      ->capture_default_str();
  command->add_option("--edf", args->edf,
                      "EDF of the intervals: greenhall (Greenhall & Riley's algorithm, the bounds "
                      "Stable32 prints) or discrete (exact for discrete power-law noise such as "
                      "independent rate samples; up to 25 % apart at the smallest taus). "
                      "Default: discrete for IMU data (a ROS bag, a gyro or accelerometer unit), "
                      "greenhall for clock data and values without a unit");
  command->add_flag("--partial",
                    args->partial, "stream mode: on a read error, still write the results for "
                                   "what was read (exit code stays 2)");
  command->callback([args] {
    args->edf = edf_model_name(args->edf, args->log, args->mode == "stream");
    run_adev(*args);
  });
}

}  // namespace sigmatau::cli
