// `sigmatau convert`: data sheet or typed-in noise terms -> discrete covariances at a filter
// rate, exported for a filter project, with the arithmetic on request (--explain).
#include <array>
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
  // Typed terms, each for the sensor its unit names (or --sensor): at most one of each per sensor.
  std::vector<std::string> noise_density;
  std::vector<std::string> bias_stability;
  std::vector<std::string> random_walk;
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
  bool allow_incomplete = false;
  std::string output;
  bool force = false;
};

/// --sensor when given; otherwise the sensor whose dimension the typed term's unit has
/// ("70 ug/sqrt(Hz)" is an accelerometer's), gyro when it tells none (the term's own parsing then
/// says what was expected).
Sensor typed_sensor(const std::string& sensor_option, const std::string& text) {
  if (sensor_option == "gyro") return Sensor::gyro;
  if (sensor_option == "accel") return Sensor::accel;
  if (!sensor_option.empty()) {
    throw Error("--sensor: found \"" + sensor_option + "\", expected gyro or accel");
  }
  try {
    const Dimension d = parse_quantity(text).dimension;
    if (d == dim::velocity_random_walk || d == dim::acceleration ||
        d == dim::accel_rate_random_walk) {
      return Sensor::accel;
    }
  } catch (const UnitError&) {
    // Malformed: reported with the option's name when the term itself is parsed.
  }
  return Sensor::gyro;
}

/// The terms typed for one sensor and what they were.
struct TypedSensor {
  NoiseTerms terms;
  std::string white_origin, bias_origin;
  bool any() const { return terms.white || terms.bias_instability || terms.rate_random_walk; }
};

/// Index of a sensor's TypedSensor in typed_terms' result.
std::size_t slot_of(Sensor sensor) { return sensor == Sensor::gyro ? 0 : 1; }

/// The typed terms by sensor (gyro, accel); a term typed twice for one sensor is refused.
std::array<TypedSensor, 2> typed_terms(const ConvertArguments& args,
                                       DensityConvention convention) {
  std::array<TypedSensor, 2> typed;
  const auto once = [](bool given, const char* option, Sensor sensor) {
    if (given) {
      throw Error(std::string(option) + " is given twice for the " +
                  std::string(to_string(sensor)) + " (each sensor takes one)");
    }
  };
  for (const std::string& text : args.noise_density) {
    const Sensor sensor = typed_sensor(args.sensor, text);
    const bool gyro = sensor == Sensor::gyro;
    TypedSensor& t = typed[slot_of(sensor)];
    once(t.terms.white.has_value(), "--noise-density", sensor);
    const double nd = parse_quantity_as(
        text, gyro ? dim::angle_random_walk : dim::velocity_random_walk, "--noise-density");
    if (!(nd > 0)) throw Error("--noise-density must be > 0");
    // A unit per root hour or second (deg/sqrt(h), m/s/sqrt(h)) is an ARW / VRW, i.e. the
    // Allan N itself, as a data sheet's random-walk line is: no density convention applies.
    // Only a value per root Hz is a PSD level.
    std::string lower = text;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const bool random_walk_form = lower.find("hz") == std::string::npos;
    t.terms.white = random_walk_form ? nd : white_from_noise_density(nd, convention);
    t.white_origin = "noise density " + text + " " +
                     (random_walk_form
                          ? "read as the random walk N itself (a unit per root time, not per "
                            "root Hz: no density convention applies)"
                          : std::string(noise_density_reading(convention)));
  }
  for (const std::string& text : args.bias_stability) {
    const Sensor sensor = typed_sensor(args.sensor, text);
    TypedSensor& t = typed[slot_of(sensor)];
    once(t.terms.bias_instability.has_value(), "--bias-stability", sensor);
    const double b = parse_quantity_as(
        text, sensor == Sensor::gyro ? dim::angular_rate : dim::acceleration, "--bias-stability");
    if (!(b > 0)) throw Error("--bias-stability must be > 0");
    t.terms.bias_instability = b / kFlickerFloorFactor;
    t.bias_origin = "bias stability " + text + " read as the ADEV floor 0.664 B";
  }
  for (const std::string& text : args.random_walk) {
    const Sensor sensor = typed_sensor(args.sensor, text);
    TypedSensor& t = typed[slot_of(sensor)];
    once(t.terms.rate_random_walk.has_value(), "--random-walk", sensor);
    const double k = parse_quantity_as(
        text, sensor == Sensor::gyro ? dim::gyro_rate_random_walk : dim::accel_rate_random_walk,
        "--random-walk");
    if (!(k > 0)) throw Error("--random-walk must be > 0");
    t.terms.rate_random_walk = k;
    t.bias_origin += std::string(t.bias_origin.empty() ? "" : "; ") + "rate random walk K = " + text;
  }
  return typed;
}

/// The error for a file whose consumer needs values the input lacks: which, what they are, and
/// the options that supply them.
std::string incomplete_error(ExportFormat format, const std::vector<MissingFilterValue>& missing,
                             const std::string& source) {
  std::string keys;
  for (const auto& m : missing) keys += (keys.empty() ? "" : ", ") + m.key;
  return "the " + std::string(to_string(format)) + " file needs " + keys + ", which " + source +
         " does not give (" + missing_values_text(missing) + "; " +
         std::string(missing_key_consequence(format)) +
         "). Give them with --noise-density, --random-walk or --bias-stability, also beside "
         "--spec or --fit (each term goes to the sensor its unit names: ug/sqrt(Hz), "
         "m/s^2/sqrt(s) an accelerometer's, deg/s/sqrt(Hz), deg/h/sqrt(h) a gyroscope's), take "
         "them from a log of the unit (sigmatau fit --format json, then --fit), or write the "
         "file without them with --allow-incomplete";
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
  if (!args.spec.empty() && !args.fit.empty()) {
    throw Error("give one of --spec FILE|NAME or --fit RESULT.json (typed terms, --noise-density, "
                "--bias-stability, --random-walk, may go with either)");
  }
  if (args.spec.empty() && args.fit.empty() && !typed) {
    throw Error("give --spec FILE|NAME, --fit RESULT.json, or the terms (--noise-density, "
                "--bias-stability, --random-walk)");
  }
  std::optional<ExportFormat> format;
  if (!args.to.empty()) format = parse_export_format(args.to);
  ExportOptions export_options;
  export_options.rostopic = args.rostopic;
  if (format == ExportFormat::px4) {
    // Checked before anything is read: PX4's documented range, whole microseconds.
    export_options.px4_predict_interval_s =
        quantity_option(args.px4_predict, dim::time, "--px4-predict", "us");
    try {
      px4_prediction_interval(export_options.px4_predict_interval_s, options.rate_hz);
    } catch (const Error& e) {
      throw Error("--px4-predict: " + std::string(e.what()));
    }
  }
  if (!args.output.empty()) {
    if (!format) throw Error("-o needs --to FORMAT (kalibr, openvins, vins-fusion, gtsam, px4, json)");
    check_can_write(args.output, args.force);
  }
  const auto typed_by_sensor = typed_terms(args, options.convention);

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
      } else if (!typed_by_sensor[slot_of(s)].any()) {
        silent_sensors += std::string(to_string(s)) +
                          ": not given (the sheet describes it but prints no noise density, "
                          "ARW/VRW, bias stability or rate random walk for it)\n";
      }
    }
    if (triads.empty() && !typed) {
      throw Error(file.string() + " prints no noise density, ARW/VRW, bias stability or rate "
                                  "random walk: nothing to convert");
    }
  } else {
    source = "command-line terms";
  }
  if (typed) {
    std::vector<TriadNoise>& into = fit ? fit->triads : triads;
    for (const Sensor s : {Sensor::gyro, Sensor::accel}) {
      const TypedSensor& t = typed_by_sensor[slot_of(s)];
      if (t.any()) replace_with_typed_terms(into, s, t.terms, t.white_origin, t.bias_origin);
    }
    if (!args.spec.empty() || !args.fit.empty()) source += " and command-line terms";
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
  if (const auto missing = missing_filter_values(noise, *format); !missing.empty()) {
    if (!args.allow_incomplete) throw Error(incomplete_error(*format, missing, source));
    std::string keys;
    for (const auto& m : missing) keys += (keys.empty() ? "" : ", ") + m.key;
    std::cerr << "sigmatau: warning: the " << to_string(*format) << " file lacks " << keys
              << " (not in the input; written with --allow-incomplete): "
              << missing_key_consequence(*format) << "\n";
  }
  const std::string text = export_filter_config(noise, *format, export_options);
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
                      "the random walk itself, e.g. \"0.3 deg/sqrt(h)\" (no --density-convention then); "
                      "once per sensor, for the sensor its unit names; with --spec or --fit it "
                      "replaces theirs");
  command->add_option("--bias-stability", args->bias_stability,
                      "in-run bias stability (ADEV floor), e.g. \"3 deg/h\" or \"0.05 mg\"; once per "
                      "sensor; with --spec or --fit it replaces their bias");
  command->add_option("--random-walk", args->random_walk,
                      "rate random walk K, e.g. \"0.02 deg/h/sqrt(h)\"; once per sensor; with --spec "
                      "or --fit it replaces their bias");
  command->add_option("--sensor", args->sensor,
                      "gyro | accel (for every typed term; default: the one each term's unit names)");
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
                      "your EKF2_PREDICT_US, e.g. 10000 (us) or \"10 ms\", 1000-20000 us; EKF2 "
                      "rounds it to whole IMU intervals at --rate (8000 us at 200 Hz: 10 ms), "
                      "and so do the values")
      ->capture_default_str();
  command->add_flag("--allow-incomplete", args->allow_incomplete,
                    "write the file even when the input lacks values its filter needs (white "
                    "noise and bias of both sensors; refused by default, exit 2)");
  command->add_flag("--explain", args->explain,
                    "also print the arithmetic (to stderr when the export goes to stdout)");
  command->add_option("-o,--output", args->output, "write the export to FILE (atomically)");
  command->add_flag("--force", args->force, "overwrite an existing output file");
  command->callback([args] { run_convert(*args); });
}

}  // namespace sigmatau::cli
