// `sigmatau demo`: `analyze` on a log simulated from a shipped data sheet (the built-in demo).
//
// The sheet's noise terms come from simulate_spec.hpp, as for `simulate --spec`: a sensor the
// sheet gives no noise term is left out (named in the report's Warnings), one without white noise
// is simulated with what the sheet gives and warned about, and a sheet with no noise term for
// either sensor is refused (exit 2).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "analysis_chain.hpp"
#include "log_options.hpp"
#include "sigmatau/analysis.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/resources.hpp"
#include "sigmatau/sampling_limits.hpp"
#include "sigmatau/simulate.hpp"
#include "sigmatau/simulate_spec.hpp"
#include "sigmatau/units.hpp"
#include "verbs.hpp"

namespace sigmatau::cli {
namespace {

struct DemoArguments {
  ChainArguments chain;
  std::string sheet = "safran_stim300";
  /// Simulated duration [h]. 10 h: the STIM300's weak flicker floor shows only at the last taus
  /// of a 3 h log, whose verdict on the gyro's bias instability was marginal or fail in 7 of 12
  /// seeds at 0.8 x typical (all pass in 12 of 12 at 10 h; ~1 GB peak, about 4 s once built).
  double hours = 10.0;
  double rate_hz = 100.0;  ///< simulated sample rate [Hz]
  std::uint64_t seed = 1;
  /// The simulated unit's noise terms as a fraction of the sheet's nominal values (typ, else
  /// max): a unit a little better than nominal, so the demo shows margins rather than a coin
  /// toss at 1.0.
  double scale = 0.8;
};

std::string join(const std::vector<std::string>& items, const std::string& separator) {
  std::string s;
  for (const auto& item : items) s += (s.empty() ? "" : separator) + item;
  return s;
}

/// "%g" of a number, for the texts.
std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

/// The noise terms of `sensor` the sheet prints without a typical value (simulated at their
/// maximum, or minimum, as SpecValue::nominal), e.g. "accel bias instability".
std::vector<std::string> non_typical_terms(const DataSheet& sheet, Sensor sensor) {
  std::vector<std::string> out;
  const SensorSheet* section = sheet.sensor(sensor);
  if (!section) return out;
  for (const SpecField field : {SpecField::noise_density, SpecField::random_walk,
                                SpecField::bias_instability, SpecField::rate_random_walk}) {
    const SpecValue* value = section->find(field);
    if (!value || value->typ || !value->nominal()) continue;
    std::string key(spec_field_info(sensor, field)->key);
    for (char& c : key) c = c == '_' ? ' ' : c;
    out.push_back(std::string(to_string(sensor)) + " " + key + " " + value->nominal()->text +
                  (value->max ? " (max)" : " (min)"));
  }
  return out;
}

/// What the demo simulates of a data sheet, and what it says about what it leaves out.
struct DemoNoise {
  SimulationConfig config;               ///< rate, samples, seed, truth left to the caller
  std::vector<std::string> notes;        ///< for the report's Warnings and stderr
  std::vector<std::string> non_typical;  ///< terms taken at their max / min (non_typical_terms)
};

/// Each sensor of `sheet` with at least one noise term, its terms x `scale`, with the
/// noise_source the sidecar records; a sensor without noise terms is left out with a note, one
/// without white noise is simulated and noted. Throws Error naming the sheet and what it lacks
/// when neither sensor has a noise term.
DemoNoise demo_noise(const DataSheet& sheet, DensityConvention convention, double scale) {
  DemoNoise out;
  std::vector<std::string> gaps;
  for (Sensor sensor : {Sensor::gyro, Sensor::accel}) {
    const std::string what(to_string(sensor));
    if (const std::string gap = sheet_noise_gap(sheet, sensor, convention); !gap.empty()) {
      gaps.push_back(gap);
      out.notes.push_back(sheet.label() + " " + gap + ", so the demo leaves the " + what +
                          " out (it would be simulated without noise)");
      continue;
    }
    SheetNoise noise = simulation_noise_from_data_sheet(sheet, sensor, convention);
    if (!noise.has_white)
      out.notes.push_back(sheet.label() + " prints no white noise for the " + what +
                          ", so the demo simulates the " + what + " with " +
                          join(noise.read, " and ") + " only (left out: " +
                          join(noise.left_out, ", ") +
                          "): its Allan deviation has no white-noise slope and its filter files "
                          "lack the " + what + " noise density");
    scale_sheet_noise(noise, scale);
    ErrorModel model;
    model.noise = noise.axes;
    (sensor == Sensor::gyro ? out.config.gyro : out.config.accel) = model;
    (sensor == Sensor::gyro ? out.config.gyro_noise_source : out.config.accel_noise_source) =
        NoiseSource{sheet_noise_origin(sheet, scale), noise.read, noise.left_out};
    for (auto& term : non_typical_terms(sheet, sensor)) out.non_typical.push_back(std::move(term));
  }
  if (!out.config.gyro && !out.config.accel)
    throw Error(sheet.label() + " " + join(gaps, " and ") +
                ", so the demo has nothing to simulate; pick a sheet that prints noise terms "
                "(sigmatau specs list) or simulate a unit with sigmatau simulate --model / "
                "--accel-model");
  return out;
}

/// Where the sheet was read: "specs/NAME.yaml" for a shipped sheet, else its path as given
/// (`--sheet my_imu.yaml`).
std::string sheet_location(const DataSheet& sheet) {
  std::error_code error;
  const bool shipped =
      std::filesystem::equivalent(sheet.file.parent_path(), resource_dir("specs"), error);
  return shipped ? "specs/" + sheet.name + ".yaml" : sheet.file.string();
}

/// The demo log's description (the report's "file"): the sheet, what was simulated and how.
std::string demo_description(const DataSheet& sheet, const DemoArguments& args,
                             const DemoNoise& noise) {
  std::string sensors = noise.config.gyro && noise.config.accel ? "gyro and accel"
                        : noise.config.gyro                     ? "gyro only"
                                                                : "accel only";
  std::string terms = "its typical noise terms";
  if (!noise.non_typical.empty())
    terms += " and, where no typical is printed, its " + join(noise.non_typical, ", its ");
  char run[96];
  std::snprintf(run, sizeof run, "%g h at %g Hz, seed %llu", args.hours, args.rate_hz,
                static_cast<unsigned long long>(args.seed));
  return "demo: " + sheet.manufacturer + " " + sheet.part + " (" + sensors +
         ") simulated from " + sheet_location(sheet) + " with " + number(args.scale) + " x " +
         terms + " (" + run + ")";
}

void run_demo(const DemoArguments& args) {
  const DataSheet sheet = load_data_sheet(find_data_sheet(args.sheet, resource_dir("specs")));
  checked_rate_hz(args.rate_hz, "--rate");
  if (!(args.hours > 0)) throw Error("--hours must be > 0");
  check_sheet_noise_scale(args.scale);
  DemoNoise noise = demo_noise(sheet, parse_density_convention(args.chain.convention), args.scale);
  check_output(args.chain);  // before the simulation
  SimulationConfig& config = noise.config;
  config.rate_hz = args.rate_hz;
  config.samples = checked_samples(args.hours * 3600, args.rate_hz, "--hours");
  config.seed = args.seed;
  StaticPose pose;
  pose.latitude_rad = 45.0 * kRadiansPerDegree;
  config.truth = static_truth(pose);
  config.threads = args.chain.threads == 0 ? 2 : args.chain.threads;
  Simulator simulator(config);
  AnalysisInput input;
  input.path = demo_description(sheet, args, noise);
  input.rate_hz = args.rate_hz;
  const auto names = simulator.channel_names();
  for (const auto& name : names) {
    AnalysisChannel channel;
    channel.name = name;
    channel.role = classify_channel(name);
    channel.values.reserve(static_cast<std::size_t>(config.samples));
    input.channels.push_back(std::move(channel));
    input.input_units.push_back("");
  }
  std::vector<double> block(static_cast<std::size_t>(65536) * names.size());
  while (true) {
    const std::int64_t rows = simulator.next(block, 65536);
    if (rows == 0) break;
    for (std::int64_t r = 0; r < rows; ++r) {
      for (std::size_t c = 0; c < names.size(); ++c)
        input.channels[c].values.push_back(block[r * names.size() + c]);
    }
  }
  ChainArguments chain = args.chain;
  if (chain.spec.empty()) chain.spec = args.sheet;
  if (chain.trim == "auto") chain.trim = "none";  // a simulated log has no warm-up
  chain.edf_model = EdfModel::discrete;  // simulated IMU samples: discrete noise
  finish([&](const AnalysisOptions& options) { return run_analysis(std::move(input), options); },
         chain, {{"truth.json", simulation_sidecar_json(config)}}, flicker_taps(config),
         noise.notes);
}

}  // namespace

void add_demo_command(CLI::App& app) {
  auto args = std::make_shared<DemoArguments>();
  args->chain.output = "demo-output";
  CLI::App* command = app.add_subcommand(
      "demo",
      "Simulate a log from a shipped data sheet and run `analyze` on it (the built-in demo)");
  command->add_option("--sheet", args->sheet, "data sheet to simulate (a name in specs/, or a sheet's YAML file)")
      ->capture_default_str();
  command->add_option("--hours", args->hours, "simulated duration [h]")->capture_default_str();
  command->add_option("--rate", args->rate_hz, "simulated sample rate [Hz]")->capture_default_str();
  command->add_option("--seed", args->seed, "random seed")->capture_default_str();
  command
      ->add_option("--scale", args->scale,
                   "simulated noise terms as a fraction of the sheet's values (typical, or the "
                   "maximum where no typical is printed)")
      ->capture_default_str();
  add_chain_options(*command, args->chain);
  command->callback([args] { run_demo(*args); });
}

}  // namespace sigmatau::cli
