// `sigmatau simulate`: a synthetic IMU log from a noise model, with its exact truth in a sidecar.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <iostream>
#include <filesystem>
#include <memory>
#include <optional>

#include "log_options.hpp"
#include "sigmatau/convert.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/output_file.hpp"
#include "sigmatau/resources.hpp"
#include "sigmatau/sampling_limits.hpp"
#include "sigmatau/spec.hpp"
#include "sigmatau/simulate.hpp"
#include "sigmatau/simulate_spec.hpp"
#include "sigmatau/units.hpp"
#include "verbs.hpp"

namespace sigmatau::cli {
namespace {

struct SimulateArguments {
  std::string gyro_model;
  std::string accel_model;
  std::string spec;
  /// --spec's noise terms as a fraction of the sheet's values (--scale); nullopt: not given.
  std::optional<double> scale;
  std::string convention = "two-sided";
  double rate_hz = 0;
  std::string duration;
  std::uint64_t seed = 1;
  std::string sensors = "gyro";
  std::string kind = "rate";
  std::string format = "csv";
  std::string output;
  std::string sidecar;  ///< empty: OUTPUT.json; "none": no sidecar
  bool force = false;
  std::string roll = "0 deg", pitch = "0 deg", yaw = "0 deg", latitude = "0 deg";
  std::string gyro_bias, accel_bias;
  std::string gyro_lsb, gyro_full_scale, accel_lsb, accel_full_scale;
  std::int64_t flicker_taps = std::int64_t{1} << 20;
  unsigned threads = 1;
  int positions = 0;
  std::string dwell = "20 s", rotation_rate = "90 deg/s";
  std::string temperature;
  std::string gyro_scale, accel_scale, gyro_misalignment, accel_misalignment;
  std::string gyro_temp_coef, accel_temp_coef;
  std::string out_unit;
  std::string gyro_quantizer, accel_quantizer;
  std::string truth_file, truth_unit;
};

/// Trims spaces at both ends.
std::string trim(std::string s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.erase(s.begin());
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.pop_back();
  return s;
}

/// A model option: "N=..., B=..." for all three axes, or per axis "x: N=...; y: N=...; z: ..."
/// where a label is any of x, y, z or a group such as "xy"; an axis no label names has no noise.
std::array<NoiseTerms, 3> axis_models(const std::string& text, Sensor sensor,
                                      const std::string& option) {
  std::vector<std::string> parts;
  for (std::size_t start = 0; start <= text.size();) {
    const std::size_t end = std::min(text.find(';', start), text.size());
    parts.push_back(trim(text.substr(start, end - start)));
    start = end + 1;
  }
  // The label of a part: the text before ':' when it is made of x, y, z only.
  const auto label_of = [](const std::string& part) -> std::string {
    const auto colon = part.find(':');
    if (colon == std::string::npos) return {};
    const std::string label = trim(part.substr(0, colon));
    if (label.empty() || label.find_first_not_of("xyz") != std::string::npos) return {};
    return label;
  };
  if (parts.size() == 1 && label_of(parts[0]).empty()) {
    const NoiseTerms t = parse_noise_terms(parts[0], sensor);
    return {t, t, t};
  }
  std::array<NoiseTerms, 3> axes;
  std::array<bool, 3> seen{};
  for (const auto& part : parts) {
    const std::string label = label_of(part);
    if (label.empty())
      throw Error(option + " '" + text + "': per-axis models are \"x: TERMS; y: TERMS; z: TERMS\" "
                  "(labels x, y, z or groups such as xy); '" + part + "' has no axis label");
    const NoiseTerms t = parse_noise_terms(trim(part.substr(part.find(':') + 1)), sensor);
    for (char axis : label) {
      const auto i = static_cast<std::size_t>(axis - 'x');
      if (seen[i])
        throw Error(option + " '" + text + "': axis " + std::string(1, axis) + " is given twice");
      seen[i] = true;
      axes[i] = t;
    }
  }
  return axes;
}

/// The sensor (0 gyro, 1 accel) whose output a unit of dimension `d` measures for `kind`, or -1.
int sensor_of_unit(const Dimension& d, OutputKind kind) {
  const bool inc = kind == OutputKind::increment;
  if (d == (inc ? dim::angle : dim::angular_rate)) return 0;
  if (d == (inc ? dim::velocity : dim::acceleration)) return 1;
  return -1;
}

/// "--out-unit deg/h, mg": each unit goes to the sensor its dimension belongs to (for the
/// output kind); a unit that fits no simulated sensor, or two units for one sensor, is an Error.
void apply_out_units(SimulationConfig& c, const std::string& text) {
  if (text.empty()) return;
  if (c.kind == OutputKind::counts)
    throw Error("--out-unit does not apply to --kind counts (values are integer counts; the LSB "
                "is --gyro-lsb / --accel-lsb)");
  const bool inc = c.kind == OutputKind::increment;
  std::array<bool, 2> seen{};
  for (const auto& item : split_list(text, "--out-unit")) {
    const Unit u = parse_unit(item);
    const int sensor = sensor_of_unit(u.dimension, c.kind);
    const bool present = sensor == 0 ? c.gyro.has_value() : sensor == 1 && c.accel.has_value();
    if (!present)
      throw Error("--out-unit '" + item + "' (" + to_string(u.dimension) + ") fits no simulated " +
                  "sensor of kind " + std::string(to_string(c.kind)) + ": expected " +
                  (inc ? "an angle (gyro, e.g. deg) or a velocity (accel, e.g. m/s)"
                       : "an angular rate (gyro, e.g. deg/s) or an acceleration (accel, e.g. mg)"));
    if (seen[static_cast<std::size_t>(sensor)])
      throw Error("--out-unit '" + text + "': two units for the " + (sensor == 0 ? "gyro" : "accel"));
    seen[static_cast<std::size_t>(sensor)] = true;
    (sensor == 0 ? c.gyro_unit : c.accel_unit) = OutputUnit{item, u.factor};
  }
}

/// "v1, v2, ..." of `count` ratios (%, ppm or plain numbers).
std::vector<double> ratios(const std::string& text, std::size_t count, const std::string& option) {
  const auto parts = split_list(text, option);
  if (parts.size() != count)
    throw Error(option + " '" + text + "': expected " + std::to_string(count) +
                " comma-separated values (e.g. 0.1 %, 500 ppm)");
  std::vector<double> v;
  for (const auto& p : parts) v.push_back(parse_quantity_as(p, dim::dimensionless, option));
  return v;
}

/// "20 degC @ 0 s, 40 degC @ 10 min": temperature points of a piecewise-linear profile.
TemperatureProfile temperature_profile(const std::string& text) {
  TemperatureProfile profile;
  for (const auto& item : split_list(text, "--temperature")) {
    const auto at = item.find('@');
    if (at == std::string::npos)
      throw Error("--temperature '" + item + "': expected TEMPERATURE @ TIME, e.g. \"20 degC @ 0 s\"");
    const Quantity t = parse_quantity(item.substr(0, at));
    if (!(t.dimension == dim::temperature))
      throw Error("--temperature '" + item + "': expected a temperature before '@'");
    profile.points.push_back(
        {parse_quantity_as(item.substr(at + 1), dim::time, "--temperature"), t.value_si});
  }
  return profile;
}

void apply_error_model(ErrorModel& m, const std::string& scale, const std::string& misalignment,
                       const std::string& temp_coef, const Dimension& coef_dim, const char* what) {
  const std::string w(what);
  if (!scale.empty()) {
    const auto v = ratios(scale, 3, "--" + w + "-scale");
    m.scale_factor = Eigen::Vector3d(v[0], v[1], v[2]);
  }
  if (!misalignment.empty()) {
    // m_xy, m_xz, m_yx, m_yz, m_zx, m_zy
    const auto v = ratios(misalignment, 6, "--" + w + "-misalignment");
    m.misalignment << 0, v[0], v[1], v[2], 0, v[3], v[4], v[5], 0;
  }
  if (!temp_coef.empty()) {
    const auto parts = split_list(temp_coef, "--" + w + "-temp-coef");
    if (parts.size() != 3)
      throw Error("--" + w + "-temp-coef: expected three values x,y,z, e.g. \"0.01 deg/s/K\"");
    Dimension d = coef_dim;
    d.temperature2 -= 2;
    for (int i = 0; i < 3; ++i)
      m.temperature_coefficient[i] =
          parse_quantity_as(parts[static_cast<std::size_t>(i)], d, "--" + w + "-temp-coef");
  }
}

/// A plain number is taken in `default_unit`; otherwise the text is a quantity with its unit.
double quantity_or_number(const std::string& text, const Dimension& d, const std::string& option,
                          const char* default_unit) {
  double v = 0;
  const auto* end = text.data() + text.size();
  const auto r = std::from_chars(text.data(), end, v);
  if (r.ec == std::errc() && r.ptr == end) return v * parse_unit(default_unit).factor;
  return parse_quantity_as(text, d, option);
}

Eigen::Vector3d triple(const std::string& text, const Dimension& d, const std::string& option) {
  const auto parts = split_list(text, option);
  if (parts.size() != 3)
    throw Error(option + " '" + text + "': expected three comma-separated values x,y,z with units");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v[i] = parse_quantity_as(parts[static_cast<std::size_t>(i)], d, option);
  return v;
}

void run_simulate(const SimulateArguments& a) {
  SimulationConfig c;
  c.rate_hz = a.rate_hz;
  checked_rate_hz(a.rate_hz, "--rate");
  StaticPose pose;
  pose.latitude_rad = parse_quantity_as(a.latitude, dim::angle, "--latitude");
  if (a.positions > 0) {
    c.schedule = calibration_schedule(
        a.positions, quantity_or_number(a.dwell, dim::time, "--dwell", "s"),
        parse_quantity_as(a.rotation_rate, dim::angular_rate, "--rotation-rate"), pose.latitude_rad);
  } else if (a.positions < 0) {
    throw Error("--positions must be >= 1");
  }
  if (a.duration.empty() && !c.schedule)
    throw Error("--duration is required (or --positions, whose schedule sets it)");
  const double duration_s = a.duration.empty()
                                ? schedule_duration_s(*c.schedule)
                                : quantity_or_number(a.duration, dim::time, "--duration", "s");
  if (!(duration_s > 0)) throw Error("--duration must be > 0");
  const double samples = std::floor(duration_s * a.rate_hz + 0.5);
  if (!(samples >= 1) || samples > 9.0e15)
    throw Error("--duration x --rate must give between 1 and 9e15 samples");
  c.samples = static_cast<std::int64_t>(samples);
  c.seed = a.seed;
  c.kind = parse_output_kind(a.kind);
  c.flicker_max_taps = a.flicker_taps;
  c.threads = a.threads;
  pose.roll_rad = parse_quantity_as(a.roll, dim::angle, "--roll");
  pose.pitch_rad = parse_quantity_as(a.pitch, dim::angle, "--pitch");
  pose.yaw_rad = parse_quantity_as(a.yaw, dim::angle, "--yaw");
  c.truth = static_truth(pose);
  if (!a.temperature.empty()) c.temperature_profile = temperature_profile(a.temperature);
  if (a.scale && a.spec.empty())
    throw Error("--scale scales a data sheet's noise terms: give --spec (the values of --model / "
                "--accel-model are typed as wanted)");
  if (a.scale) check_sheet_noise_scale(*a.scale);
  std::optional<DataSheet> sheet;
  if (!a.spec.empty()) sheet = load_data_sheet(find_data_sheet(a.spec, resource_dir("specs")));
  // A sensor's noise: --model / --accel-model when given (it replaces the sheet's terms for that
  // sensor), else the data sheet's nominal terms (typ, else max) read with the chosen density
  // convention, each x --scale when given (as the demo does); a sheet that gives a requested
  // sensor no noise at all is refused, and one that gives it no white noise is warned about
  // (simulate_spec.hpp). Without either: no noise.
  bool sheet_terms_used = false;
  const auto noise_of = [&](Sensor sensor, const std::string& model, const char* option,
                            std::optional<NoiseSource>& source) -> std::array<NoiseTerms, 3> {
    if (!model.empty()) {
      if (sheet) source = NoiseSource{option, {}, {}};
      return axis_models(model, sensor, option);
    }
    if (!sheet) return {};
    SheetNoise noise =
        simulation_noise_from_data_sheet(*sheet, sensor, parse_density_convention(a.convention));
    if (const std::string warning = sheet_noise_warning(*sheet, sensor, noise); !warning.empty())
      std::cerr << warning << "\n";
    if (a.scale) scale_sheet_noise(noise, *a.scale);
    source = NoiseSource{sheet_noise_origin(*sheet, a.scale), noise.read, noise.left_out};
    sheet_terms_used = true;
    return noise.axes;
  };
  for (const auto& s : split_list(a.sensors, "--sensors")) {
    if (s == "gyro") {
      ErrorModel m;
      m.noise = noise_of(Sensor::gyro, a.gyro_model, "--model", c.gyro_noise_source);
      if (!a.gyro_bias.empty()) m.bias = triple(a.gyro_bias, dim::angular_rate, "--gyro-bias");
      apply_error_model(m, a.gyro_scale, a.gyro_misalignment, a.gyro_temp_coef, dim::angular_rate,
                        "gyro");
      c.gyro = m;
    } else if (s == "accel") {
      ErrorModel m;
      m.noise = noise_of(Sensor::accel, a.accel_model, "--accel-model", c.accel_noise_source);
      if (!a.accel_bias.empty()) m.bias = triple(a.accel_bias, dim::acceleration, "--accel-bias");
      apply_error_model(m, a.accel_scale, a.accel_misalignment, a.accel_temp_coef,
                        dim::acceleration, "accel");
      c.accel = m;
    } else {
      throw Error("--sensors: unknown sensor '" + s + "'; expected gyro and/or accel");
    }
  }
  if (!a.gyro_model.empty() && !c.gyro) throw Error("--model is given but --sensors has no gyro");
  if (a.scale && !sheet_terms_used)
    throw Error("--scale has nothing to scale: --model / --accel-model replace the sheet's terms "
                "of every simulated sensor");
  if (!a.accel_model.empty() && !c.accel)
    throw Error("--accel-model is given but --sensors has no accel");
  if (c.kind == OutputKind::counts) {
    const auto counts = [](const std::string& lsb, const std::string& fs, const Dimension& d,
                           const char* what) {
      if (lsb.empty() || fs.empty())
        throw Error(std::string("--kind counts needs --") + what + "-lsb and --" + what +
                    "-full-scale");
      return CountsFormat{parse_quantity_as(lsb, d, std::string("--") + what + "-lsb"),
                          parse_quantity_as(fs, d, std::string("--") + what + "-full-scale")};
    };
    if (c.gyro) c.gyro_counts = counts(a.gyro_lsb, a.gyro_full_scale, dim::angular_rate, "gyro");
    if (c.accel)
      c.accel_counts = counts(a.accel_lsb, a.accel_full_scale, dim::acceleration, "accel");
  }
  apply_out_units(c, a.out_unit);
  if (!a.gyro_quantizer.empty()) {
    if (!c.gyro) throw Error("--gyro-quantizer is given but --sensors has no gyro");
    c.gyro_quantizer_step = parse_quantity_as(a.gyro_quantizer, dim::angle, "--gyro-quantizer");
  }
  if (!a.accel_quantizer.empty()) {
    if (!c.accel) throw Error("--accel-quantizer is given but --sensors has no accel");
    c.accel_quantizer_step =
        parse_quantity_as(a.accel_quantizer, dim::velocity, "--accel-quantizer");
  }
  if (!a.truth_file.empty()) {
    if (c.schedule) throw Error("give either --truth or --positions, not both");
    // --truth-unit "deg/s, g": each unit to the sensor of its dimension (rate units).
    double gyro_factor = 1, accel_factor = 1;
    if (!a.truth_unit.empty())
      for (const auto& item : split_list(a.truth_unit, "--truth-unit")) {
        const Unit u = parse_unit(item);
        const int sensor = sensor_of_unit(u.dimension, OutputKind::rate);
        if (sensor < 0)
          throw Error("--truth-unit '" + item + "' (" + to_string(u.dimension) +
                      "): expected an angular rate (gx..gz, e.g. deg/s) or an acceleration "
                      "(ax..az, e.g. g)");
        (sensor == 0 ? gyro_factor : accel_factor) = u.factor;
      }
    c.truth_series = std::make_shared<const TruthSeries>(read_truth_csv(
        a.truth_file, c.gyro.has_value(), c.accel.has_value(), gyro_factor, accel_factor));
  } else if (!a.truth_unit.empty()) {
    throw Error("--truth-unit is given without --truth");
  }
  const SampleFormat format = parse_sample_format(a.format);
  validate(c);
  for (const auto& warning : simulation_warnings(c)) std::cerr << "warning: " << warning << "\n";
  const bool tty = stderr_is_tty();
  std::optional<std::filesystem::path> sidecar;
  if (a.sidecar == "none") {
    sidecar = std::filesystem::path();
  } else if (!a.sidecar.empty()) {
    sidecar = std::filesystem::path(a.sidecar);
  }
  write_simulation(
      c, a.output, format, a.force,
      [tty](std::int64_t done, std::int64_t total) {
        if (tty) std::cerr << "\rsimulate: " << (100 * done / total) << "%" << std::flush;
      },
      sidecar);
  if (tty) std::cerr << "\n";
  // With -o /dev/stdout the log itself is on stdout: the line goes to stderr then.
  (is_stream_output(a.output) ? std::cerr : std::cout) << "wrote " << a.output << " (" << c.samples << " samples at " << c.rate_hz
            << " Hz, kind " << to_string(c.kind) << ")"
            << (!sidecar ? " and " + a.output + ".json"
                         : sidecar->empty() ? std::string(" without its truth (--sidecar none)")
                                            : " and " + sidecar->string())
            << "\n";
}

}  // namespace

void add_simulate_command(CLI::App& app) {
  auto args = std::make_shared<SimulateArguments>();
  CLI::App* command = app.add_subcommand(
      "simulate", "Synthetic IMU log from a noise model, with its exact truth and theoretical "
                  "AVAR in FILE.json");
  command->add_option("--model", args->gyro_model,
                      "gyro noise, the same on every axis, e.g. \"N=0.15 deg/sqrt(h), B=3 deg/h, "
                      "K=0.02 deg/h/sqrt(h)\" (keys Q N B K R, GM=<sigma> @ <tau>, "
                      "SIN=<amplitude> @ <frequency>), or per axis \"xy: N=0.15 deg/sqrt(h); "
                      "z: N=0.2 deg/sqrt(h), B=5 deg/h\" (labels x, y, z or groups; an axis not "
                      "named has no noise)");
  command->add_option("--spec", args->spec,
                      "simulate the noise terms of a data sheet (file or name in specs/); "
                      "--model / --accel-model replace its terms for that sensor; a sensor the "
                      "sheet gives no noise term is refused, one without white noise warned about; "
                      "--scale scales them");
  command->add_option("--scale", args->scale,
                      "with --spec: the sheet's noise terms x this factor (of its typical values, "
                      "or the maximum where no typical is printed), e.g. 0.8 for a unit a little "
                      "better than nominal, as `demo --scale`; not applied to --model / "
                      "--accel-model; recorded in FILE.json's noise_source");
  command->add_option("--density-convention", args->convention,
                      "how --spec's noise density is read: two-sided (N = ND) or one-sided")
      ->capture_default_str();
  command->add_option("--accel-model", args->accel_model,
                      "accelerometer noise, e.g. \"N=60 ug/sqrt(Hz), B=0.05 mg\" (per axis as "
                      "--model: \"x: ...; y: ...; z: ...\")");
  command->add_option("--rate", args->rate_hz, "sample rate [Hz]")->required();
  command->add_option("--duration", args->duration,
                      "log length, e.g. 2h, \"600 s\" (number: s); default with --positions: the "
                      "schedule's length");
  command->add_option("--positions", args->positions,
                      "multi-position schedule of N well-spread orientations (calibration)");
  command->add_option("--dwell", args->dwell, "time in each position")->capture_default_str();
  command->add_option("--rotation-rate", args->rotation_rate, "peak rate of the rotations")
      ->capture_default_str();
  command->add_option("--temperature", args->temperature,
                      "temperature profile, e.g. \"20 degC @ 0 s, 40 degC @ 10 min\" (linear in "
                      "between; adds a temp column in K)");
  command->add_option("--gyro-scale", args->gyro_scale, "gyro scale factor errors x,y,z, e.g. "
                                                        "\"0.2 %,-0.1 %,500 ppm\"");
  command->add_option("--accel-scale", args->accel_scale, "accelerometer scale factor errors x,y,z");
  command->add_option("--gyro-misalignment", args->gyro_misalignment,
                      "gyro cross-axis terms m_xy,m_xz,m_yx,m_yz,m_zx,m_zy");
  command->add_option("--accel-misalignment", args->accel_misalignment,
                      "accelerometer cross-axis terms m_xy,m_xz,m_yx,m_yz,m_zx,m_zy");
  command->add_option("--gyro-temp-coef", args->gyro_temp_coef,
                      "gyro bias temperature coefficients x,y,z, e.g. \"0.01 deg/s/K\"");
  command->add_option("--accel-temp-coef", args->accel_temp_coef,
                      "accelerometer bias temperature coefficients x,y,z, e.g. \"0.2 mg/K\"");
  command->add_option("--out-unit", args->out_unit,
                      "units of the written values, one per sensor, told apart by dimension, e.g. "
                      "\"deg/h\" or \"deg/s, mg\" (increments: \"deg, mm/s\"); default SI (rad/s, "
                      "m/s^2; rad, m/s); not with --kind counts");
  command->add_option("--gyro-quantizer", args->gyro_quantizer,
                      "a real quantizer: the integrated gyro output (angle) is rounded to "
                      "multiples of this step, the residual carried, e.g. \"0.0001 deg\"");
  command->add_option("--accel-quantizer", args->accel_quantizer,
                      "a real quantizer of the integrated accel output (velocity), e.g. "
                      "\"0.1 mm/s\"");
  command->add_option("--truth", args->truth_file,
                      "true signal from a CSV with columns t [s] and gx,gy,gz and/or ax,ay,az "
                      "(those of --sensors), linear between rows, held outside; replaces the "
                      "static pose; the error model and noise are applied to it");
  command->add_option("--truth-unit", args->truth_unit,
                      "units of --truth's columns, e.g. \"deg/s, g\" (default rad/s, m/s^2)");
  command->add_option("--seed", args->seed, "random seed")->capture_default_str();
  command->add_option("--sensors", args->sensors, "gyro, accel or gyro,accel")
      ->capture_default_str();
  command->add_option("--kind", args->kind, "rate | increment | counts")->capture_default_str();
  command->add_option("--format", args->format,
                      "csv | f32 | f64 | i16 | i32 (binary: little-endian rows of the channels, "
                      "no time column; i16 / i32 with --kind counts only); FILE.json says how to "
                      "read it back")
      ->capture_default_str();
  command->add_option("-o,--output", args->output, "output FILE (and FILE.json)")->required();
  command->add_option("--sidecar", args->sidecar,
                      "where the truth JSON goes (default FILE.json; needed when -o is a device "
                      "or pipe such as /dev/stdout; none: no truth written)");
  command->add_flag("--force", args->force, "overwrite existing files");
  command->add_option("--roll", args->roll, "roll of the sensor frame, e.g. \"10 deg\"")
      ->capture_default_str();
  command->add_option("--pitch", args->pitch, "pitch")->capture_default_str();
  command->add_option("--yaw", args->yaw, "yaw (heading)")->capture_default_str();
  command->add_option("--latitude", args->latitude, "latitude (Earth rate, gravity)")
      ->capture_default_str();
  command->add_option("--gyro-bias", args->gyro_bias, "constant gyro bias x,y,z, e.g. "
                                                      "\"1 deg/h,0 deg/h,-2 deg/h\"");
  command->add_option("--accel-bias", args->accel_bias, "constant accel bias x,y,z");
  command->add_option("--gyro-lsb", args->gyro_lsb, "counts: gyro rate per LSB, e.g. "
                                                    "\"0.01 deg/s\"");
  command->add_option("--gyro-full-scale", args->gyro_full_scale, "counts: gyro saturation");
  command->add_option("--accel-lsb", args->accel_lsb, "counts: accel per LSB, e.g. \"0.1 mg\"");
  command->add_option("--accel-full-scale", args->accel_full_scale, "counts: accel saturation");
  command->add_option("--flicker-taps", args->flicker_taps,
                      "longest flicker filter (power of two); flicker is flat for tau up to "
                      "taps/4 samples")
      ->capture_default_str();
  command->add_option("--threads", args->threads, "worker threads (results do not depend on it)")
      ->capture_default_str();
  command->callback([args] { run_simulate(*args); });
}

}  // namespace sigmatau::cli
