#pragma once
// adev: an explicit --taus list with several statistics (e.g. --stat totdev,oadev --taus
// 32,256 on a log where OADEV stops at 250 s): each statistic computes the asked taus it can
// reach, the skipped ones are noted on stderr, and a tau that no statistic reaches stays an
// Error (exit 2).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "sigmatau/allan_curve.hpp"
#include "sigmatau/phase_series.hpp"
#include "sigmatau/taus.hpp"

namespace sigmatau::cli {

/// Per statistic, `taus` with the explicit seconds it cannot reach on `n_phase_points` (of
/// interval tau0_s [s], input of `kind`: the stop ratios count phase points or samples) left out
/// and noted on stderr (naming `input`); a tau no statistic reaches stays in every list, so
/// averaging_factors reports it. Non-explicit specs and a single statistic: `taus` for each,
/// unchanged.
std::vector<TauSpec> taus_per_statistic(const TauSpec& taus, const std::vector<Statistic>& stats,
                                        std::int64_t n_phase_points, double tau0_s,
                                        DataKind kind, const std::string& input);

/// Stream mode: the same note from the curves (the length is known only at the end), for the
/// asked taus missing from a statistic's curve; Error for an asked tau in no curve. rate_hz [Hz].
void note_stream_skipped(const TauSpec& taus, const std::vector<Statistic>& stats,
                         const std::vector<std::vector<AllanCurve>>& curves, double rate_hz,
                         const std::string& input);

/// Computes the curves of `stats` at their `specs` (one per statistic, from
/// taus_per_statistic) with `compute(statistics, taus)` (curves[channel][statistic] of those):
/// one call when every statistic has the same taus, else one per statistic, merged. Returns
/// curves[channel][statistic].
using CurveComputer = std::function<std::vector<std::vector<AllanCurve>>(
    const std::vector<Statistic>&, const TauSpec&)>;
std::vector<std::vector<AllanCurve>> curves_for_specs(const std::vector<TauSpec>& specs,
                                                      const std::vector<Statistic>& stats,
                                                      const CurveComputer& compute);

/// compute_allan_curves with the taus of taus_per_statistic (curves_for_specs). Returns
/// curves[channel][statistic].
std::vector<std::vector<AllanCurve>> curves_per_statistic(const std::vector<PhaseSeries>& series,
                                                          const std::vector<Statistic>& stats,
                                                          const TauSpec& taus, double ci,
                                                          unsigned threads, EdfModel edf_model,
                                                          const std::string& input);

}  // namespace sigmatau::cli
