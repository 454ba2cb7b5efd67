#pragma once
/// \file simulate.hpp
/// Synthetic IMU logs with known truth: y = (I + T) x + b + c (temperature - T0) + noise, per
/// triad (noise_model.hpp), generated in streaming blocks with bounded memory.
///
/// Determinism: every random number depends only on (seed, sensor, axis, term, sample index):
/// each such stream is cut into sub-blocks of kRandomSubBlock samples, and a sub-block's
/// generator (xoshiro256++) is seeded from a hash of those four keys and the sub-block index.
/// So the same seed gives bit-identical samples whatever the caller's block size and the
/// thread count.
///
/// Per-term recipes (tau0 = 1/rate, w_k unit normal; THEORY.md section 6):
///  - white:        y_k += (N / sqrt(tau0)) w_k
///  - quantization: y_k += (e_k - e_{k-1}) / tau0, e_k uniform of width Q sqrt(12) (the additive
///                  equivalent of quantizing the integrated angle with step Q sqrt(12))
///  - flicker:      y_k += B sum_{j<L} h_j w_{k-j} (Kasdin, h_j = h_{j-1}(j - 1/2)/j), an
///                  exact L-tap FIR evaluated by FFT overlap-save (two blocks of L per complex
///                  transform); the white input is
///                  regenerated from its counter-based stream, so the process is stationary and
///                  its AVAR is flicker_avar_per_unit(m, L) B^2 exactly. It is 1/f for
///                  f >~ 1/(L tau0); flicker_band(L) gives the taus where the ADEV is flat.
///  - random walk:  b_k = b_{k-1} + K sqrt(tau0) w_k, b_{-1} = 0
///  - Gauss-Markov: g_k = phi g_{k-1} + sigma sqrt(1 - phi^2) w_k, phi = exp(-tau0/T_c),
///                  g_{-1} ~ N(0, sigma^2) (stationary from the start); a sum of entries is
///                  one such AR(1) per entry, each on its own random stream (entry 0 on the
///                  Gauss-Markov stream, so a one-entry model gives the samples it always did)
///  - ramp:         y_k += R t_k;   sinusoid: y_k += A sin(2 pi f t_k + phase)
/// Sample k is at t_k = k tau0 (rate and counts). Increment output: sample k is the integral
/// over [k tau0, (k+1) tau0]: deterministic parts (truth, bias, ramp, sinusoid) are integrated
/// exactly, and each noise sample above is taken as the mean rate over its interval.
///
/// Multi-position schedules (calibration): the sensor dwells in each orientation, then turns to
/// the next about the fixed body axis of the shortest rotation, with the cycloidal angle profile
/// phi(s) = theta (s/D - sin(2 pi s/D)/(2 pi)), D = 2 theta / omega_max: the rate rises smoothly
/// from 0 to the peak omega_max and back, so point-sampled rates integrate accurately. Truth:
/// gyro = u phi'(s) + C(s)^T omega_ie (body rate plus Earth rate), accel = C(s)^T (0, 0, -g), with
/// C(s) = C_k Exp(u phi(s)) the body-to-NED attitude (sensor at the centre of rotation). Increment
/// output integrates the truth over each sample interval (split at segment boundaries, 8-point
/// Gauss-Legendre inside a rotation: exact to rounding for the angles per sample of any real
/// schedule). A temperature profile (piecewise linear in time) drives the bias temperature
/// coefficients and adds a "temp" channel [K] (increment output: the mean over the interval).
/// A user truth series (TruthSeries, e.g. from read_truth_csv) replaces the static truth: linear
/// in time between its rows, held outside them; increment output integrates it exactly.

#include <Eigen/Core>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sigmatau/earth.hpp"  // kEarthRate, earth_rate_ned, normal_gravity: the truth at rest
#include "sigmatau/noise_model.hpp"

namespace sigmatau {

/// Random streams are generated in sub-blocks of this many samples (see file comment).
inline constexpr std::int64_t kRandomSubBlock = 4096;

/// A static sensor: attitude of the sensor (body) frame relative to local north-east-down,
/// as roll, pitch, yaw (z-y-x Euler angles) [rad], and the latitude [rad].
struct StaticPose {
  double roll_rad = 0;
  double pitch_rad = 0;
  double yaw_rad = 0;
  double latitude_rad = 0;
};

/// The true (error-free) signals in the sensor frame.
struct Truth {
  Eigen::Vector3d angular_rate = Eigen::Vector3d::Zero();    ///< [rad/s]
  Eigen::Vector3d specific_force = Eigen::Vector3d::Zero();  ///< [m/s^2]
};

/// Earth rate and minus gravity (specific force of a static sensor) rotated into the sensor
/// frame: omega_n = Omega (cos lat, 0, -sin lat), f_n = (0, 0, -g(lat)); level, z down reads -g.
Truth static_truth(const StaticPose& pose);

/// One static position of a multi-position schedule: attitude as in StaticPose and its dwell.
struct SchedulePosition {
  double roll_rad = 0;
  double pitch_rad = 0;
  double yaw_rad = 0;
  double dwell_s = 0;  ///< time spent static in this orientation [s] (>= 0)
};

/// A multi-position schedule: dwell in positions[0], rotate to positions[1] (cycloidal profile,
/// peak rate rotation_rate_rad_s, see the file comment), dwell, ... After the last dwell the
/// sensor stays in the last position.
struct Schedule {
  std::vector<SchedulePosition> positions;
  double rotation_rate_rad_s = 0;  ///< peak rate of each rotation [rad/s] (> 0 for >= 2 positions)
  double latitude_rad = 0;         ///< latitude [rad] (Earth rate, normal gravity)
};

/// One segment of a schedule's timeline.
struct ScheduleSegment {
  double start_s = 0;
  double end_s = 0;
  int position = 0;       ///< static: the position; rotation: the position it leaves
  bool rotating = false;
};

/// The timeline of a schedule: dwell 0, rotation 0->1, dwell 1, ... (zero-length rotations
/// between identical orientations are omitted). Throws Error on a bad schedule.
std::vector<ScheduleSegment> schedule_timeline(const Schedule& schedule);

/// Duration of the schedule [s] (end of the last dwell).
double schedule_duration_s(const Schedule& schedule);

/// The true signals at time t [s] (before 0: the first position; after the end: the last).
Truth schedule_truth(const Schedule& schedule, double t_s);

/// A schedule of `count` well-spread orientations for calibration: gravity directions on a
/// Fibonacci sphere (so every count >= 6 spans all three axes both ways), yaw advancing by the
/// golden angle, each held for `dwell_s` [s], rotations at `rotation_rate_rad_s` [rad/s].
/// Throws Error if count < 1 or the dwell or rate is not > 0.
Schedule calibration_schedule(int count, double dwell_s, double rotation_rate_rad_s,
                              double latitude_rad);

/// A temperature profile: (time [s], temperature [K]) points, linear in between, constant
/// outside. Two points at the same time make a step.
struct TemperaturePoint {
  double t_s = 0;
  double temperature_k = 0;
};
struct TemperatureProfile {
  std::vector<TemperaturePoint> points;  ///< non-decreasing in time, at least one
};

/// Temperature at t [s] [K] (at a step: the value after it).
double temperature_at(const TemperatureProfile& profile, double t_s);
/// Mean temperature over [t0, t1] [K] (exact for the piecewise-linear profile; t0 == t1: the
/// value at t0).
double mean_temperature(const TemperatureProfile& profile, double t0_s, double t1_s);

/// A user-given true signal in the sensor frame: rows at strictly increasing times, linear in
/// time between rows and held constant before the first and after the last row. Either vector
/// may be empty when that sensor is not simulated; otherwise each has one entry per time.
struct TruthSeries {
  std::vector<double> t_s;                      ///< strictly increasing, finite [s]
  std::vector<Eigen::Vector3d> angular_rate;    ///< [rad/s] (empty: no gyro truth)
  std::vector<Eigen::Vector3d> specific_force;  ///< [m/s^2] (empty: no accel truth)
  std::string source;                           ///< where it came from (for the sidecar)
};

/// Checks a series (sizes, strictly increasing finite times, finite values); throws Error naming
/// the first bad row (1-based).
void validate(const TruthSeries& series);
/// The series at t [s] (linear interpolation, constant outside); an empty vector gives zeros.
Truth truth_at(const TruthSeries& series, double t_s);
/// The mean of the series over [t0, t1] [s] (exact for the piecewise-linear signal; t0 == t1:
/// truth_at(t0)).
Truth truth_mean(const TruthSeries& series, double t0_s, double t1_s);

/// Reads a truth CSV (or any text log LogReader reads): time column "t" [s] and the columns
/// gx, gy, gz (when `gyro`) and ax, ay, az (when `accel`), each multiplied by its factor to SI
/// (rad/s | m/s^2 per unit of the file; 1 for SI). Throws ParseError / Error naming the file,
/// the line and the problem (missing column, non-numeric or non-finite value, time not
/// increasing).
TruthSeries read_truth_csv(const std::filesystem::path& path, bool gyro, bool accel,
                           double gyro_factor = 1, double accel_factor = 1);

enum class OutputKind { rate, increment, counts };
/// "rate" | "increment" | "counts"; throws Error otherwise.
OutputKind parse_output_kind(std::string_view text);
std::string_view to_string(OutputKind kind);

/// Integer-count output of one triad: value = round(rate / lsb), clamped to
/// +-floor(full_scale / lsb).
struct CountsFormat {
  double lsb = 0;         ///< rate per count [rad/s | m/s^2]
  double full_scale = 0;  ///< saturation [rad/s | m/s^2]
};

/// The unit values are written in (write_simulation only; the Simulator produces SI): a written
/// value is the SI value / factor, e.g. {"deg/s", pi/180}. Empty name: SI (factor 1).
struct OutputUnit {
  std::string name;
  double factor = 1;  ///< SI value of one unit [SI / unit], > 0
};

/// Where a sensor's noise terms came from, recorded in the sidecar as "<sensor>/noise_source".
struct NoiseSource {
  std::string origin;                 ///< e.g. "data sheet tdk_icm42688p" or "--model"
  std::vector<std::string> read;      ///< how each term was read (simulate_spec.hpp)
  std::vector<std::string> left_out;  ///< terms the source does not give (simulated as zero)
};

struct SimulationConfig {
  double rate_hz = 0;          ///< sample rate [Hz]
  std::int64_t samples = 0;    ///< number of samples
  std::uint64_t seed = 1;
  std::optional<ErrorModel> gyro;   ///< simulated when present (channels gx, gy, gz)
  std::optional<ErrorModel> accel;  ///< simulated when present (channels ax, ay, az)
  Truth truth;                      ///< true signals (e.g. static_truth(pose))
  /// Multi-position schedule; when present it gives the truth (and `truth` is ignored).
  std::optional<Schedule> schedule;
  /// A user-given true signal (e.g. read_truth_csv); when present it gives the truth (and
  /// `truth` is ignored). Shared, not copied, by the Simulator. Not together with `schedule`.
  std::shared_ptr<const TruthSeries> truth_series;
  double temperature_k = 298.15;    ///< constant sensor temperature [K]
  /// Temperature profile; when present it replaces temperature_k and adds the "temp" channel.
  std::optional<TemperatureProfile> temperature_profile;
  OutputKind kind = OutputKind::rate;
  CountsFormat gyro_counts;         ///< for kind == counts
  CountsFormat accel_counts;        ///< for kind == counts
  /// A real quantizer (rate and increment kinds; 0 = none): the integrated output (angle
  /// [rad] | velocity [m/s]) is rounded to multiples of this step, carrying the rounding error
  /// from sample to sample, so each increment is an integer number of steps and each rate sample
  /// an integer number of steps / tau0. Unlike the additive Q term this is a deterministic
  /// function of the signal; when the other noise spans several steps per sample, it adds
  /// 3 Q^2 / tau^2 to the AVAR with Q = step / sqrt(12). The sidecar's theory uses the exact
  /// AVAR for a coarser step when the model allows (white, Q, Gauss-Markov and flicker noise,
  /// constant truth; lib/src/simulate_quantizer.hpp), else 3 Q^2 / tau^2 and
  /// simulation_warnings().
  double gyro_quantizer_step = 0;
  double accel_quantizer_step = 0;
  OutputUnit gyro_unit;             ///< unit of the written gyro values (see OutputUnit)
  OutputUnit accel_unit;            ///< unit of the written accel values
  /// Longest flicker filter [taps], a power of two >= kRandomSubBlock. Memory is about
  /// 16 L bytes per flicker channel plus 32 L per thread plus 16 L; the flat band ends near
  /// flicker_band(L).m_high tau0.
  std::int64_t flicker_max_taps = std::int64_t{1} << 20;
  unsigned threads = 1;             ///< worker threads (results do not depend on it)
  std::optional<NoiseSource> gyro_noise_source;   ///< recorded in the sidecar when present
  std::optional<NoiseSource> accel_noise_source;  ///< recorded in the sidecar when present
};

/// Throws Error on a bad configuration (rate, samples, no sensor, bad model, counts format).
void validate(const SimulationConfig& config);

/// Lines for the user about a valid configuration whose sidecar theory is only approximate: a
/// real quantizer step more than 2x the per-sample white noise on an axis whose model has no
/// exact quantizer theory (rate random walk, ramp, sinusoid, schedule, truth series,
/// temperature profile; see lib/src/simulate_quantizer.hpp). The sidecar records them too.
std::vector<std::string> simulation_warnings(const SimulationConfig& config);

/// Taps of the flicker filter used for a configuration: the smallest power of two >= samples
/// (at least kRandomSubBlock), capped at flicker_max_taps.
std::int64_t flicker_taps(const SimulationConfig& config);

/// The sampling description for sampled_avar() of a simulated log.
Sampling sampling_of(const SimulationConfig& config);

/// Streaming generator. Channels are gx, gy, gz (if gyro) then ax, ay, az (if accel), then temp
/// [K] (if a temperature profile is given).
class Simulator {
 public:
  explicit Simulator(const SimulationConfig& config);  ///< validates; throws Error
  ~Simulator();
  Simulator(const Simulator&) = delete;
  Simulator& operator=(const Simulator&) = delete;

  const SimulationConfig& config() const;
  int channels() const;
  std::vector<std::string> channel_names() const;
  std::int64_t position() const;  ///< samples produced so far
  /// Time stamp of sample k [s]: k tau0 (rate, counts) or (k + 1) tau0 (increment: end of the
  /// integration interval).
  double time_s(std::int64_t k) const;

  /// Produces the next rows (at most max_rows, fewer at the end of the log) into `out`, row-major
  /// [rows x channels()] in SI (rate: rad/s, m/s^2; increment: rad, m/s; counts: counts).
  /// Requires out.size() >= max_rows * channels(). Returns the rows produced (0 at the end).
  std::int64_t next(std::span<double> out, std::int64_t max_rows);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Data file formats: text, little-endian floats, or (kind counts only) little-endian signed
/// integers of 16 or 32 bits, as a sensor's registers give them.
enum class SampleFormat { csv, f32, f64, i16, i32 };
/// "csv" | "f32" | "f64" | "i16" | "i32"; throws Error otherwise.
SampleFormat parse_sample_format(std::string_view text);
std::string_view to_string(SampleFormat format);

/// Throws Error when `config` cannot be written in `format`: i16 / i32 need kind counts, no
/// temperature channel (it is in K) and, for i16, full_scale / lsb <= 32767 on every sensor.
void check_sample_format(const SimulationConfig& config, SampleFormat format);

/// The exact truth of a configuration as JSON text: every parameter in SI, the truth vectors,
/// the flicker taps and band, and the theoretical AVAR (sampled_avar) per channel at the octave
/// averaging factors 1, 2, 4, ... <= (samples - 1) / 4. "columns" and "file" describe the data
/// file as write_simulation writes it in `format`: csv starts with the time column "t"; f32 and
/// f64 hold only the channels, and "file"/"read_with" gives the options that read it back
/// (e.g. "--binary f32 --channels 3 --rate 100").
std::string simulation_sidecar_json(const SimulationConfig& config,
                                    SampleFormat format = SampleFormat::csv);

/// Streams a simulated log to `path` (csv with header "t,gx,gy,gz,ax,ay,az,temp" for the
/// sensors and temperature present; f32/f64/i16/i32: little-endian rows of the channels, no time
/// column (check_sample_format);
/// values in config.gyro_unit / accel_unit, SI by default) and its sidecar to
/// "<path>.json". Both files are written to a temporary name in their directory and renamed
/// into place; an existing file is an Error unless `overwrite`. `progress(done, total)` is
/// called after each block when set. `sidecar` replaces "<path>.json" (an empty path: no
/// sidecar). When `path` is a device or pipe (is_stream_output: -o /dev/stdout) and no
/// `sidecar` is given, Error before anything is written: "<path>.json" would land in /dev.
void write_simulation(const SimulationConfig& config, const std::filesystem::path& path,
                      SampleFormat format, bool overwrite,
                      const std::function<void(std::int64_t, std::int64_t)>& progress = {},
                      const std::optional<std::filesystem::path>& sidecar = std::nullopt);

}  // namespace sigmatau
