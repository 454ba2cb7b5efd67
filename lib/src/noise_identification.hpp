#pragma once
// Internal: the lag-1 autocorrelation noise identification of confidence.cpp on a caller's
// buffer, so that the out-of-core path (allan_out_of_core.cpp) can hold the averaged series in
// spilled storage and still identify exactly as the in-memory path does.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "sigmatau/confidence.hpp"
#include "sigmatau/phase_series.hpp"

namespace sigmatau::detail {

/// Fewest points of the averaged series z for the lag-1 ACF method; below it confidence.cpp
/// uses the B1 ratio (Riley & Greenhall 2004 and Stable32: "at least 30 analysis points").
inline constexpr std::int64_t kMinAcfPoints = 30;

/// Number of points of z at averaging factor m: phase decimated by m (phase input), or rate
/// averaged over the complete non-overlapping blocks of m samples. 1 <= m < series.size().
std::int64_t averaged_series_points(const PhaseSeries& series, std::int64_t m);

/// Writes z (averaged_series_points values) to out.
void fill_averaged_series(const PhaseSeries& series, std::int64_t m, double* out);

/// identify_noise (1 <= m < series.size()) with the averaged series written to `scratch`,
/// which must hold averaged_series_points(series, m) doubles when that is >= kMinAcfPoints (it
/// is not touched otherwise): the taus of a curve share one buffer instead of allocating and
/// zeroing one each.
NoiseIdentification identify_noise_with(const PhaseSeries& series, Statistic statistic,
                                        std::int64_t m, double* scratch);

/// The lag-1 ACF identification of z[0..n), n >= kMinAcfPoints, which it overwrites (z is
/// differenced in place). Method lag1_acf, or assumed (alpha 0) for a constant series; alpha
/// clamped to the range the statistic can resolve.
NoiseIdentification identify_noise_by_acf(double* z, std::size_t n, bool phase_input,
                                          Statistic statistic);

/// For each factor of m: the alpha, before clamping, that identify_noise_by_acf finds on the
/// averaged series at that factor, when this one pass over the phase can tell it for certain
/// (the identification ends after at most one difference and r1 is clear of every decision
/// boundary: acf_first_steps.cpp); nullopt where it cannot, where the series has fewer than
/// kMinAcfPoints points, and for a spilled phase. The statistic only clamps the alpha (its
/// differencing limit is >= 2), so one call serves every statistic.
std::vector<std::optional<int>> acf_first_steps(const PhaseSeries& series,
                                                std::span<const std::int64_t> m);

/// The identification identify_noise_by_acf returns for an unclamped alpha: method lag1_acf,
/// alpha clamped to the range the statistic resolves.
NoiseIdentification acf_identification(int alpha, Statistic statistic);

}  // namespace sigmatau::detail
