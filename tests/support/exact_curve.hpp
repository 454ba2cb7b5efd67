#pragma once
// An exact theoretical OADEV curve for the fit tests: sampled_avar of the terms at the octave
// averaging factors of a log, with the EDF of an ideal estimator (N / m).
#include <cmath>
#include <cstdint>

#include "sigmatau/allan_curve.hpp"
#include "sigmatau/noise_model.hpp"
#include "sigmatau/taus.hpp"

namespace sigmatau::test {

/// The OADEV curve of `truth` for a log of `samples` rate samples at `tau0_s` [s], octave taus;
/// `flicker_taps` as in Sampling (0: untruncated flicker).
inline AllanCurve exact_oadev_curve(const NoiseTerms& truth, std::int64_t samples, double tau0_s,
                                    std::int64_t flicker_taps = 0) {
  AllanCurve curve;
  curve.statistic = Statistic::oadev;
  const std::int64_t n = samples + 1;
  for (const auto m : averaging_factors(TauSpec{}, Statistic::oadev, n, tau0_s)) {
    CurvePoint p;
    p.value.m = m;
    p.value.tau_s = static_cast<double>(m) * tau0_s;
    p.value.dev = std::sqrt(sampled_avar(truth, m, Sampling{tau0_s, flicker_taps, false}));
    p.confidence.edf = static_cast<double>(n) / static_cast<double>(m);
    curve.points.push_back(p);
  }
  return curve;
}

}  // namespace sigmatau::test
