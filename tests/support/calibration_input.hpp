#pragma once
// A simulated log as a CalibrationInput (for the calibrate tests): the simulator's channels gx..gz,
// ax..az and temp distributed into the input's vectors, row by row.
#include <cstdint>
#include <string>
#include <vector>

#include "sigmatau/calibrate.hpp"
#include "sigmatau/simulate.hpp"

namespace sigmatau::test {

/// Runs the simulator for `c` and returns its rows as a CalibrationInput (rates or increments
/// as configured; a "temp" channel, when simulated, in temperature_k).
inline CalibrationInput simulate_calibration_input(const SimulationConfig& c) {
  Simulator sim(c);
  const int nch = sim.channels();
  const auto names = sim.channel_names();
  std::vector<double> block(static_cast<std::size_t>(4096 * nch));
  CalibrationInput in;
  in.rate_hz = c.rate_hz;
  in.increments = c.kind == OutputKind::increment;
  for (std::int64_t rows; (rows = sim.next(block, 4096)) > 0;) {
    for (std::int64_t r = 0; r < rows; ++r)
      for (int ch = 0; ch < nch; ++ch) {
        const double v = block[static_cast<std::size_t>(r * nch + ch)];
        const std::string& n = names[static_cast<std::size_t>(ch)];
        if (n == "temp") in.temperature_k.push_back(v);
        else (n[0] == 'g' ? in.gyro : in.accel)[static_cast<std::size_t>(n[1] - 'x')].push_back(v);
      }
  }
  return in;
}

}  // namespace sigmatau::test
