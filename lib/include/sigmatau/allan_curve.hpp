#pragma once
/// \file allan_curve.hpp
/// A deviation curve with confidence intervals: the estimate stage's output, consumed by the
/// fit, the plots and the reports. Composes allan.hpp (values) and confidence.hpp (intervals).

#include <cstdint>
#include <vector>

#include "sigmatau/allan.hpp"
#include "sigmatau/confidence.hpp"
#include "sigmatau/phase_series.hpp"
#include "sigmatau/taus.hpp"

namespace sigmatau {

/// TOTVAR bias B = E[TOTVAR] / AVAR = 1 - a tau/T for the identified noise alpha (NIST SP 1065
/// sec. 5.2.11): a = 0 for white FM and PM noise, 1/(3 ln 2) for flicker FM, 3/4 for random-walk
/// FM. T is the record length as Stable32 takes it: (number of data points) x tau0, i.e. M tau0
/// for rate or increment input and N tau0 for phase input.
double totvar_bias(int alpha, std::int64_t m, const PhaseSeries& series);

/// The record length in data points as Stable32 counts it: M for rate or increment input, N for
/// phase input (used by totvar_bias and by TOTDEV's EDF).
std::int64_t record_points(const PhaseSeries& series);

/// Averages K = floor((N-1)/m) at or below which compute_allan_curve does not identify the noise
/// at m but takes the type identified at kept_noise_factor (Stable32's convention): 9 for adev
/// and hdev, 3 for totdev, 7 otherwise.
std::int64_t kept_noise_threshold(Statistic statistic);

/// The averaging factor whose noise type is used at m where K <= kept_noise_threshold: the
/// largest factor of m's grid with floor((N-1)/factor) above the threshold (1 if none), N the
/// phase points. m's grid is Stable32's decade grid (1, 2, 4, 10, 20, 40, 100, ...) for m >= 10
/// on it, else the octave grid (powers of two). Stable32 keeps the type of the previous tau of
/// its run, which on octave and decade runs is this factor (every Stable32 table in
/// ../shared/data agrees); depending on the record and m alone, the type at one tau does not
/// depend on which other taus were asked for (1024 alone and 512 with 1024 give 1024 one type).
std::int64_t kept_noise_factor(Statistic statistic, std::int64_t phase_points, std::int64_t m);

/// One point: the deviation and its confidence interval (in the series' rate unit; TDEV in its
/// phase unit).
struct CurvePoint {
  DeviationPoint value;
  ConfidencePoint confidence;
};

/// One statistic of one series at every averaging factor that has terms, with intervals.
struct AllanCurve {
  Statistic statistic = Statistic::oadev;  ///< which deviation the points hold
  double confidence_level = 0.683;  ///< two-sided probability of the intervals
  std::vector<CurvePoint> points;   ///< in increasing tau
};

/// The statistic at the averaging factors of `taus`, with intervals at `confidence_level`
/// (in (0, 1); Error otherwise). Averaging factors with no terms are left out.
/// Stable32's conventions are followed: TOTDEV is divided by sqrt(totvar_bias) with the noise
/// identified at that tau, and once few averages remain the type identified at
/// kept_noise_factor is used (NoiseIdentification::Method::kept).
AllanCurve compute_allan_curve(const PhaseSeries& series, Statistic statistic,
                               const TauSpec& taus, double confidence_level,
                               EdfModel edf_model = EdfModel::greenhall);

/// Several statistics for several channels; (channel, statistic) pairs are spread over
/// `threads` worker threads (0: one per hardware core). Result: [channel][statistic], in the
/// order given.
std::vector<std::vector<AllanCurve>> compute_allan_curves(
    const std::vector<PhaseSeries>& channels, const std::vector<Statistic>& statistics,
    const TauSpec& taus, double confidence_level, unsigned threads = 0,
    EdfModel edf_model = EdfModel::greenhall);

/// Points whose identified noise type differs by 2 or more from both neighbours, the two
/// neighbours agreeing (white PM at one tau between white FM on either side). Power-law noise
/// changes type gradually along a curve; an isolated jump is usually a periodic component (a
/// spectral line) that the lag-1 autocorrelation reads as another noise type, and the point's
/// EDF, hence its interval, follows the type read (44x the neighbours' EDF on the HiPNUC CH104
/// log's gyro at 2.56 s, a 0.2 Hz line). Indices into curve.points; the first and last points
/// are never flagged.
std::vector<std::size_t> isolated_noise_types(const AllanCurve& curve);

/// True when every deviation of the curve is 0 (also for a curve without points): the input
/// never changed (a stuck sensor, precision lost, or a column that is not a signal), so the
/// curve says nothing about noise.
bool all_deviations_zero(const AllanCurve& curve);

}  // namespace sigmatau
