#pragma once
// Internal: the one place where deviations, noise identification, EDF and intervals are put
// together into an AllanCurve; the in-memory and out-of-core paths differ only in how they
// identify the noise.

#include <cstdint>
#include <functional>

#include "sigmatau/allan_curve.hpp"

namespace sigmatau::detail {

/// compute_allan_curve with the noise at averaging factor m identified by identify(m) (before
/// the curve-level rule that keeps the previous tau's type once few averages remain) and the
/// EDF from `edf_model`.
AllanCurve assemble_allan_curve(const PhaseSeries& series, Statistic statistic,
                                const TauSpec& taus, double confidence_level, EdfModel edf_model,
                                const std::function<NoiseIdentification(std::int64_t)>& identify);

}  // namespace sigmatau::detail
