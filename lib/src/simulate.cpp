// The streaming simulator: per channel, the deterministic output plus each noise term present.
//
// Glossary (simulate.hpp, THEORY.md section 6): tau0 = 1/rate [s]; k sample index; chunk = the
// block of kChunk samples every channel computes at a time (a power of two, so it divides the
// flicker block L and the random sub-block size divides it); w unit normals; e centred uniforms.
#include "sigmatau/sampling_limits.hpp"
#include "sigmatau/simulate.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <thread>

#include "sigmatau/error.hpp"
#include "simulate_flicker.hpp"
#include "simulate_random.hpp"
#include "simulate_schedule.hpp"
#include "simulate_truth.hpp"

namespace sigmatau {
namespace {

constexpr double kPi = std::numbers::pi;
/// Samples per channel computed at a time (64 Ki: 512 KiB per channel buffer, a few per cache).
constexpr std::int64_t kChunk = std::int64_t{1} << 16;
/// Width of the uniform quantization error per unit Q: a uniform of width q has variance
/// q^2/12, so q = Q sqrt(12) gives variance Q^2.
const double kUniformWidthPerQ = std::sqrt(12.0);
/// Longest flicker filter accepted (2^28 taps: 2 GiB of FFT scratch per thread).
constexpr std::int64_t kMaxFlickerTaps = std::int64_t{1} << 28;
/// Stream number of the real quantizer's initial residual (after the NoiseTerm streams).
constexpr int kQuantizerStream = static_cast<int>(kAllNoiseTerms.size());
/// Stream number of Gauss-Markov entry i >= 1 is kQuantizerStream + i (after every older stream,
/// so a model with one GM, entry 0 on the NoiseTerm::gauss_markov stream, reproduces the samples
/// it gave before sums of Gauss-Markov processes existed).
int gauss_markov_stream(std::size_t index) { return kQuantizerStream + static_cast<int>(index); }
/// The sinusoid recurrence restarts from std::sin/cos every this many samples (see generate).
constexpr std::int64_t kSinusoidRestart = 1024;

bool is_power_of_two(std::int64_t v) { return v > 0 && (v & (v - 1)) == 0; }

struct Channel {
  int sensor = 0;  // 0 gyro, 1 accel, 2 temperature
  int axis = 0;
  double constant = 0;  // (I + T) x + b + c (temperature - T0) on this axis [SI rate]
  // For a time-varying truth or temperature: this axis's row of (I + T), b and c (T0).
  Eigen::RowVector3d gain = Eigen::RowVector3d::Zero();
  double bias = 0;
  double temperature_coefficient = 0;
  double reference_temperature_k = 0;
  NoiseTerms terms;
  CountsFormat counts;
  std::array<std::uint64_t, kAllNoiseTerms.size()> keys{};
  std::array<std::uint64_t, kMaxGaussMarkov> gm_keys{};  // per Gauss-Markov entry
  // Streaming state.
  double rw = 0;      // random-walk value b_{k-1}
  std::array<double, kMaxGaussMarkov> gm{};  // Gauss-Markov values g_{k-1}, per entry
  double e_prev = 0;  // quantization error e_{k-1}
  double quantizer_step = 0;      // real quantizer step [rad | m/s] (0: none)
  double quantizer_residual = 0;  // integrated output minus its quantized value [rad | m/s]
  std::vector<double> flicker;  // current flicker block pair (unit innovation)
  std::int64_t flicker_block = -1;  // its pair index
  std::vector<double> values;   // the current chunk
  std::vector<double> scratch;
};

std::uint64_t key_of(const Channel& c, NoiseTerm t) { return c.keys[static_cast<std::size_t>(t)]; }

}  // namespace

Truth static_truth(const StaticPose& p) {
  const double cr = std::cos(p.roll_rad), sr = std::sin(p.roll_rad);
  const double cp = std::cos(p.pitch_rad), sp = std::sin(p.pitch_rad);
  const double cy = std::cos(p.yaw_rad), sy = std::sin(p.yaw_rad);
  Eigen::Matrix3d rx, ry, rz;
  rx << 1, 0, 0, 0, cr, -sr, 0, sr, cr;
  ry << cp, 0, sp, 0, 1, 0, -sp, 0, cp;
  rz << cy, -sy, 0, sy, cy, 0, 0, 0, 1;
  const Eigen::Matrix3d body_to_ned = rz * ry * rx;
  const Eigen::Vector3d omega_n = earth_rate_ned(p.latitude_rad);
  const Eigen::Vector3d f_n(0, 0, -normal_gravity(p.latitude_rad));
  return {body_to_ned.transpose() * omega_n, body_to_ned.transpose() * f_n};
}

OutputKind parse_output_kind(std::string_view text) {
  if (text == "rate") return OutputKind::rate;
  if (text == "increment") return OutputKind::increment;
  if (text == "counts") return OutputKind::counts;
  throw Error("unknown output kind '" + std::string(text) + "'; expected rate, increment or counts");
}

std::string_view to_string(OutputKind kind) {
  switch (kind) {
    case OutputKind::rate: return "rate";
    case OutputKind::increment: return "increment";
    case OutputKind::counts: return "counts";
  }
  return "?";
}

void validate(const SimulationConfig& c) {
  checked_rate_hz(c.rate_hz, "simulation: rate_hz");
  if (!(c.samples >= 1))
    throw Error("simulation: the log needs at least one sample (rate x duration >= 1)");
  if (!c.gyro && !c.accel) throw Error("simulation: no sensor selected (gyro and/or accel)");
  if (c.gyro) c.gyro->validate("gyro");
  if (c.accel) c.accel->validate("accel");
  if (!c.truth.angular_rate.allFinite() || !c.truth.specific_force.allFinite())
    throw Error("simulation: the true signals must be finite");
  if (!(c.temperature_k > 0) || !std::isfinite(c.temperature_k))
    throw Error("simulation: temperature must be > 0 K");
  if (c.schedule) (void)detail::ScheduleTruth(*c.schedule);  // validates
  if (c.truth_series) {
    if (c.schedule)
      throw Error("simulation: a truth series and a multi-position schedule both give the truth; "
                  "use one of them");
    validate(*c.truth_series);
    if (c.gyro && c.truth_series->angular_rate.empty())
      throw Error("simulation: the truth series has no angular rate (gx, gy, gz) for the gyro");
    if (c.accel && c.truth_series->specific_force.empty())
      throw Error("simulation: the truth series has no specific force (ax, ay, az) for the "
                  "accelerometer");
  }
  if (c.temperature_profile) {
    const auto& p = c.temperature_profile->points;
    if (p.empty()) throw Error("simulation: the temperature profile has no points");
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (!std::isfinite(p[i].t_s) || !(p[i].temperature_k > 0) ||
          !std::isfinite(p[i].temperature_k))
        throw Error("simulation: temperature profile point " + std::to_string(i + 1) +
                    " needs a finite time and a temperature > 0 K");
      if (i > 0 && !(p[i].t_s >= p[i - 1].t_s))
        throw Error("simulation: temperature profile times must not decrease (point " +
                    std::to_string(i + 1) + ")");
    }
  }
  if (!is_power_of_two(c.flicker_max_taps) || c.flicker_max_taps < kRandomSubBlock ||
      c.flicker_max_taps > kMaxFlickerTaps)
    throw Error("simulation: flicker_max_taps must be a power of two in [4096, 2^28], got " +
                std::to_string(c.flicker_max_taps));
  for (const auto& [step, what] : {std::pair{c.gyro_quantizer_step, "gyro"},
                                    std::pair{c.accel_quantizer_step, "accel"}}) {
    if (!(step >= 0) || !std::isfinite(step))
      throw Error(std::string("simulation: the ") + what + " quantizer step must be >= 0");
    if (step > 0 && c.kind == OutputKind::counts)
      throw Error(std::string("simulation: a ") + what +
                  " quantizer step and counts output both quantize; use one of them");
  }
  for (const auto& [unit, what] : {std::pair{&c.gyro_unit, "gyro"}, std::pair{&c.accel_unit, "accel"}}) {
    if (!(unit->factor > 0) || !std::isfinite(unit->factor))
      throw Error(std::string("simulation: the ") + what + " output unit factor must be > 0");
    if (c.kind == OutputKind::counts && unit->factor != 1)
      throw Error("simulation: counts output is in counts; an output unit does not apply");
  }
  if (c.kind == OutputKind::counts) {
    const auto check = [](const CountsFormat& f, const char* what) {
      if (!(f.lsb > 0) || !std::isfinite(f.lsb))
        throw Error(std::string("simulation: counts output needs the ") + what + " LSB > 0");
      if (!(f.full_scale >= f.lsb) || !std::isfinite(f.full_scale))
        throw Error(std::string("simulation: counts output needs the ") + what +
                    " full scale >= one LSB");
      if (f.full_scale / f.lsb > 9.0e15)
        throw Error(std::string("simulation: ") + what + " full scale / LSB exceeds 2^53");
    };
    if (c.gyro) check(c.gyro_counts, "gyro");
    if (c.accel) check(c.accel_counts, "accel");
  }
}

std::int64_t flicker_taps(const SimulationConfig& c) {
  std::int64_t taps = kRandomSubBlock;
  while (taps < c.samples && taps < c.flicker_max_taps) taps *= 2;
  return std::min(taps, c.flicker_max_taps);
}

Sampling sampling_of(const SimulationConfig& c) {
  return {1.0 / c.rate_hz, flicker_taps(c), c.kind == OutputKind::increment};
}

struct Simulator::Impl {
  SimulationConfig config;
  double tau0 = 0;
  std::vector<Channel> channels;
  std::unique_ptr<detail::FlickerFilter> filter;
  std::vector<std::unique_ptr<detail::FlickerFilter::Workspace>> workspaces;
  unsigned threads = 1;
  std::int64_t position = 0;     // rows handed out
  std::int64_t chunk_start = 0;  // first sample of the current chunk
  std::int64_t chunk_rows = 0;   // rows in the current chunk (0 before the first)
  // Time-varying truth (schedule) and temperature (profile), per row of the current chunk.
  std::optional<detail::ScheduleTruth> schedule;
  std::optional<detail::TruthCursor> truth_cursor;  // user truth series
  bool dynamic = false;
  std::vector<Eigen::Vector3d> gyro_truth, accel_truth;
  std::vector<double> temperature;

  void fill_truth();

  void generate(Channel& c, detail::FlickerFilter::Workspace* ws, std::int64_t a,
                std::int64_t n) const;
  void refill();
};

void Simulator::Impl::generate(Channel& c, detail::FlickerFilter::Workspace* ws, std::int64_t a,
                               std::int64_t n) const {
  const auto un = static_cast<std::size_t>(n);
  if (c.sensor == 2) {  // temperature channel [K]
    c.values = temperature;
    return;
  }
  if (dynamic) {
    c.values.resize(un);
    const auto& x = c.sensor == 0 ? gyro_truth : accel_truth;
    for (std::size_t i = 0; i < un; ++i)
      c.values[i] = c.gain.dot(x[i]) + c.bias +
                    c.temperature_coefficient * (temperature[i] - c.reference_temperature_k);
  } else {
    c.values.assign(un, c.constant);
  }
  c.scratch.resize(un);
  double* v = c.values.data();
  double* w = c.scratch.data();
  const NoiseTerms& t = c.terms;
  const bool increment = config.kind == OutputKind::increment;
  if (t.white) {
    detail::fill_normal(key_of(c, NoiseTerm::white), a, n, w);
    const double sigma = *t.white / std::sqrt(tau0);
    for (std::int64_t i = 0; i < n; ++i) v[i] += sigma * w[i];
  }
  if (t.quantization) {
    detail::fill_uniform_centered(key_of(c, NoiseTerm::quantization), a, n, w);
    const double width = *t.quantization * kUniformWidthPerQ;
    const double scale = width / tau0;
    double e_prev = c.e_prev;
    for (std::int64_t i = 0; i < n; ++i) {
      v[i] += scale * (w[i] - e_prev);
      e_prev = w[i];
    }
    c.e_prev = e_prev;
  }
  if (t.bias_instability) {
    const std::int64_t span = 2 * filter->taps();  // one block pair
    const double b = *t.bias_instability;
    for (std::int64_t i = 0; i < n;) {
      const std::int64_t k = a + i;
      const std::int64_t pair = k / span;
      if (pair != c.flicker_block) {
        c.flicker.resize(static_cast<std::size_t>(span));
        filter->block_pair(*ws, key_of(c, NoiseTerm::bias_instability), pair, c.flicker.data());
        c.flicker_block = pair;
      }
      const std::int64_t offset = k - pair * span;
      const std::int64_t m = std::min(n - i, span - offset);
      for (std::int64_t j = 0; j < m; ++j) v[i + j] += b * c.flicker[offset + j];
      i += m;
    }
  }
  if (t.rate_random_walk) {
    detail::fill_normal(key_of(c, NoiseTerm::rate_random_walk), a, n, w);
    const double step = *t.rate_random_walk * std::sqrt(tau0);
    double rw = c.rw;
    for (std::int64_t i = 0; i < n; ++i) {
      rw += step * w[i];
      v[i] += rw;
    }
    c.rw = rw;
  }
  for (std::size_t e = 0; e < t.gauss_markov.size(); ++e) {  // one AR(1) per entry
    const GaussMarkov& gm = t.gauss_markov[e];
    detail::fill_normal(c.gm_keys[e], a, n, w);
    const double phi = std::exp(-tau0 / gm.tau_c_s);
    // sqrt(1 - phi^2) without cancellation: 1 - phi^2 = -expm1(-2 tau0/T_c).
    const double drive = gm.sigma * std::sqrt(-std::expm1(-2 * tau0 / gm.tau_c_s));
    double g = c.gm[e];
    for (std::int64_t i = 0; i < n; ++i) {
      g = phi * g + drive * w[i];
      v[i] += g;
    }
    c.gm[e] = g;
  }
  // Deterministic terms at the sample time (rate) or averaged over the interval (increment).
  const double t_offset = increment ? 0.5 : 0.0;
  if (t.rate_ramp) {
    const double r = *t.rate_ramp;
    for (std::int64_t i = 0; i < n; ++i)
      v[i] += r * (static_cast<double>(a + i) + t_offset) * tau0;
  }
  if (t.sinusoid) {
    const double omega = 2 * kPi * t.sinusoid->frequency_hz;
    double amplitude = t.sinusoid->amplitude;
    if (increment) {
      const double x = kPi * t.sinusoid->frequency_hz * tau0;
      amplitude *= std::sin(x) / x;
    }
    // A rotation recurrence (sin, cos) -> (sin, cos) advanced by omega tau0, restarted from
    // std::sin / std::cos every kSinusoidRestart samples of the absolute index grid (so the
    // values do not depend on the chunking); rounding grows by ~1e-16 per step: < 1e-13.
    const double step_c = std::cos(omega * tau0), step_s = std::sin(omega * tau0);
    for (std::int64_t i = 0; i < n;) {
      const double phase = omega * (static_cast<double>(a + i) + t_offset) * tau0 +
                           t.sinusoid->phase_rad;
      double sn = std::sin(phase), cs = std::cos(phase);
      const std::int64_t end = std::min(n, i + kSinusoidRestart - (a + i) % kSinusoidRestart);
      for (; i < end; ++i) {
        v[i] += amplitude * sn;
        const double next_s = sn * step_c + cs * step_s;
        cs = cs * step_c - sn * step_s;
        sn = next_s;
      }
    }
  }
  if (c.quantizer_step > 0) {
    // Integrated output theta_k = theta_{k-1} + tau0 v_k, written as round(theta_k / q) q:
    // the increment is (count_k - count_{k-1}) q = round((r_{k-1} + tau0 v_k) / q) q with
    // r the carried residual theta - quantized theta (no growing sum, so no rounding drift).
    const double q = c.quantizer_step;
    double r = c.quantizer_residual;
    const double out_scale = increment ? q : q / tau0;
    for (std::int64_t i = 0; i < n; ++i) {
      const double d = r + tau0 * v[i];
      const double steps = std::nearbyint(d / q) + 0.0;  // + 0.0: no "-0" in the output
      r = d - steps * q;
      v[i] = steps * out_scale;
    }
    c.quantizer_residual = r;
  } else if (increment) {
    for (std::int64_t i = 0; i < n; ++i) v[i] *= tau0;
  } else if (config.kind == OutputKind::counts) {
    const double limit = std::floor(c.counts.full_scale / c.counts.lsb);
    for (std::int64_t i = 0; i < n; ++i)
      v[i] = std::clamp(std::nearbyint(v[i] / c.counts.lsb), -limit, limit) + 0.0;
  }
}

void Simulator::Impl::fill_truth() {
  // Rate and counts: the truth at t_k = k tau0; increment: its mean over [t_k, t_k + tau0].
  const auto n = static_cast<std::size_t>(chunk_rows);
  const bool increment = config.kind == OutputKind::increment;
  gyro_truth.resize(n);
  accel_truth.resize(n);
  temperature.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(chunk_start + static_cast<std::int64_t>(i)) * tau0;
    Truth x = config.truth;
    if (schedule) x = increment ? schedule->mean(t, t + tau0) : schedule->at(t);
    if (truth_cursor) x = increment ? truth_cursor->mean(t, t + tau0) : truth_cursor->at(t);
    gyro_truth[i] = x.angular_rate;
    accel_truth[i] = x.specific_force;
    temperature[i] = !config.temperature_profile ? config.temperature_k
                     : increment ? mean_temperature(*config.temperature_profile, t, t + tau0)
                                 : temperature_at(*config.temperature_profile, t);
  }
}

void Simulator::Impl::refill() {
  chunk_start += chunk_rows;
  chunk_rows = std::min(kChunk, config.samples - chunk_start);
  if (dynamic) fill_truth();
  const auto count = static_cast<unsigned>(channels.size());
  const unsigned workers = std::max(1u, std::min(threads, count));
  const auto work = [&](unsigned worker) {
    for (unsigned i = worker; i < count; i += workers)
      generate(channels[i], workspaces.empty() ? nullptr : workspaces[worker].get(), chunk_start,
               chunk_rows);
  };
  if (workers == 1) {
    work(0);
    return;
  }
  std::vector<std::thread> pool;
  for (unsigned worker = 1; worker < workers; ++worker) pool.emplace_back(work, worker);
  work(0);
  for (auto& th : pool) th.join();
}

Simulator::Simulator(const SimulationConfig& config) : impl_(std::make_unique<Impl>()) {
  validate(config);
  Impl& s = *impl_;
  s.config = config;
  s.tau0 = 1.0 / config.rate_hz;
  s.threads = std::max(1u, config.threads);
  bool any_flicker = false;
  const auto add = [&](const ErrorModel& model, const Eigen::Vector3d& truth, int sensor,
                       const CountsFormat& counts) {
    const Eigen::Vector3d out = model.deterministic_output(truth, config.temperature_k);
    const Eigen::Matrix3d gain = Eigen::Matrix3d::Identity() + model.error_matrix();
    for (int axis = 0; axis < 3; ++axis) {
      Channel c;
      c.sensor = sensor;
      c.axis = axis;
      c.constant = out[axis];
      c.gain = gain.row(axis);
      c.bias = model.bias[axis];
      c.temperature_coefficient = model.temperature_coefficient[axis];
      c.reference_temperature_k = model.reference_temperature_k;
      c.terms = model.noise[static_cast<std::size_t>(axis)];
      c.counts = counts;
      for (NoiseTerm term : kAllNoiseTerms)
        c.keys[static_cast<std::size_t>(term)] =
            detail::stream_key(config.seed, sensor, axis, static_cast<int>(term));
      if (c.terms.quantization) {  // e_{-1}
        detail::fill_uniform_centered(key_of(c, NoiseTerm::quantization), -1, 1, &c.e_prev);
      }
      c.quantizer_step = sensor == 0 ? config.gyro_quantizer_step : config.accel_quantizer_step;
      if (c.quantizer_step > 0) {  // initial residual: uniform over one step (unknown phase)
        detail::fill_uniform_centered(
            detail::stream_key(config.seed, sensor, axis, kQuantizerStream), -1, 1,
            &c.quantizer_residual);
        c.quantizer_residual *= c.quantizer_step;
      }
      for (std::size_t e = 0; e < c.terms.gauss_markov.size(); ++e) {
        c.gm_keys[e] = e == 0 ? key_of(c, NoiseTerm::gauss_markov)
                              : detail::stream_key(config.seed, sensor, axis,
                                                   gauss_markov_stream(e));
        // g_{-1} from the stationary distribution
        detail::fill_normal(c.gm_keys[e], -1, 1, &c.gm[e]);
        c.gm[e] *= c.terms.gauss_markov[e].sigma;
      }
      any_flicker = any_flicker || c.terms.bias_instability.has_value();
      s.channels.push_back(std::move(c));
    }
  };
  if (config.gyro) add(*config.gyro, config.truth.angular_rate, 0, config.gyro_counts);
  if (config.accel) add(*config.accel, config.truth.specific_force, 1, config.accel_counts);
  if (config.schedule) s.schedule.emplace(*config.schedule);
  if (s.config.truth_series) s.truth_cursor.emplace(*s.config.truth_series);
  s.dynamic = config.schedule.has_value() || config.temperature_profile.has_value() ||
              config.truth_series != nullptr;
  if (config.temperature_profile) {
    Channel c;
    c.sensor = 2;
    s.channels.push_back(std::move(c));
  }
  if (any_flicker) {
    const std::int64_t taps = flicker_taps(config);
    s.filter = std::make_unique<detail::FlickerFilter>(taps);
    const unsigned workers =
        std::max(1u, std::min(s.threads, static_cast<unsigned>(s.channels.size())));
    for (unsigned i = 0; i < workers; ++i)
      s.workspaces.push_back(std::make_unique<detail::FlickerFilter::Workspace>(taps));
  }
}

Simulator::~Simulator() = default;

const SimulationConfig& Simulator::config() const { return impl_->config; }
int Simulator::channels() const { return static_cast<int>(impl_->channels.size()); }

std::vector<std::string> Simulator::channel_names() const {
  std::vector<std::string> names;
  for (const auto& c : impl_->channels)
    names.push_back(c.sensor == 2 ? std::string("temp")
                                  : std::string(c.sensor == 0 ? "g" : "a") + "xyz"[c.axis]);
  return names;
}

std::int64_t Simulator::position() const { return impl_->position; }

double Simulator::time_s(std::int64_t k) const {
  const double offset = impl_->config.kind == OutputKind::increment ? 1.0 : 0.0;
  return (static_cast<double>(k) + offset) * impl_->tau0;
}

std::int64_t Simulator::next(std::span<double> out, std::int64_t max_rows) {
  Impl& s = *impl_;
  const std::int64_t nch = channels();
  if (!(max_rows >= 0) || static_cast<std::int64_t>(out.size()) < max_rows * nch)
    throw Error("Simulator::next: output buffer smaller than max_rows x channels");
  std::int64_t rows = 0;
  while (rows < max_rows && s.position < s.config.samples) {
    if (s.position == s.chunk_start + s.chunk_rows) s.refill();
    const std::int64_t offset = s.position - s.chunk_start;
    const std::int64_t take = std::min(max_rows - rows, s.chunk_rows - offset);
    for (std::int64_t ch = 0; ch < nch; ++ch) {
      const double* src = s.channels[static_cast<std::size_t>(ch)].values.data() + offset;
      double* dst = out.data() + rows * nch + ch;
      for (std::int64_t i = 0; i < take; ++i) dst[i * nch] = src[i];
    }
    rows += take;
    s.position += take;
  }
  return rows;
}

}  // namespace sigmatau
