// `sigmatau convert`: data sheet or typed-in noise terms -> discrete covariances at a filter
// rate, exported for a filter project, with the arithmetic on request (--explain).
#include <cctype>
#include <cstdlib>
#include <iostream>

#include "sigmatau/convert.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/filter_export.hpp"
#include "sigmatau/output_file.hpp"
#include "sigmatau/resources.hpp"
#include "sigmatau/sampling_limits.hpp"
#include "sigmatau/spec.hpp"
#include "sigmatau/units.hpp"
#include "log_options.hpp"
#include "verbs.hpp"

namespace sigmatau::cli {
namespace {

struct ConvertArguments {
  std::string spec;
  std::string fit;
  std::string noise_density;
  std::string bias_stability;
  std::string random_walk;
  std::string sensor;  // "" : from the typed terms' units
  std::string rate;
  std::string bias_model = "rw";
  std::string tref = "100 s";
  std::string tau_min;
  double inflate = 1;
  std::string convention = "two-sided";
  std::string to;
  std::string rostopic = ExportOptions{}.rostopic;
  std::string px4_predict = "10 ms";
  bool explain = false;
  std::string output;
  bool force = false;
};

/// --sensor when given; otherwise the sensor whose dimension the first typed term's unit has
/// ("70 ug/sqrt(Hz)" is an accelerometer's), gyro when none tells (the terms' own parsing then
/// says what was expected).
Sensor typed_sensor(const ConvertArguments& args) {
  if (args.sensor == "gyro") return Sensor::gyro;
  if (args.sensor == "accel") return Sensor::accel;
  if (!args.sensor.empty()) {
    throw Error("--sensor: found \"" + args.sensor + "\", expected gyro or accel");
  }
  for (const std::string* text : {&args.noise_density, &args.bias_stability, &args.random_walk}) {
    if (text->empty()) continue;
    try {
      const Dimension d = parse_quantity(*text).dimension;
      if (d == dim::angle_random_walk || d == dim::angular_rate || d == dim::gyro_rate_random_walk) {
        return Sensor::gyro;
      }
      if (d == dim::velocity_random_walk || d == dim::acceleration ||
          d == dim::accel_rate_random_walk) {
        return Sensor::accel;
      }
    } catch (const UnitError&) {
      // Malformed: reported with the option's name when the term itself is parsed.
    }
  }
  return Sensor::gyro;
}

void run_convert(const ConvertArguments& args) {
  ConvertOptions options;
  if (args.rate.empty()) throw Error("--rate is required (the filter's IMU rate, e.g. 200 Hz)");
  options.rate_hz = checked_rate_hz(quantity_option(args.rate, dim::frequency, "--rate", "Hz"), "--rate");
  options.bias_model = parse_bias_model(args.bias_model);
  options.t_ref_s = checked_time_s(quantity_option(args.tref, dim::time, "--tref", "s"), "--tref");
  if (!args.tau_min.empty()) {
    options.tau_min_s =
        checked_time_s(quantity_option(args.tau_min, dim::time, "--tau-min", "s"), "--tau-min");
  }
  options.inflate = args.inflate;
  options.convention = parse_density_convention(args.convention);
  const bool typed = !args.noise_density.empty() || !args.bias_stability.empty() ||
                     !args.random_walk.empty();
  const int sources = (args.spec.empty() ? 0 : 1) + (args.fit.empty() ? 0 : 1) + (typed ? 1 : 0);
  if (sources != 1) {
    throw Error("give one of --spec FILE|NAME, --fit RESULT.json, or the terms (--noise-density, "
                "--bias-stability, --random-walk)");
  }
  std::optional<ExportFormat> format;
  if (!args.to.empty()) format = parse_export_format(args.to);
  if (!args.output.empty()) {
    if (!format) throw Error("-o needs --to FORMAT (kalibr, openvins, vins-fusion, gtsam, px4, json)");
    check_can_write(args.output, args.force);
  }

  std::vector<TriadNoise> triads;
  std::optional<FitForFilter> fit;
  std::string source;
  // Sensors the sheet describes without any noise term: said in the explanation, as a sensor
  // with some terms says "white noise: not given" (the BMI088's accelerometer used to vanish).
  std::string silent_sensors;
  if (!args.fit.empty()) {
    fit = read_fit_for_filter(read_text_file(args.fit), args.fit);
    source = "noise-term fit " + args.fit;
  } else if (!args.spec.empty()) {
    const auto file = find_data_sheet(args.spec, resource_dir("specs"));
    const DataSheet sheet = load_data_sheet(file);
    source = "data sheet " + file.string();
    for (const Sensor s : {Sensor::gyro, Sensor::accel}) {
      if (!sheet.sensor(s)) continue;
      TriadNoise t = triad_from_data_sheet(sheet, s, options.convention);
      const NoiseTerms& a = t.axes[0];
      if (a.white || a.bias_instability || a.rate_random_walk) {
        triads.push_back(std::move(t));
      } else {
        silent_sensors += std::string(to_string(s)) +
                          ": not given (the sheet describes it but prints no noise density, "
                          "ARW/VRW, bias stability or rate random walk for it)\n";
      }
    }
    if (triads.empty()) {
      throw Error(file.string() + " prints no noise density, ARW/VRW, bias stability or rate "
                                  "random walk: nothing to convert");
    }
  } else {
    const Sensor sensor = typed_sensor(args);
    const bool gyro = sensor == Sensor::gyro;
    NoiseTerms terms;
    TriadNoise t;
    if (!args.noise_density.empty()) {
      const double nd = parse_quantity_as(
          args.noise_density, gyro ? dim::angle_random_walk : dim::velocity_random_walk,
          "--noise-density");
      if (!(nd > 0)) throw Error("--noise-density must be > 0");
      // A unit per root hour or second (deg/sqrt(h), m/s/sqrt(h)) is an ARW / VRW, i.e. the
      // Allan N itself, as a data sheet's random-walk line is: no density convention applies.
      // Only a value per root Hz is a PSD level.
      std::string lower = args.noise_density;
      for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      const bool random_walk_form = lower.find("hz") == std::string::npos;
      terms.white = random_walk_form ? nd : white_from_noise_density(nd, options.convention);
      t.white_origin =
          "noise density " + args.noise_density + " " +
          (random_walk_form ? "read as the random walk N itself (a unit per root time, not per "
                              "root Hz: no density convention applies)"
                            : std::string(noise_density_reading(options.convention)));
    }
    std::string bias;
    if (!args.bias_stability.empty()) {
      const double b = parse_quantity_as(args.bias_stability,
                                         gyro ? dim::angular_rate : dim::acceleration,
                                         "--bias-stability");
      if (!(b > 0)) throw Error("--bias-stability must be > 0");
      terms.bias_instability = b / kFlickerFloorFactor;
      bias = "bias stability " + args.bias_stability + " read as the ADEV floor 0.664 B";
    }
    if (!args.random_walk.empty()) {
      const double k = parse_quantity_as(
          args.random_walk, gyro ? dim::gyro_rate_random_walk : dim::accel_rate_random_walk,
          "--random-walk");
      if (!(k > 0)) throw Error("--random-walk must be > 0");
      terms.rate_random_walk = k;
      bias += std::string(bias.empty() ? "" : "; ") + "rate random walk K = " + args.random_walk;
    }
    t.sensor = sensor;
    t.axes = {terms, terms, terms};
    t.bias_origin = bias;
    triads.push_back(std::move(t));
    source = "command-line terms";
  }

  DiscreteNoise noise = fit ? convert_fit(*fit, options, source) : convert_noise(triads, options, source);
  noise.explain += silent_sensors;
  // What the files' headers say about the fit they rest on, said where a user sees it too.
  for (const auto& w : noise.warnings) std::cerr << "sigmatau: warning: " << args.fit << ": " << w << "\n";
  if (!noise.rate_note.empty()) std::cerr << "sigmatau: warning: " << noise.rate_note << "\n";
  if (!format) {
    std::cout << noise.explain;
    return;
  }
  ExportOptions export_options;
  export_options.rostopic = args.rostopic;
  export_options.px4_predict_interval_s =
      quantity_option(args.px4_predict, dim::time, "--px4-predict", "us");
  if (!(export_options.px4_predict_interval_s > 0)) {
    throw Error("--px4-predict: expected a time > 0, got \"" + args.px4_predict + "\"");
  }
  const std::string text = export_filter_config(noise, *format, export_options);
  if (const auto missing = missing_filter_keys(noise, *format); !missing.empty()) {
    std::string keys;
    for (const auto& k : missing) keys += (keys.empty() ? "" : ", ") + k;
    std::cerr << "sigmatau: warning: the " << to_string(*format) << " file lacks " << keys
              << " (not in the input); that tool refuses it until they are added\n";
  }
  if (!args.output.empty()) {
    write_file_atomically(args.output, text, args.force);
    if (args.explain) std::cout << noise.explain;
    std::cout << "wrote " << args.output << " (" << to_string(*format) << ")\n";
    return;
  }
  if (args.explain) std::cerr << noise.explain;
  std::cout << text;
}

}  // namespace

void add_convert_command(CLI::App& app) {
  auto args = std::make_shared<ConvertArguments>();
  CLI::App* command = app.add_subcommand(
      "convert",
      "continuous noise (data sheet or typed terms) -> discrete filter covariances at a rate, "
      "exported for kalibr, openvins, vins-fusion, gtsam, px4 or json");
  command->add_option("--spec", args->spec, "data sheet: a YAML file or a name from `specs list`");
  command->add_option("--fit", args->fit,
                      "a `sigmatau fit --format json` result or an analyze results.json");
  command->add_option("--noise-density", args->noise_density,
                      "printed noise density ND, e.g. \"0.015 deg/s/sqrt(Hz)\" or \"70 ug/sqrt(Hz)\", or "
                      "the random walk itself, e.g. \"0.3 deg/sqrt(h)\" (no --density-convention then)");
  command->add_option("--bias-stability", args->bias_stability,
                      "in-run bias stability (ADEV floor), e.g. \"3 deg/h\" or \"0.05 mg\"");
  command->add_option("--random-walk", args->random_walk,
                      "rate random walk K, e.g. \"0.02 deg/h/sqrt(h)\"");
  command->add_option("--sensor", args->sensor,
                      "gyro | accel (for the typed terms; default: the one their units name)");
  command->add_option("--rate", args->rate, "filter / IMU rate, e.g. 200 or \"200 Hz\"");
  command->add_option("--bias-model", args->bias_model, "rw (random walk) | gm (Gauss-Markov)")
      ->capture_default_str();
  command->add_option("--tref", args->tref,
                      "time after which the bias stability is reached (rw), e.g. 100s")
      ->capture_default_str();
  command->add_option("--tau-min", args->tau_min,
                      "tau of the ADEV minimum for --bias-model gm, on every axis (default: "
                      "with --fit, each axis's tau of the ADEV minimum the fit measured; else "
                      "--tref)");
  command->add_option("--inflate", args->inflate,
                      "inflation factor F: densities and sigmas x F, variances x F^2")
      ->capture_default_str();
  command->add_option("--density-convention", args->convention,
                      "two-sided (N = ND, Kalibr) | one-sided (N = ND/sqrt(2))")
      ->capture_default_str();
  command->add_option("--to,--format", args->to,
                      "kalibr | openvins | vins-fusion | gtsam | px4 | json (default: print the "
                      "arithmetic)");
  command->add_option("--rostopic", args->rostopic, "IMU topic in the kalibr / openvins file")
      ->capture_default_str();
  command->add_option("--px4-predict", args->px4_predict,
                      "PX4 EKF2 prediction interval, your EKF2_PREDICT_US, e.g. 10000 (us) or \"8 ms\"")
      ->capture_default_str();
  command->add_flag("--explain", args->explain,
                    "also print the arithmetic (to stderr when the export goes to stdout)");
  command->add_option("-o,--output", args->output, "write the export to FILE (atomically)");
  command->add_flag("--force", args->force, "overwrite an existing output file");
  command->callback([args] { run_convert(*args); });
}

}  // namespace sigmatau::cli
