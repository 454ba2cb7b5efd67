// The sidecar's theory for a real quantizer coarser than the noise (review C finding 5): the
// exact AVAR of lib/src/simulate_quantizer.hpp against simulated logs, its limits, and the
// warning when the model has no exact theory.
//
// Statistical design: each case simulates R = 16 seeds x 3 axes = 48 independent logs of 2^15
// samples and compares the mean of their OAVARs at m = 1, 2, 8 with the sidecar's theory. The
// tolerance is 4.5 standard errors of that mean, the standard error taken from the spread of the
// 48 estimates themselves: a coarse quantizer's rounding error is strongly correlated from sample
// to sample, so the usual power-law EDF would understate the scatter. With 48 realizations the
// mean is close to normal; P(|Z| > 4.5) = 7e-6 per check, about 1e-4 for this file's 15 checks.
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>
#include <span>
#include <vector>

#include "../../lib/src/simulate_quantizer.hpp"  // internal interface under test
#include "sigmatau/simulate.hpp"
#include "test_support.hpp"

using namespace sigmatau;
using sigmatau::test::rel;

namespace {

constexpr std::int64_t kSamples = std::int64_t{1} << 15;
constexpr int kSeeds = 16;
constexpr double kRate = 100.0;  // Hz
constexpr double kTau0 = 1.0 / kRate;
constexpr double kStandardErrors = 4.5;  // see the file comment
/// The octave factors checked and their index in the sidecar's tau list (1, 2, 4, 8, ...).
constexpr std::array<std::int64_t, 3> kFactors{1, 2, 8};
constexpr std::array<std::size_t, 3> kIndex{0, 1, 3};

SimulationConfig quantized(const NoiseTerms& terms, double step, std::uint64_t seed) {
  SimulationConfig c;
  c.rate_hz = kRate;
  c.samples = kSamples;
  c.seed = seed;
  ErrorModel g;
  g.noise = {terms, terms, terms};
  c.gyro = g;
  c.gyro_quantizer_step = step;
  return c;
}

/// Overlapping AVAR [rate^2] of channel `ch` of rows with `stride` channels at factor m
/// (SP 1065 eq. 11 on the phase x_k = tau0 sum y).
double oavar(const std::vector<double>& rows, int stride, int ch, std::int64_t m) {
  const std::int64_t n = static_cast<std::int64_t>(rows.size()) / stride;
  std::vector<long double> x(static_cast<std::size_t>(n + 1), 0.0L);
  for (std::int64_t i = 0; i < n; ++i)
    x[static_cast<std::size_t>(i + 1)] =
        x[static_cast<std::size_t>(i)] + rows[static_cast<std::size_t>(i * stride + ch)] * kTau0;
  long double s = 0;
  for (std::int64_t i = 0; i + 2 * m <= n; ++i) {
    const long double d = x[static_cast<std::size_t>(i + 2 * m)] -
                          2 * x[static_cast<std::size_t>(i + m)] + x[static_cast<std::size_t>(i)];
    s += d * d;
  }
  const double tau = static_cast<double>(m) * kTau0;
  return static_cast<double>(s / static_cast<long double>(n + 1 - 2 * m)) / (2 * tau * tau);
}

std::vector<double> simulate(const SimulationConfig& c) {
  Simulator sim(c);
  std::vector<double> rows(static_cast<std::size_t>(c.samples * sim.channels()));
  std::int64_t done = 0;
  while (done < c.samples)
    done += sim.next(std::span<double>(rows).subspan(static_cast<std::size_t>(done * 3)),
                     c.samples - done);
  return rows;
}

nlohmann::json theory_of(const SimulationConfig& c) {
  return nlohmann::json::parse(simulation_sidecar_json(c))["theory"];
}

/// The mean OAVAR of the 48 logs agrees with the sidecar's theory within kStandardErrors; returns
/// the means and standard errors for further checks.
struct Pooled {
  std::array<double, 3> mean{}, standard_error{};
};
Pooled check_against_sidecar(const NoiseTerms& terms, double step, const Eigen::Vector3d& bias) {
  std::array<std::vector<double>, 3> estimates;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    SimulationConfig c = quantized(terms, step, static_cast<std::uint64_t>(seed));
    c.gyro->bias = bias;
    const auto rows = simulate(c);
    for (int axis = 0; axis < 3; ++axis)
      for (std::size_t i = 0; i < kFactors.size(); ++i)
        estimates[i].push_back(oavar(rows, 3, axis, kFactors[i]));
  }
  SimulationConfig c = quantized(terms, step, 1);
  c.gyro->bias = bias;
  const auto theory = theory_of(c);
  Pooled p;
  for (std::size_t i = 0; i < kFactors.size(); ++i) {
    const auto& e = estimates[i];
    const double r = static_cast<double>(e.size());
    double mean = 0, var = 0;
    for (double v : e) mean += v / r;
    for (double v : e) var += (v - mean) * (v - mean) / (r - 1);
    p.mean[i] = mean;
    p.standard_error[i] = std::sqrt(var / r);
    for (const char* ch : {"gx", "gy", "gz"}) {
      const double expected = theory["avar"][ch][kIndex[i]].get<double>();
      INFO(std::string(ch) << " m = " << kFactors[i] << ": mean OAVAR " << mean << " +- "
              << p.standard_error[i] << ", sidecar theory " << expected);
      CHECK(std::abs(mean - expected) <= kStandardErrors * p.standard_error[i]);
    }
  }
  return p;
}

double additive(double step, std::int64_t m) {
  const double tau = static_cast<double>(m) * kTau0;
  return step * step / (4 * tau * tau);
}

}  // namespace

TEST_CASE("a step 40x the white noise: the sidecar's theory matches the log, 3 Q^2/tau^2 does not") {
  // The review's case: N sqrt(tau0) = 2.5e-4 deg per sample against a 0.01 deg step.
  NoiseTerms t;
  t.white = 0.15 * std::numbers::pi / 180 / 60;  // 0.15 deg/sqrt(h) [rad/s/sqrt(Hz)]
  const double step = 0.01 * std::numbers::pi / 180;
  const Pooled p = check_against_sidecar(t, step, Eigen::Vector3d::Zero());
  // The old additive theory lies far outside the same interval (it is ~3x too high at tau0).
  const double white_m1 = *t.white * *t.white / kTau0;
  CHECK(additive(step, 1) + white_m1 - p.mean[0] > 20 * p.standard_error[0]);
}

TEST_CASE("a step 4x the noise with a drift of 0.3 step per sample and Gauss-Markov noise") {
  NoiseTerms t;
  t.white = 1e-3;  // 1e-4 rad per sample
  t.gauss_markov = {GaussMarkov{2e-3, 0.05}};
  const double step = 4e-4;
  check_against_sidecar(t, step, Eigen::Vector3d::Constant(0.3 * step / kTau0));
}

TEST_CASE("a step 4x the white noise with flicker of about the same per-sample size") {
  // The flicker FIR's per-sample standard deviation is B sqrt(sum h^2) ~ 2.3 B for 2^15 taps:
  // 2.3e-4 rad per sample, twice the white 1e-4, so the window sums of the taps matter.
  NoiseTerms t;
  t.white = 1e-3;
  t.bias_instability = 1e-2;
  const double step = 4e-4;
  check_against_sidecar(t, step, Eigen::Vector3d::Constant(0.3 * step / kTau0));
}

TEST_CASE("the flicker window variance: one tap is a sum of j unit normals; j = 1 is sum h^2") {
  CHECK(detail::flicker_window_variance(1, 1) == rel(1, 1e-15));  // rounding only
  CHECK(detail::flicker_window_variance(7, 1) == rel(7, 1e-15));
  // Two taps h = (1, 1/2): j = 1 gives 1 + 1/4; j = 2 sums (h0), (h0 + h1), (h1): 1 + 9/4 + 1/4.
  CHECK(detail::flicker_window_variance(1, 2) == rel(1.25, 1e-15));
  CHECK(detail::flicker_window_variance(2, 2) == rel(3.5, 1e-15));
}

TEST_CASE("a step 3x the white noise with an additive quantization term") {
  NoiseTerms t;
  t.white = 1e-3;
  t.quantization = 2e-5;  // the additive term's uniform width 6.9e-5 rad, a fifth of the step
  check_against_sidecar(t, 3e-4, Eigen::Vector3d::Zero());
}

TEST_CASE("the exact quantizer theory reaches its limits") {
  NoiseTerms t;
  const double step = 1e-4;
  SUBCASE("noise much larger than the step: 3 Q^2/tau^2") {
    t.white = 1e-2;  // 1e-3 rad per sample = 10 steps: the harmonics vanish (exp(-2 pi^2 100))
    const auto theory = theory_of(quantized(t, step, 1));
    for (std::size_t i : {std::size_t{0}, std::size_t{3}}) {
      const std::int64_t m = std::int64_t{1} << i;
      const double white = *t.white * *t.white / (static_cast<double>(m) * kTau0);
      // 1e-12: the series and the closed form agree to rounding.
      CHECK(theory["avar"]["gx"][i].get<double>() == rel(white + additive(step, m), 1e-12));
    }
  }
  SUBCASE("no noise, a drift of half a step per sample: twice 3 Q^2/tau^2 at tau0") {
    // The output alternates 0 and one step per sample: the second difference is +-step.
    SimulationConfig c = quantized(t, step, 1);
    c.gyro->bias = Eigen::Vector3d::Constant(0.5 * step / kTau0);
    const auto theory = theory_of(c);
    CHECK(theory["avar"]["gx"][0].get<double>() == rel(2 * additive(step, 1), 1e-12));
    // ... and the log agrees: every OAVAR term is step^2 (up to the start phase's first terms).
    c.samples = 4096;
    const auto rows = simulate(c);
    CHECK(oavar(rows, 3, 0, 1) == rel(2 * additive(step, 1), 1e-3));
  }
  SUBCASE("no noise and no drift: the quantizer adds nothing") {
    const auto theory = theory_of(quantized(t, step, 1));
    CHECK(std::abs(theory["avar"]["gx"][0].get<double>()) <= 1e-12 * additive(step, 1));
  }
}

TEST_CASE("a coarse quantizer on a model without exact theory is warned about and recorded") {
  NoiseTerms t;
  t.white = 1e-3;
  t.rate_random_walk = 1e-5;  // increments that grow along the log: no exact quantizer theory
  SUBCASE("step 40x the per-sample noise: a warning naming the axes, in the sidecar too") {
    const SimulationConfig c = quantized(t, 4e-3, 1);
    const auto warnings = simulation_warnings(c);
    REQUIRE(warnings.size() == 1);
    CHECK(warnings[0].find("40x the per-sample white noise on gx, gy, gz") != std::string::npos);
    const auto j = nlohmann::json::parse(simulation_sidecar_json(c));
    CHECK(j["warnings"][0].get<std::string>() == warnings[0]);
    CHECK(j["theory"]["quantizer"].get<std::string>().find("additive equivalent") !=
          std::string::npos);
  }
  SUBCASE("step 2x the per-sample noise: within 0.6 %, no warning") {
    CHECK(simulation_warnings(quantized(t, 2e-4, 1)).empty());
  }
  SUBCASE("white noise and flicker: the theory is exact, no warning") {
    t.rate_random_walk.reset();
    t.bias_instability = 1e-5;
    CHECK(simulation_warnings(quantized(t, 4e-3, 1)).empty());
  }
}
