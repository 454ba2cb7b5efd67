#pragma once
// Reference lag correlations and lag sums of the OAVAR covariance by FFT: the covariance
// basis's previous path, kept as an oracle for tests/test_fit_covariance.cpp and as the
// baseline of bench/bench_fit_covariance.cpp. Not part of the library (the basis uses
// lib/src/fit_covariance_lagsum.cpp); built as the sigmatau_fit_covariance_fft target
// (tests/support/fit_covariance_fft.cmake). Notation as in lib/src/fit_covariance_lags.hpp.
#include <cstdint>
#include <optional>
#include <vector>

#include "../../lib/src/fit_covariance_lags.hpp"

namespace sigmatau::detail {

/// The lag correlations by an inverse FFT of length big_p (a power of two > 2 (m_a + m_b + 1)):
/// c_t(u) for 0 <= u <= big_p / 2 per term t (Q, N, B, K [, GM], units as
/// PairCorrelation::evaluate), aliased by the tail beyond big_p / 2 for B and GM. `tau0_s` the
/// sample interval [s], `gm_rate` tau0 / tau_c when a Gauss-Markov term is modelled.
std::vector<std::vector<double>> fft_lag_correlations(std::int64_t ma, std::int64_t mb,
                                                      double tau0_s, std::optional<double> gm_rate,
                                                      std::int64_t big_p);

/// Lag sums over the window |u| < big_p / 2 of fft_lag_correlations, big_p =
/// lag_factor (m_a + m_b) rounded up to a power of two (at least 256): the previous basis
/// used lag_factor 8. Memory ~ 5 big_p doubles.
LagSums covariance_lag_sums_fft(std::int64_t ma, std::int64_t mb, std::int64_t n_phase_points,
                                double tau0_s, std::optional<double> gm_rate,
                                std::int64_t lag_factor);

}  // namespace sigmatau::detail
