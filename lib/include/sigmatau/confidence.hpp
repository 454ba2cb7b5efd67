#pragma once
/// \file confidence.hpp
/// Confidence intervals for Allan-family deviations: power-law noise identification, equivalent
/// degrees of freedom and chi-squared bounds.
///
/// References:
///  - W. J. Riley, C. A. Greenhall, "Power law noise identification using the lag 1
///    autocorrelation", 18th EFTF, 2004 (lag-1 ACF method).
///  - D. W. Allan, J. A. Barnes, B1 bias function (Barnes 1974), and NIST SP 1065 sec. 5.6
///    (B1 ratio and R(n) methods, used when too few points remain for the ACF).
///  - C. A. Greenhall, W. J. Riley, "Uncertainty of stability variances based on finite
///    differences", 35th PTTI, 2003 (EDF algorithm).
///  - NIST SP 1065 Table 7 (TOTDEV EDF b T/tau - c, with D. A. Howe's three-digit b and c, as
///    Stable32 uses them), eq. (45) (chi-squared interval).
///
/// alpha is the exponent of the fractional-frequency (rate) PSD S_y(f) ~ f^alpha:
///  +2 white PM (quantization), +1 flicker PM, 0 white FM (angle random walk),
///  -1 flicker FM (bias instability), -2 random-walk FM (rate random walk).

#include <cstdint>

#include "sigmatau/allan.hpp"
#include "sigmatau/phase_series.hpp"
#include "sigmatau/units.hpp"

namespace sigmatau {

/// Identified power-law noise at one averaging factor.
struct NoiseIdentification {
  int alpha = 0;             ///< integer exponent in [-2, 2]
  /// kept: too few averages for a reliable estimate at this tau, so the noise type identified
  /// at a shorter tau that depends on the record alone (kept_noise_factor in allan_curve.hpp) is
  /// used, as Stable32 keeps its previous tau's type on an octave run (compute_allan_curve).
  enum class Method { lag1_acf, b1_ratio, assumed, kept } method = Method::lag1_acf;
};

/// Identifies the dominant power-law noise at averaging factor m the way Stable32 does: lag-1
/// autocorrelation of the series averaged (rate) or decimated (phase) to m, differenced until
/// the lag-1 ACF is below 0.25 (needs at least ~30 points); the B1 ratio (with R(n) to separate
/// white and flicker PM) where fewer points remain. The statistic matters for mdev/tdev/hdev
/// (see Stable32 "Noise identification").
NoiseIdentification identify_noise(const PhaseSeries& series, Statistic statistic,
                                   std::int64_t m);

/// Greenhall's EDF for a variance of difference order d (2 Allan, 3 Hadamard), modified (F = 1)
/// or not (F = m), overlapping (S = m) or not (S = 1), at averaging factor m on N phase points.
/// Returns NaN when the arguments are outside the algorithm's domain.
double greenhall_edf(int alpha, int d, std::int64_t m, std::int64_t F, std::int64_t S,
                     std::int64_t n_phase_points);

/// EDF of one statistic at averaging factor m: Greenhall for adev/oadev/mdev/tdev/hdev/ohdev,
/// SP 1065 Table 7 for totdev.
double equivalent_dof(Statistic statistic, int alpha, std::int64_t m,
                      std::int64_t n_phase_points);

/// Exact EDF, 2 E[A]^2 / Var[A], of the statistic's estimator A for Gaussian discrete-time
/// power-law noise: phase with digital spectrum |2 sin(pi f tau0)|^(alpha - 2) (white FM =
/// independent rate samples, random-walk FM = their running sum, flicker = Kasdin's fractional
/// filter), at averaging factor m on N phase points. No tables, no continuous-time model: time
/// and memory O(min(N, 64 k m)) with k = 2..3 (lags of the flicker autocovariance beyond 64 filter
/// spans are left out, < 1e-7 of the variance). NaN for totdev and outside alpha + 2d > 1.
///
/// Differs from equivalent_dof (Greenhall's algorithm, what Stable32 prints): for the unmodified
/// variances Greenhall models each phase sample as the continuous phase averaged over tau0
/// (F = m while m (d+1) <= 100, sampled phase beyond), which for white FM correlates
/// neighbouring rate samples (lag-1 correlation 1/4). OADEV at m = 1, white FM: Greenhall
/// ~ 18/23 (N - 2), exact 2 n^2 / (3 n - 1) with n = N - 2, ~ 2/3 (N - 2). Measured at N = 65537:
/// +10..+25 % (-24 % random-walk FM) at m = 1; OADEV/OHDEV white FM -3..-12 % for m = 2..16 and
/// within 0.1 % once Greenhall samples the phase (m >= 34 for d = 2); ADEV/HDEV within 2 % from
/// m = 8; OADEV/OHDEV flicker PM 11..16 % below exact at all m (a noise whose variance depends
/// on the sampling bandwidth); white PM identical (tests/test_edf_exact.cpp).
double discrete_edf(Statistic statistic, int alpha, std::int64_t m, std::int64_t n_phase_points);

/// EDF model for equivalent_dof.
enum class EdfModel {
  /// Greenhall & Riley 2003 throughout, as Stable32 prints it (the library's default; the CLI
  /// chooses by the data, default_edf_model).
  greenhall,
  /// discrete_edf while m (d + 1) <= 100, the range where Greenhall models each phase sample as
  /// averaged over tau0 (there discrete_edf costs at most ~2e4 lags); Greenhall beyond, where it
  /// samples the phase and agrees with discrete_edf within 1 % except for flicker PM.
  discrete,
};

/// The EDF model for data of `kind` whose values are in a unit of dimension `unit`:
/// EdfModel::discrete for sampled inertial sensors, whose noise is discrete (independent rate
/// samples for white noise, their running sum for a random walk: bench/results_edf_coverage.md
/// shows Greenhall's intervals miss or overshoot their level there at the shortest taus), i.e.
/// an angular rate or acceleration for rate input, an angle or velocity for increments and phase
/// (an integrated angle), or raw counts; EdfModel::greenhall otherwise: clock data (fractional
/// frequency, phase in s), as Stable32 prints them, and values of unknown unit
/// (dim::dimensionless with no unit given).
EdfModel default_edf_model(DataKind kind, const Dimension& unit);

/// equivalent_dof with a choice of model; EdfModel::greenhall gives equivalent_dof(statistic,
/// alpha, m, n_phase_points). TOTDEV always uses SP 1065 Table 7.
double equivalent_dof(Statistic statistic, int alpha, std::int64_t m, std::int64_t n_phase_points,
                      EdfModel model);

/// Chi-squared confidence bounds for a deviation `dev` with `edf` degrees of freedom at two-sided
/// confidence `confidence` (e.g. 0.683): sigma^2 edf / chi2_{(1+p)/2}(edf) and
/// sigma^2 edf / chi2_{(1-p)/2}(edf) (SP 1065 eq. 45), returned as deviations.
struct Interval {
  double low = 0;
  double high = 0;
};
Interval chi_squared_interval(double dev, double edf, double confidence);

/// Everything above for one point: identified alpha, EDF and the interval at `confidence`.
struct ConfidencePoint {
  NoiseIdentification noise;
  double edf = 0;
  Interval interval;
};
ConfidencePoint confidence_for(const PhaseSeries& series, Statistic statistic,
                               const DeviationPoint& point, double confidence);

}  // namespace sigmatau
