#pragma once
// The AVAR a real quantizer (SimulationConfig::gyro_quantizer_step) adds to a simulated channel.
//
// Glossary: D the step [rad | m/s]; theta_k the unquantized integrated output; q_k = D round(
// theta_k / D) the written one; e_k = q_k - theta_k the rounding error; tau = m tau0; delta_m =
// theta_{k+m} - theta_k with mean mu_m (the constant rate d: mu_m = m tau0 d) and Gaussian
// variance V_m; w the width of the additive Q term's uniform variable (Q sqrt(12)).
//
// The simulator starts the residual uniform over one step, so theta_k mod D is uniform and
// independent of every increment. Then the cross terms between the second differences of theta
// and of e average to zero and AVAR_q(m) = AVAR_theta(m) + AVAR_e(m), with
//   AVAR_e(m) = (6 R(0) - 8 R(m) + 2 R(2m)) / (2 tau^2),  R(0) = D^2 / 12,
//   R(j) = sum_{n>=1} D^2/(2 pi^2 n^2) cos(2 pi n mu_j / D) exp(-2 pi^2 n^2 V_j / D^2)
//          sinc^2(pi n w / D)
// from the Fourier series of the sawtooth e(theta) and the characteristic function of delta_j.
// When the increments span several steps (V_1 >> D^2) R(j) -> 0 and AVAR_e -> D^2 / (4 tau^2),
// the additive 3 Q^2 / tau^2 with Q = D / sqrt(12). With a step much larger than the per-sample
// noise AVAR_e is smaller than that (0.10x at tau0 for D = 40 sigma); with a drift of half a
// step per sample and little noise it is larger (up to 2x). Verified against simulated logs in
// tests/test_simulate_quantizer.cpp.
//
// Exact when delta_m is Gaussian plus the additive term with constant mean: the noise is white,
// additive quantization, Gauss-Markov and flicker (the simulator's flicker is a stationary L-tap
// FIR of white noise, so its sum over j samples has variance B^2 tau0^2 sum_p c_p^2 with c_p the
// sums of j consecutive taps), and the truth, the temperature and the bias are constant.
// Otherwise (rate random walk, whose increments grow along the log, ramp, sinusoid, a schedule,
// a truth series or a temperature profile) the sidecar keeps the additive term and says it is
// approximate.

#include <cstdint>

#include "sigmatau/noise_model.hpp"
#include "sigmatau/simulate.hpp"

namespace sigmatau::detail {

/// The largest step per Gaussian per-sample noise for which the additive term is within 0.6 %
/// of the exact quantization AVAR at every tau and for any drift: |R(j)| <= R(0) 6/pi^2
/// sum exp(-2 pi^2 n^2 V_1/D^2)/n^2 = 0.0044 R(0) when V_1 = (D/2)^2, so AVAR_e is within
/// (8 x 0.0044 + 2 x 1e-8) / 6 = 0.6 % of 6 R(0).
inline constexpr double kQuantizerStepRatioLimit = 2.0;

/// Whether the exact model applies to `terms` of a channel of `config` (see the file comment).
bool real_quantizer_exact(const SimulationConfig& config, const NoiseTerms& terms);

/// The variance of the Gaussian part of one sample's integrated noise [rad^2 | (m/s)^2]:
/// N^2 tau0 (white) + sigma^2 tau0^2 (each Gauss-Markov entry).
double per_sample_gaussian_variance(const NoiseTerms& terms, double tau0_s);

/// AVAR_e(m) [rate unit^2] of the file comment for step D > 0, averaging factor m >= 1, the
/// channel's terms (white, quantization, every gauss_markov entry and bias_instability with the flicker
/// filter's `flicker_taps` are used) and constant rate d [rad/s | m/s^2].
double real_quantizer_avar(double step, std::int64_t m, double tau0_s, const NoiseTerms& terms,
                           double drift, std::int64_t flicker_taps);

/// Variance of the sum of j consecutive samples of the unit flicker FIR (h_0 = 1, h_k =
/// h_{k-1} (k - 1/2) / k, k < taps, unit white input): sum_p c_p^2 with c_p the sum of the taps
/// h_i, max(0, p) <= i <= min(taps - 1, j - 1 + p), p > -j. O(taps + j).
double flicker_window_variance(std::int64_t j, std::int64_t taps);

}  // namespace sigmatau::detail
