#pragma once
/// \file phase_series.hpp
/// One channel in integrated ("phase") form, the common input of every deviation estimator.
///
/// Notation (NIST SP 1065): rate samples y_1..y_M at interval tau0; phase points x_0..x_{N-1}
/// with N = M + 1 and x_0 = 0, x_k = sum_{i<=k} (y_i - ybar). Removing the mean rate ybar does
/// not change any Allan-family statistic (their differences cancel a linear phase) and keeps the
/// phase small. The phase is held in double-double (hi + lo) so that a window sum
/// x[k+m] - x[k] is accurate to about one ulp of the window sum itself, whatever the length of
/// the log, the offset of the data or the size of the phase (random-walk data).
///
/// Units: for rate data x is in (input unit) x samples, and rate_scale(m) = 1/m turns a phase
/// difference over m samples into the input unit. For increment data (delta angle per sample)
/// and phase data (angle, or clock phase in s) x is in the input unit and rate_scale(m) =
/// 1/(m tau0), so deviations come out in (input unit)/s.

#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

namespace sigmatau {

/// What the numbers in a log mean.
enum class DataKind {
  rate,       ///< angular rate or specific force, e.g. rad/s, m/s^2 (or clock fractional frequency)
  increment,  ///< delta angle / delta velocity per sample, e.g. rad, m/s
  phase,      ///< integrated angle, or clock phase (time error) in s
};

/// "rate" | "increment" | "phase"; throws sigmatau::Error otherwise.
DataKind parse_data_kind(std::string_view text);
std::string_view to_string(DataKind kind);

class PhaseSeries {
 public:
  /// From rate samples y_1..y_M taken every tau0_s seconds. Throws Error if tau0_s is not a
  /// finite number > 0, or naming the first sample (0-based index) that is not finite.
  static PhaseSeries from_rate(std::span<const double> y, double tau0_s);
  /// From increments (per-sample delta angle or delta velocity); the phase is their running sum.
  static PhaseSeries from_increments(std::span<const double> increments, double tau0_s);
  /// From phase points x_0..x_{N-1} (angle, or time error in s).
  static PhaseSeries from_phase(std::span<const double> x, double tau0_s);
  /// Dispatches on kind to one of the three constructors above.
  static PhaseSeries from_samples(std::span<const double> values, DataKind kind, double tau0_s);

  /// Number of phase points N (M + 1 for rate and increment input).
  std::int64_t size() const { return static_cast<std::int64_t>(hi_.size()); }
  /// Sample interval [s].
  double tau0_s() const { return tau0_s_; }
  DataKind kind() const { return kind_; }

  /// x[k + m] - x[k], accurate to ~1 ulp of the result. Requires 0 <= k, k + m < size().
  double window_sum(std::int64_t k, std::int64_t m) const {
    return (hi_[k + m] - hi_[k]) + (lo_[k + m] - lo_[k]);
  }
  /// The phase point x[k] rounded to double (for noise identification and plots).
  double x(std::int64_t k) const { return hi_[k] + lo_[k]; }
  /// Turns a phase difference over m samples into the deviation's unit (see file comment).
  double rate_scale(std::int64_t m) const;
  /// The mean rate removed before integration: in the input unit for rate input, input unit / s
  /// (mean increment / tau0) for increment input, 0 for phase input.
  double mean_rate() const { return mean_rate_; }

  /// Raw double-double storage, for estimators that stream over it.
  std::span<const double> hi() const { return hi_; }
  std::span<const double> lo() const { return lo_; }

 private:
  PhaseSeries(DataKind kind, double tau0_s) : kind_(kind), tau0_s_(tau0_s) {}
  DataKind kind_;
  double tau0_s_;
  double mean_rate_ = 0.0;
  std::vector<double> hi_;
  std::vector<double> lo_;
};

}  // namespace sigmatau
