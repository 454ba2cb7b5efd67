#pragma once
// Internal: the one place where deviations, noise identification, EDF and intervals are put
// together into an AllanCurve; the in-memory and out-of-core paths differ only in how they
// identify the noise.

#include <cstdint>
#include <functional>

#include "sigmatau/allan_curve.hpp"

namespace sigmatau::detail {

/// Throws Error unless the deviation of `point` is finite: a deviation beyond the largest double
/// (about 1.8e308) is not representable, whatever the scaling inside (values that large for
/// their sample interval: another unit is the remedy).
void check_representable(Statistic statistic, const DeviationPoint& point);

/// Whether m >= 10 is on Stable32's decade grid 1, 2, 4, 10, 20, 40, 100, ... (the grid whose
/// factors kept_noise_factor takes for such an m; the octave grid otherwise).
bool on_decade_grid(std::int64_t m);

/// compute_allan_curve with the noise at averaging factor m identified by identify(m) (called
/// at kept_noise_factor instead where few averages remain) and the EDF from `edf_model`; the
/// deviations computed on up to `threads` threads (compute_deviation).
AllanCurve assemble_allan_curve(const PhaseSeries& series, Statistic statistic,
                                const TauSpec& taus, double confidence_level, EdfModel edf_model,
                                const std::function<NoiseIdentification(std::int64_t)>& identify,
                                unsigned threads = 1);

}  // namespace sigmatau::detail
