#pragma once
// The simulated profiles with known truth that the fit benchmarks share (bench_fit_accuracy,
// bench_fit_baselines): the same names, truths, rates and lengths in both tables.
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "sigmatau/noise_model.hpp"
#include "sigmatau/simulate.hpp"

namespace sigmatau::bench {

/// One simulated sensor: its noise terms (parse_noise_terms text), rate [Hz] and length [h].
struct Profile {
  std::string name;
  std::string description;
  Sensor sensor;
  double rate_hz;
  double hours;
  std::string model;  // parse_noise_terms text
};

inline const std::vector<Profile>& profiles() {
  static const std::vector<Profile> p{
      {"mems_gyro", "MEMS gyro, 100 Hz, 2 h", Sensor::gyro, 100, 2,
       "N=0.15 deg/sqrt(h), B=3 deg/h, K=15 deg/h/sqrt(h)"},
      {"tactical_gyro", "tactical gyro, 200 Hz, 2 h", Sensor::gyro, 200, 2,
       "Q=1 arcsec, N=0.02 deg/sqrt(h), B=0.3 deg/h"},
      {"consumer_accel", "consumer MEMS accelerometer, 100 Hz, 2 h", Sensor::accel, 100, 2,
       "N=150 ug/sqrt(Hz), B=40 ug, K=5e-5 m/s^2.5"},
      // The demo's case (specs/safran_stim300.yaml typical gyro terms, 3 h at 100 Hz): a flicker
      // floor that only shows at the end of the curve and no K, where a criterion too eager
      // for a large-tau term picks N,K or N,B,K instead of N,B.
      {"weak_flicker_gyro", "STIM300-like gyro (weak flicker, no K), 100 Hz, 3 h", Sensor::gyro,
       100, 3, "N=0.15 deg/sqrt(h), B=0.5 deg/h"},
      // The demo's accelerometer (specs/safran_stim300.yaml typical VRW 0.06 m/s/sqrt(h) and
      // bias instability 0.05 mg, read as the ADEV floor): a flicker floor from ~4 s to the
      // end of the log and no K, where the scatter of the last taus can pass for a K.
      {"flicker_accel", "STIM300-like accelerometer (flicker floor from 4 s, no K), 100 Hz, 3 h",
       Sensor::accel, 100, 3, "N=102 ug/sqrt(Hz), B=75 ug"},
      // A rate ramp (a warm-up or thermal drift) that crosses the flicker floor near 250 s, as
      // the MEMS gyro's K does near 200 s: selection must still find R although it gives a
      // ramp a low prior (fit_select.hpp, kRampPriorPenalty).
      {"ramp_gyro", "MEMS gyro with a rate ramp (no K), 100 Hz, 2 h", Sensor::gyro, 100, 2,
       "N=0.15 deg/sqrt(h), B=3 deg/h, R=40 deg/h^2"},
      // A small quantization (3.7 % of the AVAR at tau0): selection must still find Q although
      // it gives quantization a prior (fit_select.hpp, kQuantizationPriorPenalty).
      {"quantized_gyro", "MEMS gyro with a small quantization, 100 Hz, 2 h", Sensor::gyro, 100, 2,
       "Q=0.1 arcsec, N=0.15 deg/sqrt(h), B=3 deg/h, K=15 deg/h/sqrt(h)"},
      // Short logs (review F, finding 2): VIO users record 5-30 min, where K's rise and B's
      // floor share the last few taus. bench/results_fit_short_logs.md.
      {"short_gyro_5min", "MEMS gyro, 200 Hz, 5 min", Sensor::gyro, 200, 5.0 / 60,
       "N=0.2 deg/sqrt(h), B=4 deg/h, K=20 deg/h/sqrt(h)"},
      {"short_gyro_30min", "MEMS gyro, 200 Hz, 30 min", Sensor::gyro, 200, 0.5,
       "N=0.2 deg/sqrt(h), B=4 deg/h, K=20 deg/h/sqrt(h)"},
  };
  return p;
}

/// The true value of `term` in SI (0 when the profile has none).
inline double truth_of(const NoiseTerms& t, NoiseTerm term) {
  switch (term) {
    case NoiseTerm::quantization: return t.quantization.value_or(0);
    case NoiseTerm::white: return t.white.value_or(0);
    case NoiseTerm::bias_instability: return t.bias_instability.value_or(0);
    case NoiseTerm::rate_random_walk: return t.rate_random_walk.value_or(0);
    case NoiseTerm::rate_ramp: return t.rate_ramp.value_or(0);
    default: return 0;
  }
}

/// The simulation of a profile: its rate and length, `truth` (the profile's model, parsed) on
/// all three axes of its sensor; the seed is left for each run to set.
inline SimulationConfig simulation_config(const Profile& profile, const NoiseTerms& truth) {
  SimulationConfig config;
  config.rate_hz = profile.rate_hz;
  config.samples = static_cast<std::int64_t>(std::llround(profile.hours * 3600 * profile.rate_hz));
  ErrorModel model;
  model.noise = {truth, truth, truth};
  (profile.sensor == Sensor::gyro ? config.gyro : config.accel) = model;
  return config;
}

}  // namespace sigmatau::bench
