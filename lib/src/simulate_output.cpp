// Simulated logs to files (csv, f32, f64) with their sidecar JSON, written atomically.

#include <nlohmann/json.hpp>

#include <bit>
#include <charconv>
#include <cmath>
#include <future>
#include <limits>
#include <tuple>
#include <utility>

#include "json_text.hpp"
#include "sigmatau/display_units.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/output_file.hpp"
#include "sigmatau/simulate.hpp"
#include "simulate_quantizer.hpp"

namespace sigmatau {
namespace {

/// Rows per write: 16 Ki rows x 6 channels x 8 bytes = 768 KiB of samples per block.
constexpr std::int64_t kRowsPerWrite = std::int64_t{1} << 14;

nlohmann::json vector_json(const Eigen::Vector3d& v) { return {v[0], v[1], v[2]}; }

nlohmann::json terms_json(const NoiseTerms& t) {
  nlohmann::json j = nlohmann::json::object();
  if (t.quantization) j["quantization"] = *t.quantization;
  if (t.white) j["white"] = *t.white;
  if (t.bias_instability) j["bias_instability"] = *t.bias_instability;
  if (t.rate_random_walk) j["rate_random_walk"] = *t.rate_random_walk;
  if (t.rate_ramp) j["rate_ramp"] = *t.rate_ramp;
  if (!t.gauss_markov.empty()) {  // a list: one object per Gauss-Markov entry, in order
    nlohmann::json list = nlohmann::json::array();
    for (const GaussMarkov& gm : t.gauss_markov)
      list.push_back({{"sigma", gm.sigma}, {"tau_c_s", gm.tau_c_s}});
    j["gauss_markov"] = list;
  }
  if (t.sinusoid)
    j["sinusoid"] = {{"amplitude", t.sinusoid->amplitude},
                     {"frequency_hz", t.sinusoid->frequency_hz},
                     {"phase_rad", t.sinusoid->phase_rad}};
  return j;
}

nlohmann::json model_json(const ErrorModel& m, Sensor sensor, const Eigen::Vector3d& truth,
                          double temperature_k) {
  nlohmann::json j;
  // The rate is the sample unit; the terms' units are si_unit's (display_units.hpp).
  j["units"] = {{"rate", sensor == Sensor::gyro ? "rad/s" : "m/s^2"}};
  for (const NoiseTerm term : {NoiseTerm::quantization, NoiseTerm::white,
                               NoiseTerm::bias_instability, NoiseTerm::rate_random_walk,
                               NoiseTerm::rate_ramp}) {
    j["units"][std::string(to_string(term))] = std::string(si_unit(term, sensor));
  }
  j["truth"] = vector_json(truth);
  j["scale_factor"] = vector_json(m.scale_factor);
  j["misalignment"] = {vector_json(m.misalignment.row(0).transpose()),
                       vector_json(m.misalignment.row(1).transpose()),
                       vector_json(m.misalignment.row(2).transpose())};
  j["bias"] = vector_json(m.bias);
  j["temperature_coefficient"] = vector_json(m.temperature_coefficient);
  j["reference_temperature_k"] = m.reference_temperature_k;
  j["expected_mean"] = vector_json(m.deterministic_output(truth, temperature_k));
  j["noise"] = {terms_json(m.noise[0]), terms_json(m.noise[1]), terms_json(m.noise[2])};
  return j;
}

void append_number(std::string& s, double v) {
  char buffer[32];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, v);
  s.append(buffer, r.ptr);
}

}  // namespace

SampleFormat parse_sample_format(std::string_view text) {
  if (text == "csv") return SampleFormat::csv;
  if (text == "f32") return SampleFormat::f32;
  if (text == "f64") return SampleFormat::f64;
  if (text == "i16") return SampleFormat::i16;
  if (text == "i32") return SampleFormat::i32;
  throw Error("unknown format '" + std::string(text) + "'; expected csv, f32, f64, i16 or i32");
}

std::string_view to_string(SampleFormat format) {
  switch (format) {
    case SampleFormat::csv: return "csv";
    case SampleFormat::f32: return "f32";
    case SampleFormat::f64: return "f64";
    case SampleFormat::i16: return "i16";
    case SampleFormat::i32: return "i32";
  }
  return "?";
}

void check_sample_format(const SimulationConfig& c, SampleFormat format) {
  if (format != SampleFormat::i16 && format != SampleFormat::i32) return;
  const std::string name(to_string(format));
  if (c.kind != OutputKind::counts)
    throw Error("format " + name + " writes integers: it needs --kind counts (with --gyro-lsb / "
                "--accel-lsb); use f32 or f64 for kind " + std::string(to_string(c.kind)));
  if (c.temperature_profile)
    throw Error("format " + name + " cannot hold the temperature channel (K, not counts); use "
                "f32, f64 or csv with a temperature profile");
  const long long limit = format == SampleFormat::i16 ? std::numeric_limits<std::int16_t>::max()
                                                     : std::numeric_limits<std::int32_t>::max();
  for (const auto& [present, counts, sensor] :
       {std::tuple{c.gyro.has_value(), c.gyro_counts, "gyro"},
        std::tuple{c.accel.has_value(), c.accel_counts, "accel"}}) {
    if (!present) continue;
    const double full_scale_lsb = std::floor(counts.full_scale / counts.lsb);
    if (!(full_scale_lsb <= static_cast<double>(limit)))
      throw Error(std::string("format ") + name + ": the " + sensor + " full scale is " +
                  std::to_string(static_cast<long long>(std::min(full_scale_lsb, 9.0e18))) +
                  " LSB, more than " + std::to_string(limit) + "; use " +
                  (format == SampleFormat::i16 ? "i32" : "f64") + " or a larger LSB");
  }
}

std::string simulation_sidecar_json(const SimulationConfig& c, SampleFormat format) {
  validate(c);
  check_sample_format(c, format);
  nlohmann::json j;
  j["format"] = "sigmatau-simulation";
  j["schema_version"] = 1;
  j["seed"] = c.seed;
  j["rate_hz"] = c.rate_hz;
  j["samples"] = c.samples;
  j["duration_s"] = static_cast<double>(c.samples) / c.rate_hz;
  j["kind"] = std::string(to_string(c.kind));
  j["temperature_k"] = c.temperature_k;
  std::vector<std::string> columns{"t"};
  if (c.gyro) {
    j["gyro"] = model_json(*c.gyro, Sensor::gyro, c.truth.angular_rate, c.temperature_k);
    for (const char* n : {"gx", "gy", "gz"}) columns.emplace_back(n);
  }
  if (c.accel) {
    j["accel"] = model_json(*c.accel, Sensor::accel, c.truth.specific_force, c.temperature_k);
    for (const char* n : {"ax", "ay", "az"}) columns.emplace_back(n);
  }
  if (c.temperature_profile) {
    columns.emplace_back("temp");
    nlohmann::json points = nlohmann::json::array();
    for (const auto& q : c.temperature_profile->points)
      points.push_back({{"t_s", q.t_s}, {"temperature_k", q.temperature_k}});
    j["temperature_profile"] = {{"unit", "K"}, {"interpolation", "linear, constant outside"},
                                {"points", points}};
  }
  if (c.schedule) {
    // The truth of each static position, its time span and the expected noise-free output at the
    // profile's temperature at the middle of the dwell.
    nlohmann::json positions = nlohmann::json::array();
    for (const auto& seg : schedule_timeline(*c.schedule)) {
      const double mid = (seg.start_s + seg.end_s) / 2;
      const Truth x = schedule_truth(*c.schedule, mid);
      const auto& p = c.schedule->positions[static_cast<std::size_t>(seg.position)];
      nlohmann::json e{{"start_s", seg.start_s}, {"end_s", seg.end_s},
                       {"rotating", seg.rotating}, {"position", seg.position}};
      if (!seg.rotating) {
        const double temp = c.temperature_profile ? temperature_at(*c.temperature_profile, mid)
                                                  : c.temperature_k;
        e["roll_rad"] = p.roll_rad;
        e["pitch_rad"] = p.pitch_rad;
        e["yaw_rad"] = p.yaw_rad;
        e["angular_rate"] = vector_json(x.angular_rate);
        e["specific_force"] = vector_json(x.specific_force);
        if (c.gyro) e["gyro_expected_mean"] = vector_json(c.gyro->deterministic_output(x.angular_rate, temp));
        if (c.accel)
          e["accel_expected_mean"] = vector_json(c.accel->deterministic_output(x.specific_force, temp));
      }
      positions.push_back(e);
    }
    j["schedule"] = {{"rotation_rate_rad_s", c.schedule->rotation_rate_rad_s},
                     {"latitude_rad", c.schedule->latitude_rad},
                     {"rotation_profile", "cycloidal about the shortest-rotation body axis"},
                     {"duration_s", schedule_duration_s(*c.schedule)},
                     {"segments", positions}};
  }
  if (c.truth_series) {
    // The series itself is the truth (the "truth" and "expected_mean" above are for the static
    // pose and do not apply): where it came from, its span and how it is evaluated.
    const TruthSeries& x = *c.truth_series;
    j["truth_series"] = {{"source", x.source},
                         {"rows", x.t_s.size()},
                         {"t_first_s", x.t_s.front()},
                         {"t_last_s", x.t_s.back()},
                         {"units", {{"angular_rate", "rad/s"}, {"specific_force", "m/s^2"}}},
                         {"interpolation", "linear in time, held constant outside; increment "
                                           "output integrates it exactly"}};
    for (const char* sensor : {"gyro", "accel"})
      if (j.contains(sensor)) {
        j[sensor].erase("truth");
        j[sensor].erase("expected_mean");
      }
  }
  // The data file as written: csv has the time column first; f32 / f64 hold only the channels
  // (little-endian rows), so the reader needs their count and the rate.
  const bool binary = format != SampleFormat::csv;
  if (binary) columns.erase(columns.begin());
  j["columns"] = columns;
  {
    const std::string kind_option =
        c.kind == OutputKind::increment ? " --kind increment" : std::string();
    nlohmann::json file{{"format", std::string(to_string(format))},
                        {"rows", c.samples},
                        {"channels", columns.size()}};
    std::string rate_text;
    append_number(rate_text, c.rate_hz);
    if (binary) {
      const int bytes = format == SampleFormat::i16                                   ? 2
                        : format == SampleFormat::f32 || format == SampleFormat::i32 ? 4
                                                                                      : 8;
      const char* type = format == SampleFormat::i16   ? "two's-complement int16"
                         : format == SampleFormat::i32 ? "two's-complement int32"
                         : format == SampleFormat::f32 ? "IEEE-754 float32"
                                                       : "IEEE-754 float64";
      file["layout"] = std::string("little-endian ") + type +
                       ", one row of the columns per sample, no header and no time column";
      file["bytes"] = static_cast<std::int64_t>(bytes) * c.samples *
                      static_cast<std::int64_t>(columns.size());
      file["time"] = "sample k (0-based) is at t = " +
                     std::string(c.kind == OutputKind::increment ? "(k + 1)" : "k") + " / rate_hz s";
      file["read_with"] = "--binary " + std::string(to_string(format)) + " --channels " +
                          std::to_string(columns.size()) + " --rate " + rate_text + kind_option;
    } else {
      file["layout"] = "text, header line then one row per sample; t in s";
      file["read_with"] = "--time-column t" + kind_option;
    }
    j["file"] = file;
  }
  // Units of the written values (the sidecar's parameters and theory stay SI).
  nlohmann::json units;
  const bool inc = c.kind == OutputKind::increment;
  const auto unit_name = [&](const OutputUnit& u, const char* rate, const char* integrated) {
    return c.kind == OutputKind::counts ? std::string("counts")
           : !u.name.empty()            ? u.name
                                        : std::string(inc ? integrated : rate);
  };
  if (c.gyro) units["gyro"] = unit_name(c.gyro_unit, "rad/s", "rad");
  if (c.accel) units["accel"] = unit_name(c.accel_unit, "m/s^2", "m/s");
  if (c.temperature_profile) units["temp"] = "K";
  j["output_units"] = units;
  for (const auto& [source, sensor] : {std::pair{&c.gyro_noise_source, "gyro"},
                                        std::pair{&c.accel_noise_source, "accel"}})
    if (*source && j.contains(sensor))
      j[sensor]["noise_source"] = {{"origin", (*source)->origin},
                                   {"read", (*source)->read},
                                   {"left_out", (*source)->left_out}};
  if (c.gyro && c.gyro_quantizer_step > 0) j["gyro"]["quantizer_step"] = c.gyro_quantizer_step;
  if (c.accel && c.accel_quantizer_step > 0) j["accel"]["quantizer_step"] = c.accel_quantizer_step;
  if (c.kind == OutputKind::counts) {
    if (c.gyro) j["gyro"]["counts"] = {{"lsb", c.gyro_counts.lsb}, {"full_scale", c.gyro_counts.full_scale}};
    if (c.accel)
      j["accel"]["counts"] = {{"lsb", c.accel_counts.lsb}, {"full_scale", c.accel_counts.full_scale}};
  }
  const Sampling sampling = sampling_of(c);
  bool any_flicker = false;
  for (const auto* model : {c.gyro ? &*c.gyro : nullptr, c.accel ? &*c.accel : nullptr})
    if (model)
      for (const auto& t : model->noise) any_flicker = any_flicker || t.bias_instability;
  if (any_flicker) {
    const FlickerBand band = flicker_band(sampling.flicker_taps);
    j["flicker"] = {{"method", "Kasdin fractional integration, exact FIR by FFT overlap-save"},
                    {"taps", sampling.flicker_taps},
                    {"flat_band_tau_s",
                     {static_cast<double>(band.m_low) * sampling.tau0_s,
                      static_cast<double>(band.m_high) * sampling.tau0_s}}};
  }
  // Theoretical AVAR at octave taus, up to Stable32's OADEV stop ratio (m <= (N-1)/4) where N =
  // samples + 1 phase points.
  std::vector<double> taus;
  std::vector<std::int64_t> ms;
  for (std::int64_t m = 1; 4 * m <= c.samples; m *= 2) {
    ms.push_back(m);
    taus.push_back(static_cast<double>(m) * sampling.tau0_s);
  }
  nlohmann::json theory;
  theory["statistic"] = "avar (overlapping), exact for the sampled process, in rate unit^2";
  theory["tau_s"] = taus;
  theory["note"] =
      c.kind == OutputKind::counts
          ? "the counts' LSB rounding is not included (with enough other noise it adds white "
            "noise of variance LSB^2/12 per sample)"
          : "";
  // The flicker AVAR per unit B^2 costs O(taps + m) per factor: computed once per factor, not
  // once per channel.
  std::vector<double> flicker_unit;
  if (any_flicker)
    for (std::int64_t m : ms) flicker_unit.push_back(flicker_avar_per_unit(m, sampling.flicker_taps));
  bool quantizer_exact = false, quantizer_additive = false;
  const auto curves = [&](const ErrorModel& model, const char* prefix, double quantizer_step,
                          const Eigen::Vector3d& truth) {
    const Eigen::Vector3d drift = model.deterministic_output(truth, c.temperature_k);
    for (int axis = 0; axis < 3; ++axis) {
      const NoiseTerms& terms = model.noise[static_cast<std::size_t>(axis)];
      const bool exact = quantizer_step > 0 && detail::real_quantizer_exact(c, terms);
      quantizer_exact = quantizer_exact || exact;
      quantizer_additive = quantizer_additive || (quantizer_step > 0 && !exact);
      std::vector<double> avar;
      for (std::size_t i = 0; i < ms.size(); ++i) {
        double total = 0;
        for (NoiseTerm term : kAllNoiseTerms)
          if (term != NoiseTerm::bias_instability) total += sampled_avar(terms, term, ms[i], sampling);
        if (terms.bias_instability)
          total += *terms.bias_instability * *terms.bias_instability * flicker_unit[i];
        if (exact) {
          total += detail::real_quantizer_avar(quantizer_step, ms[i], sampling.tau0_s, terms,
                                               drift[axis], sampling.flicker_taps);
        } else if (quantizer_step > 0) {  // additive equivalent Q = step / sqrt(12): 3 Q^2 / tau^2
          const double tau = static_cast<double>(ms[i]) * sampling.tau0_s;
          total += quantizer_step * quantizer_step / (4 * tau * tau);
        }
        avar.push_back(total);
      }
      theory["avar"][std::string(prefix) + "xyz"[axis]] = avar;
    }
  };
  if (c.gyro) curves(*c.gyro, "g", c.gyro_quantizer_step, c.truth.angular_rate);
  if (c.accel) curves(*c.accel, "a", c.accel_quantizer_step, c.truth.specific_force);
  if (quantizer_exact || quantizer_additive) {
    std::string text;
    if (quantizer_exact)
      text = "the real quantizer's AVAR is exact for the channels whose noise is white, "
             "additive Q, Gauss-Markov and flicker with a constant truth (rounding error of the "
             "integrated output as a sawtooth, averaged over a uniform start phase; "
             "lib/src/simulate_quantizer.hpp); it equals 3 Q^2/tau^2, Q = step/sqrt(12), only "
             "when the noise moves the output over several steps per sample";
    if (quantizer_additive)
      text += std::string(text.empty() ? "" : ". ") +
              "on the other channels the real quantizer is included as its additive equivalent "
              "3 Q^2/tau^2, Q = step/sqrt(12) (within 0.6 % when the step is at most 2x the "
              "per-sample white noise; otherwise approximate, see warnings)";
    theory["quantizer"] = text;
  }
  if (const auto warnings = simulation_warnings(c); !warnings.empty()) j["warnings"] = warnings;
  j["theory"] = theory;
  return detail::json_text(j, 2) + "\n";
}

void write_simulation(const SimulationConfig& config, const std::filesystem::path& path,
                      SampleFormat format, bool overwrite,
                      const std::function<void(std::int64_t, std::int64_t)>& progress,
                      const std::optional<std::filesystem::path>& sidecar) {
  if (!sidecar && is_stream_output(path)) {
    throw Error(path.string() + " is a device or pipe, so its truth cannot go beside it as " +
                path.string() + ".json: give --sidecar FILE (or --sidecar none to write no truth)");
  }
  std::filesystem::path sidecar_path = sidecar ? *sidecar : std::filesystem::path(path.string() + ".json");
  check_can_write(path, overwrite);
  if (!sidecar_path.empty()) check_can_write(sidecar_path, overwrite);
  const std::string sidecar_text = simulation_sidecar_json(config, format);  // validates
  Simulator simulator(config);
  AtomicOutputFile file(path, overwrite);
  const int nch = simulator.channels();
  // Output scale per channel: SI value / unit factor (temperature stays in K).
  std::vector<double> inverse_factor;
  for (const auto& name : simulator.channel_names())
    inverse_factor.push_back(name[0] == 'g'   ? 1.0 / config.gyro_unit.factor
                             : name[0] == 'a' ? 1.0 / config.accel_unit.factor
                                              : 1.0);
  std::string text;
  std::vector<float> floats;
  std::vector<std::int16_t> int16s;
  std::vector<std::int32_t> int32s;
  if (format == SampleFormat::csv) {
    text = "t";
    for (const auto& n : simulator.channel_names()) text += "," + n;
    text += "\n";
    file.write(text);
  }
  static_assert(std::endian::native == std::endian::little,
                "binary output is little-endian; add byte swapping for this platform");
  // Double buffering: the simulator fills the next block on another thread while this one
  // formats and writes the current block (the simulator is only ever used by one thread at a
  // time, so the samples are the same as without the pipeline).
  std::vector<double> block(static_cast<std::size_t>(kRowsPerWrite * nch));
  std::vector<double> next_block(block.size());
  std::int64_t first = simulator.position();
  std::int64_t rows = simulator.next(block, kRowsPerWrite);
  while (rows > 0) {
    const std::int64_t next_first = simulator.position();
    auto pending = std::async(std::launch::async,
                              [&] { return simulator.next(next_block, kRowsPerWrite); });
    try {
      const auto values = static_cast<std::size_t>(rows * nch);
      for (std::size_t i = 0; i < values; ++i)
        block[i] *= inverse_factor[i % static_cast<std::size_t>(nch)];
      if (format == SampleFormat::csv) {
        text.clear();
        for (std::int64_t r = 0; r < rows; ++r) {
          append_number(text, simulator.time_s(first + r));
          for (int ch = 0; ch < nch; ++ch) {
            text += ',';
            append_number(text, block[static_cast<std::size_t>(r * nch + ch)]);
          }
          text += '\n';
        }
        file.write(text);
      } else if (format == SampleFormat::f64) {
        file.write({reinterpret_cast<const char*>(block.data()), values * sizeof(double)});
      } else if (format == SampleFormat::f32) {
        floats.assign(block.begin(), block.begin() + static_cast<std::ptrdiff_t>(values));
        file.write({reinterpret_cast<const char*>(floats.data()), values * sizeof(float)});
      } else if (format == SampleFormat::i16) {  // whole counts within +-32767 (checked)
        int16s.resize(values);
        for (std::size_t i = 0; i < values; ++i) int16s[i] = static_cast<std::int16_t>(block[i]);
        file.write({reinterpret_cast<const char*>(int16s.data()), values * sizeof(std::int16_t)});
      } else {
        int32s.resize(values);
        for (std::size_t i = 0; i < values; ++i) int32s[i] = static_cast<std::int32_t>(block[i]);
        file.write({reinterpret_cast<const char*>(int32s.data()), values * sizeof(std::int32_t)});
      }
      if (progress) progress(next_first, config.samples);
    } catch (...) {
      pending.wait();
      throw;
    }
    rows = pending.get();
    first = next_first;
    std::swap(block, next_block);
  }
  // The sidecar first: a log without its truth is worse than truth without its log.
  if (!sidecar_path.empty()) write_file_atomically(sidecar_path, sidecar_text, overwrite);
  file.commit();
}

}  // namespace sigmatau
