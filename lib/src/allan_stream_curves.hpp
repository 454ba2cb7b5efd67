#pragma once
// Internal (allan_stream.cpp): the curves of the stream mode from its finished sums: deviation,
// noise type, EDF of the strided estimator and interval at every tau.

#include <cstdint>
#include <span>

#include "allan_stream_noise.hpp"
#include "allan_stream_terms.hpp"
#include "sigmatau/allan_curve.hpp"

namespace sigmatau::detail {

/// The state of a stream at the end of its data, as the curves need it.
struct StreamTotals {
  DataKind kind;
  double tau0_s;                                ///< sample interval [s]
  std::int64_t points;                          ///< N, phase points
  std::span<const StridedTerms> taus;           ///< every statistic and factor, terms finished
  std::span<const std::int64_t> noise_factors;  ///< ascending distinct m
  std::span<const NoiseSums> noise;             ///< the noise state of each of them
  double value_scale = 1.0;  ///< the values were processed divided by this power of two
};

/// The curve of `statistic`: at each of its taus with terms, the deviation (SP 1065
/// normalisation of the mean square), the noise type (the one at kept_noise_factor once few
/// averages remain, as compute_allan_curve), the strided EDF and the interval at `confidence_level`.
AllanCurve stream_curve(Statistic statistic, const StreamTotals& totals, double confidence_level);

}  // namespace sigmatau::detail
