// `sigmatau psd`: Welch PSD of every channel and the white-noise density read from it.
#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "channel_units.hpp"
#include "json_text.hpp"
#include "log_options.hpp"
#include "memory_budget.hpp"
#include "psd_stream.hpp"
#include "sigmatau/data_checks.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/output_file.hpp"
#include "sigmatau/plot.hpp"
#include "sigmatau/psd.hpp"
#include "verbs.hpp"

namespace sigmatau::cli {
namespace {

/// Log bins per decade of a plotted PSD: smooth enough to read, fine enough to see features.
constexpr int kPlotBinsPerDecade = 20;

struct PsdArguments {
  LogArguments log;
  std::int64_t segment = 0;
  double overlap = 0.5;
  std::string window = "hann";
  std::string detrend = "mean";
  std::string band;
  int bins_per_decade = 0;
  double ci = 0.683;
  std::string format = "table";
  std::string output;
  std::string out_unit;
  bool force = false;
  std::string plot;
  std::string memory = "1GiB";
};

std::optional<std::pair<double, double>> parse_band(const std::string& text) {
  if (text.empty()) return std::nullopt;
  const auto colon = text.find(':');
  try {
    if (colon == std::string::npos) throw std::invalid_argument("no colon");
    std::size_t used1 = 0, used2 = 0;
    const double f1 = std::stod(text.substr(0, colon), &used1);
    const double f2 = std::stod(text.substr(colon + 1), &used2);
    if (used1 != colon || used2 != text.size() - colon - 1) throw std::invalid_argument("trailing");
    return std::make_pair(f1, f2);
  } catch (const std::exception&) {
    throw Error("--band expects F1:F2 in Hz (e.g. 1:10), got \"" + text + "\"");
  }
}

struct DensityUnit {
  std::string psd_label;      // unit of the PSD values
  std::string density_label;  // unit of the noise density
  double density_from_si = 1; // printed density = computed * factor
  double psd_from_si = 1;
};

/// The units of every channel's PSD and noise density: its own rate unit (rate_unit), or the
/// --out-unit of the density's dimension ("deg/sqrt(h)", or one per sensor:
/// "deg/sqrt(h),ug/sqrt(Hz)").
std::vector<DensityUnit> density_units(const LoadedChannels& loaded, const std::string& out_unit) {
  std::vector<RateUnit> rates;
  std::vector<Dimension> densities;
  std::vector<bool> known;
  for (const ChannelUnit& cu : loaded.channel_units) {
    rates.push_back(rate_unit(cu, loaded.kind));
    Dimension d = rates.back().dimension;
    d.time2 += 1;  // x sqrt(s) = / sqrt(Hz)
    densities.push_back(d);
    known.push_back(!rates.back().label.empty());
  }
  const std::vector<std::string> outs =
      out_unit.empty() ? std::vector<std::string>{} : split_list(out_unit, "--out-unit");
  const std::vector<int> chosen = match_out_units(outs, densities, known, "a noise density of these channels is");
  std::vector<DensityUnit> units;
  for (std::size_t c = 0; c < rates.size(); ++c) {
    DensityUnit u;
    if (!known[c]) {
      u.psd_label = "(input unit)^2/Hz";
      u.density_label = "(input unit)/sqrt(Hz)";
      units.push_back(u);
      continue;
    }
    u.psd_label = "(" + rates[c].label + ")^2/Hz";
    u.psd_from_si = rates[c].from_result * rates[c].from_result;
    u.density_label = rates[c].label + "/sqrt(Hz)";
    u.density_from_si = rates[c].from_result;
    if (chosen[c] >= 0) {
      const std::string& text = outs[static_cast<std::size_t>(chosen[c])];
      u.density_label = text;
      u.density_from_si = loaded.channel_units[c].result_to_si / parse_unit(text).factor;
    }
    units.push_back(u);
  }
  return units;
}

void run_psd(const PsdArguments& args) {
  WelchOptions options;
  options.segment_length = args.segment;
  if (args.segment > kMaxSegmentLength) {
    throw Error("--segment must be at most " + std::to_string(kMaxSegmentLength) +
                " samples (FFTW's transform length is an int), got " + std::to_string(args.segment));
  }
  options.overlap = args.overlap;
  options.window = parse_window(args.window);
  options.detrend = parse_detrend(args.detrend);
  const auto band = parse_band(args.band);
  if (args.bins_per_decade < 0) throw Error("--bins-per-decade must be >= 0");
  if (args.format != "table" && args.format != "csv" && args.format != "json") {
    throw Error("--format must be table, csv or json, got \"" + args.format + "\"");
  }
  if (!args.output.empty()) check_can_write(args.output, args.force);
  if (!args.plot.empty()) {
    plot_format_for(args.plot);
    check_can_write(args.plot, args.force);
  }

  const std::int64_t memory = parse_bytes(args.memory);
  if (const auto early = early_channel_units(args.log)) {
    density_units(*early, args.out_unit);  // the units and --out-unit, before a long read
  } else {
    LoadedChannels unit_only;  // --kind, --unit and --out-unit are checked before reading
    set_input_unit(args.log, unit_only);
    if (!per_channel_units(args.log)) {  // channel units from names or a bag: known once read
      unit_only.channel_units.push_back(
          {unit_only.unit, unit_only.dimension, unit_only.to_si, 1.0, "--unit"});
      density_units(unit_only, args.out_unit);
    }
  }

  LogPsd computed = log_psd(args.log, options, memory);
  const LoadedChannels& loaded = computed.input;
  const std::vector<DensityUnit> units = density_units(loaded, args.out_unit);
  // A constant channel has no noise: its "density" is rounding residue (1e-31): said.
  std::vector<std::string> warnings;
  for (std::size_t c = 0; c < computed.constant_value.size(); ++c) {
    if (!computed.constant_value[c]) continue;
    char value[40];
    std::snprintf(value, sizeof value, "%.9g", *computed.constant_value[c]);
    warnings.push_back(constant_channel_text(loaded.log.channel_names[c],
                                             "every value is " + std::string(value)) +
                       "; its PSD and noise density are rounding residue, not noise");
    std::cerr << "sigmatau: warning: " << args.log.input << ": " << warnings.back() << "\n";
  }
  for (const std::string& message : computed.outlier_warnings) {  // analyze's text, as it is
    warnings.push_back(message);
    std::cerr << "sigmatau: warning: " << args.log.input << ": " << warnings.back() << "\n";
  }

  std::vector<PsdCurve> curves;
  std::vector<PsdCurve> plotted;  // log-binned for the plot
  std::vector<NoiseDensity> densities;
  for (PsdCurve& psd : computed.curves) {
    densities.push_back(noise_density(psd, band, args.ci));
    if (!args.plot.empty()) plotted.push_back(log_binned(psd, kPlotBinsPerDecade));
    curves.push_back(args.bins_per_decade > 0 ? log_binned(psd, args.bins_per_decade) : std::move(psd));
  }

  std::ostringstream out;
  std::string json_text;  // JSON is dumped straight into one string (a PSD of 2^20-sample
                          // segments is ~40 MB of JSON per channel: no second copy in `out`)
  if (args.format == "json") {
    nlohmann::json doc;
    doc["tool"] = "sigmatau";
    doc["version"] = SIGMATAU_VERSION;
    doc["input"] = {{"path", loaded.log.path}, {"rate_hz", loaded.rate_hz},
                    {"kind", std::string(to_string(loaded.kind))}, {"unit", loaded.unit}};
    doc["warnings"] = warnings;
    doc["results"] = nlohmann::json::array();
    for (std::size_t c = 0; c < curves.size(); ++c) {
      const DensityUnit& unit = units[c];
      const auto& psd = curves[c];
      const auto& nd = densities[c];
      std::vector<double> values;
      for (double p : psd.psd) values.push_back(p * unit.psd_from_si);
      doc["results"].push_back(
          {{"channel", loaded.log.channel_names[c]},
           {"unit", unit.psd_label},
           {"convention", "one-sided"},
           {"window", std::string(to_string(psd.window))},
           {"segment_length", psd.segment_length},
           {"segments", psd.segments},
           {"overlap", psd.overlap},
           {"frequency", psd.frequency_hz},
           {"psd", values},
           {"edf", psd.edf},
           {"noise_density",
            {{"value", nd.value * unit.density_from_si},
             {"ci_low", nd.ci_low * unit.density_from_si},
             {"ci_high", nd.ci_high * unit.density_from_si},
             {"confidence", args.ci},
             {"unit", unit.density_label},
             {"convention", "N = sqrt(two-sided PSD level): data-sheet / Kalibr / Allan N"},
             {"band_hz", {nd.band_low_hz, nd.band_high_hz}},
             {"band_detected", nd.band_detected},
             {"edf", nd.edf},
             {"one_sided_asd", nd.one_sided_asd * unit.density_from_si}}}});
    }
    json_text = cli::json_text(doc, 1);
    json_text += '\n';
  } else if (args.format == "csv") {
    out << "channel,frequency_hz,psd,edf,unit\n";
    for (std::size_t c = 0; c < curves.size(); ++c) {
      const DensityUnit& unit = units[c];
      for (std::size_t k = 0; k < curves[c].psd.size(); ++k) {
        char line[128];
        std::snprintf(line, sizeof line, "%.9g,%.9e,%.6g,", curves[c].frequency_hz[k],
                      curves[c].psd[k] * unit.psd_from_si, curves[c].edf[k]);
        out << loaded.log.channel_names[c] << ',' << line << unit.psd_label << '\n';
      }
    }
  } else {
    out << "# " << loaded.log.path << ": rate " << loaded.rate_hz << " Hz; one-sided PSD; noise density N = sqrt(two-sided level) (data-sheet/Kalibr convention), one-sided ASD = sqrt(2) N\n";
    for (std::size_t c = 0; c < curves.size(); ++c) {
      const auto& nd = densities[c];
      const DensityUnit& unit = units[c];
      char line[256];
      std::snprintf(line, sizeof line,
                    "%-8s N = %.5g [%.5g, %.5g] %s (%.1f%%)  band %.4g-%.4g Hz%s  one-sided ASD %.5g\n",
                    loaded.log.channel_names[c].c_str(), nd.value * unit.density_from_si,
                    nd.ci_low * unit.density_from_si, nd.ci_high * unit.density_from_si,
                    unit.density_label.c_str(), args.ci * 100, nd.band_low_hz, nd.band_high_hz,
                    nd.band_detected ? " (auto)" : "", nd.one_sided_asd * unit.density_from_si);
      out << line;
    }
    if (args.bins_per_decade > 0) {
      for (std::size_t c = 0; c < curves.size(); ++c) {
        const DensityUnit& unit = units[c];
        out << "\n# " << loaded.log.channel_names[c] << "  PSD [" << unit.psd_label << "]\n";
        for (std::size_t k = 0; k < curves[c].psd.size(); ++k) {
          char line[96];
          std::snprintf(line, sizeof line, "%12.5g %14.6e %10.4g\n", curves[c].frequency_hz[k],
                        curves[c].psd[k] * unit.psd_from_si, curves[c].edf[k]);
          out << line;
        }
      }
    }
  }
  if (args.output.empty()) {
    std::cout << (args.format == "json" ? json_text : out.str());
  } else {
    write_file_atomically(args.output, args.format == "json" ? json_text : out.str(), args.force);
  }
  if (!args.plot.empty()) {
    SpectrumPlot plot;
    plot.title = loaded.log.path;
    bool one_unit = true;
    for (const auto& u : units) one_unit = one_unit && u.psd_label == units.front().psd_label;
    plot.y_label = "one-sided PSD [" + (one_unit ? units.front().psd_label : std::string("unit per channel")) + "]";
    for (std::size_t c = 0; c < plotted.size(); ++c) {
      const DensityUnit& unit = units[c];
      PlotCurve curve;
      curve.name = loaded.log.channel_names[c] + (one_unit ? "" : " [" + unit.psd_label + "]");
      curve.x = plotted[c].frequency_hz;
      for (double p : plotted[c].psd) curve.y.push_back(p * unit.psd_from_si);
      plot.curves.push_back(std::move(curve));
      const double asd = densities[c].one_sided_asd;
      const double level = asd * asd * unit.psd_from_si;
      PlotCurve line;
      line.name = loaded.log.channel_names[c] + " noise density";
      line.x = {densities[c].band_low_hz, densities[c].band_high_hz};
      line.y = {level, level};
      plot.lines.push_back(std::move(line));
    }
    render_spectrum_plot(plot, args.plot, args.force);
  }
}

}  // namespace

void add_psd_command(CLI::App& app) {
  auto args = std::make_shared<PsdArguments>();
  CLI::App* command = app.add_subcommand(
      "psd", "Welch power spectral density (one-sided) and the white-noise density read from it");
  add_log_options(*command, args->log);
  add_sensor_unit_options(*command, args->log);
  // Checked only when given (0, the default, means "choose"): a zero or negative length used to be
  // taken silently as that default.
  command->add_option("--segment", args->segment,
                      "samples per segment (default: largest power of two <= samples/8)")
      ->check([](const std::string& value) {
        std::int64_t samples = 0;
        const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), samples);
        return ec == std::errc() && end == value.data() + value.size() && samples > 0
                   ? std::string()
                   : "expected a positive number of samples (at least 4), got " + value;
      });
  command->add_option("--overlap", args->overlap, "overlap of consecutive segments, 0..<1")
      ->capture_default_str();
  command->add_option("--window", args->window, "hann | blackman-harris | rectangular")
      ->capture_default_str();
  command->add_option("--detrend", args->detrend, "per segment: none | mean | linear")
      ->capture_default_str();
  command->add_option("--band", args->band,
                      "F1:F2 [Hz] band for the noise density (default: widest flat band)");
  command->add_option("--bins-per-decade", args->bins_per_decade,
                      "average the PSD into log-spaced bins (0: every FFT bin)")
      ->capture_default_str();
  command->add_option("--ci", args->ci,
                      "two-sided confidence level of the noise-density interval; 0.683 (one "
                      "sigma) by default, as adev's error bars, so the two compare (fit and "
                      "calibrate default to 0.95)")
      ->capture_default_str();
  command->add_option("--format", args->format, "table | csv | json")->capture_default_str();
  command->add_option("-o,--output", args->output, "write to FILE (atomically) instead of stdout");
  command->add_flag("--force", args->force, "overwrite an existing output file");
  command->add_option("--plot", args->plot, "also plot the PSD to FILE (.svg, .png or .pdf)");
  command->add_option("--out-unit", args->out_unit,
                      "unit of the noise density, e.g. deg/s/sqrt(Hz), deg/sqrt(h), ug/sqrt(Hz); one per "
                      "sensor: deg/sqrt(h),ug/sqrt(Hz) (needs --unit, --gyro-unit or --accel-unit, "
                      "or a ROS bag)");
  command->add_option("--memory", args->memory,
                      "most samples held while the default --segment cannot be chosen yet (it "
                      "depends on the log's length); a longer file is counted first, a longer "
                      "pipe needs --segment. The PSD itself is computed segment by segment")
      ->capture_default_str();
  command->callback([args] { run_psd(*args); });
}

}  // namespace sigmatau::cli
