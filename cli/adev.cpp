// `sigmatau adev`: Allan-family deviations of every channel of a log, with confidence intervals.
#include <nlohmann/json.hpp>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "log_options.hpp"
#include "sigmatau/allan_curve.hpp"
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
};

/// How deviations (computed in SI, or in the input's own unit without --unit) are printed.
struct OutputUnit {
  std::string label;   // "" when the input unit is unknown
  double from_si = 1;  // printed = computed * from_si
};

Dimension divided_by_time(Dimension d) {
  d.time2 -= 2;
  return d;
}

OutputUnit output_unit(const LoadedChannels& loaded, const std::string& out_unit) {
  if (loaded.unit.empty()) {
    if (!out_unit.empty()) throw Error("--out-unit needs --unit (the unit of the input values)");
    return {};
  }
  const Dimension dev_dimension =
      loaded.kind == DataKind::rate ? loaded.dimension : divided_by_time(loaded.dimension);
  if (!out_unit.empty()) {
    const Unit unit = parse_unit(out_unit);
    if (!(unit.dimension == dev_dimension)) {
      throw Error("--out-unit " + out_unit + " is " + to_string(unit.dimension) +
                  ", but the deviations of --unit " + loaded.unit + " (--kind " +
                  std::string(to_string(loaded.kind)) + ") are " + to_string(dev_dimension));
    }
    return {out_unit, 1.0 / unit.factor};
  }
  if (loaded.kind == DataKind::rate) return {loaded.unit, 1.0 / loaded.to_si};
  if (loaded.dimension == dim::time) return {"1", 1.0};  // clock phase in s: fractional frequency
  return {"(" + loaded.unit + ")/s", 1.0 / loaded.to_si};
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
                         const OutputUnit& unit) {
  std::ostringstream out;
  out << "# " << loaded.log.path << ": " << samples << " samples at "
      << loaded.rate_hz << " Hz, kind " << to_string(loaded.kind) << "\n";
  for (std::size_t c = 0; c < curves.size(); ++c) {
    for (std::size_t s = 0; s < stats.size(); ++s) {
      const auto& curve = curves[c][s];
      const auto u = unit_for(stats[s], unit);
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
                       const std::vector<std::vector<AllanCurve>>& curves, const OutputUnit& unit) {
  std::ostringstream out;
  out << "channel,statistic,unit,tau_s,m,n,alpha,edf,ci_low,dev,ci_high\n";
  for (std::size_t c = 0; c < curves.size(); ++c) {
    for (std::size_t s = 0; s < stats.size(); ++s) {
      const auto u = unit_for(stats[s], unit);
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
                        const OutputUnit& unit) {
  nlohmann::json doc;
  doc["tool"] = "sigmatau";
  doc["version"] = SIGMATAU_VERSION;
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
  }
  doc["results"] = nlohmann::json::array();
  for (std::size_t c = 0; c < curves.size(); ++c) {
    for (std::size_t s = 0; s < stats.size(); ++s) {
      const auto u = unit_for(stats[s], unit);
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
  return doc.dump(1) + "\n";
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

  LoadedChannels loaded = load_channels(args.log);
  const OutputUnit unit = output_unit(loaded, args.out_unit);
  const auto samples = loaded.log.channels.front().size();
  std::vector<PhaseSeries> series;
  series.reserve(loaded.log.channels.size());
  for (auto& channel : loaded.log.channels) {
    series.push_back(PhaseSeries::from_samples(channel, loaded.kind, 1.0 / loaded.rate_hz));
    std::vector<double>().swap(channel);  // the raw samples are no longer needed
  }
  const auto curves = compute_allan_curves(series, stats, taus, args.ci, args.threads);

  std::string text;
  if (args.format == "table") text = render_table(loaded, samples, stats, curves, unit);
  if (args.format == "csv") text = render_csv(loaded, stats, curves, unit);
  if (args.format == "json") text = render_json(loaded, samples, stats, curves, unit);
  if (args.output.empty()) {
    std::cout << text;
  } else {
    write_file_atomically(args.output, text, args.force);
  }
  if (!args.plot.empty()) {
    // The first statistic asked, every channel, with its confidence band.
    const auto u = unit_for(stats.front(), unit);
    DeviationPlot plot;
    plot.title = loaded.log.path;
    std::string name(to_string(stats.front()));
    for (char& ch : name) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
    plot.y_label = name + " [" + (u.label.empty() ? "input unit" : u.label) + "]";
    for (std::size_t c = 0; c < curves.size(); ++c) {
      PlotCurve curve;
      curve.name = loaded.log.channel_names[c];
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
  command->add_option("--stat", args->statistics,
                      "statistics, comma-separated: oadev,adev,mdev,tdev,hdev,ohdev,totdev")
      ->capture_default_str();
  command->add_option("--taus", args->taus,
                      "averaging times: octave | decade | many[:P] | all | list of seconds")
      ->capture_default_str();
  command->add_option("--ci", args->ci, "two-sided confidence level of the intervals")
      ->capture_default_str();
  command->add_option("--format", args->format, "table | csv | json")->capture_default_str();
  command->add_option("-o,--output", args->output, "write to FILE (atomically) instead of stdout");
  command->add_flag("--force", args->force, "overwrite an existing output file");
  command->add_option("--out-unit", args->out_unit,
                      "unit of the printed deviations, e.g. deg/h (needs --unit)");
  command->add_option("--plot", args->plot,
                      "also plot the first statistic to FILE (.svg, .png or .pdf; needs gnuplot)");
  command->add_option("--threads", args->threads, "worker threads (0: one per core)")
      ->capture_default_str();
  command->callback([args] { run_adev(*args); });
}

}  // namespace sigmatau::cli
