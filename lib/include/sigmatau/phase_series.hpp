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
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sigmatau {

namespace detail {
struct PhaseStore;  // lib/src/phase_store.hpp
}

/// What the numbers in a log mean.
enum class DataKind {
  rate,       ///< angular rate or specific force, e.g. rad/s, m/s^2 (or clock fractional frequency)
  increment,  ///< delta angle / delta velocity per sample, e.g. rad, m/s
  phase,      ///< integrated angle, or clock phase (time error) in s
};

/// "rate" | "increment" | "phase"; throws sigmatau::Error otherwise.
DataKind parse_data_kind(std::string_view text);
std::string_view to_string(DataKind kind);

/// Where a phase series keeps its points (16 bytes each, plus 8 bytes each for the copy the
/// overlapping estimators sweep over, made on first use and kept).
struct PhaseStorage {
  /// false: anonymous memory. true: an unlinked temporary file, memory-mapped ("out of core"):
  /// the kernel's page cache holds what fits in RAM, and the process's resident set stays near
  /// resident_bytes whatever the length of the log. Results are identical either way.
  bool spill = false;
  /// Directory of the temporary files; empty: $TMPDIR, else /tmp.
  std::string directory;
  /// Spilled storage: file-backed bytes the process may keep mapped before the mappings are
  /// dropped (their data stays in the file) [bytes]. Process-wide; the last value set applies.
  std::int64_t resident_bytes = std::int64_t{256} << 20;
};

/// PhaseStorage with spill = true and the other fields at their defaults.
inline PhaseStorage spilled_storage() {
  PhaseStorage storage;
  storage.spill = true;
  return storage;
}

/// A channel in phase form, double-double (see the file comment). Copies share the (immutable)
/// storage.
class PhaseSeries {
 public:
  /// From rate samples y_1..y_M taken every tau0_s seconds. Throws Error if tau0_s is not a
  /// finite number > 0, or naming the first sample (0-based index) that is not finite.
  static PhaseSeries from_rate(std::span<const double> y, double tau0_s,
                               const PhaseStorage& storage = {});
  /// From increments (per-sample delta angle or delta velocity); the phase is their running sum.
  static PhaseSeries from_increments(std::span<const double> increments, double tau0_s,
                                     const PhaseStorage& storage = {});
  /// From phase points x_0..x_{N-1} (angle, or time error in s).
  static PhaseSeries from_phase(std::span<const double> x, double tau0_s,
                                const PhaseStorage& storage = {});
  /// Dispatches on kind to one of the three constructors above.
  static PhaseSeries from_samples(std::span<const double> values, DataKind kind, double tau0_s,
                                  const PhaseStorage& storage = {});

  /// Number of phase points N (M + 1 for rate and increment input).
  std::int64_t size() const { return size_; }
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
  std::span<const double> hi() const { return {hi_, static_cast<std::size_t>(size_)}; }
  std::span<const double> lo() const { return {lo_, static_cast<std::size_t>(size_)}; }
  /// Whether the points live in a temporary file (PhaseStorage::spill).
  bool spilled() const;
  /// Frees the cached sweep copy of the phase (8 bytes per point; rebuilt on the next use).
  void drop_sweep_cache() const;
  /// Hands the series memory it may keep for its sweep copy (typically the samples it was built
  /// from, no longer needed: their values are overwritten): used, instead of fresh pages, when
  /// its capacity holds size() doubles and the copy is not built yet; else freed at once.
  void recycle(std::vector<double>&& memory) const;
  /// Internal (lib/src): the storage and its caches.
  detail::PhaseStore& store() const { return *store_; }

 private:
  friend class PhaseSeriesBuilder;
  PhaseSeries(DataKind kind, double tau0_s) : kind_(kind), tau0_s_(tau0_s) {}
  DataKind kind_;
  double tau0_s_;
  double mean_rate_ = 0.0;
  std::shared_ptr<detail::PhaseStore> store_;
  const double* hi_ = nullptr;
  const double* lo_ = nullptr;
  std::int64_t size_ = 0;
};

/// Builds a PhaseSeries from samples delivered in blocks, in two passes over the same values
/// (for logs that do not fit in memory: read the file twice). Pass 1 (scan) counts the samples,
/// checks that they are finite and, for rate and increment data, computes their mean; pass 2
/// (append) integrates them into the storage. The result is bit-identical to
/// PhaseSeries::from_samples on the whole array, whatever the block sizes.
class PhaseSeriesBuilder {
 public:
  explicit PhaseSeriesBuilder(DataKind kind, PhaseStorage storage = {});
  ~PhaseSeriesBuilder();
  PhaseSeriesBuilder(PhaseSeriesBuilder&&) noexcept;
  PhaseSeriesBuilder& operator=(PhaseSeriesBuilder&&) noexcept;

  /// Pass 1: the next values. Throws Error naming the first non-finite sample (0-based index in
  /// the whole log).
  void scan(std::span<const double> values);
  /// Pass 2: the same values again, in the same order (the first call ends pass 1 and allocates
  /// the storage). Throws Error if more values arrive than pass 1 saw.
  void append(std::span<const double> values);
  /// The series, with sample interval tau0_s [s]. Throws Error if pass 2 delivered fewer values
  /// than pass 1, or if tau0_s is not a finite number > 0. The builder may then be reused.
  PhaseSeries finish(double tau0_s);
  /// Samples seen by pass 1 so far.
  std::int64_t samples() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace sigmatau
