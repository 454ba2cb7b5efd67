// Plausibility checks on channels in memory (see sigmatau/data_checks.hpp for the thresholds and
// their reasons).
//
// Glossary: run = maximal sequence of consecutive equal values; raw = value as written in the
// file = SI value / to_si; f = a candidate unit's factor to SI.
#include "sigmatau/data_checks.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <sstream>

#include "sigmatau/error.hpp"
#include "sigmatau/units.hpp"

namespace sigmatau {
namespace {

/// Largest plausible mean rate of a static gyro [rad/s]: see data_checks.hpp.
constexpr double kMaxStaticGyroRate = 0.5;
/// Plausible band of a static accelerometer's mean norm [g]: see data_checks.hpp.
constexpr double kAccelNormLow = 0.75;
constexpr double kAccelNormHigh = 1.25;
/// Two factors within this relative distance are the same unit (deg/s typed two ways).
constexpr double kSameFactor = 1e-9;

/// The units a mislabelled channel is most likely in, by name: their factors come from
/// units.hpp (parse_unit), as every other unit's.
constexpr const char* kRateUnits[] = {"rad/s", "deg/s", "mrad/s", "deg/h"};
constexpr const char* kAccelUnits[] = {"m/s^2", "g", "mg", "ft/s^2"};

std::string format_value(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

DataWarning make_warning(DataWarningKind kind, std::string channel, double value) {
  DataWarning w;
  w.kind = kind;
  w.channel = std::move(channel);
  w.value = value;
  return w;
}

/// Calls `on_run(start, length, value)` for every run of finite equal values of >= min_run.
template <class OnRun>
void for_each_run(std::span<const double> x, std::int64_t min_run, OnRun on_run) {
  const auto n = static_cast<std::int64_t>(x.size());
  std::int64_t i = 0;
  while (i < n) {
    std::int64_t j = i + 1;
    const double v = x[static_cast<std::size_t>(i)];
    while (j < n && x[static_cast<std::size_t>(j)] == v) ++j;  // NaN != NaN: never a run
    if (j - i >= min_run) on_run(i, j - i, v);
    i = j;
  }
}

void add_run(DataWarning& w, std::int64_t start, std::int64_t length) {
  if (w.runs == 0) {
    w.first_row = start;
    w.first_rows = length;
  }
  if (length > w.longest_rows) {
    w.longest_row = start;
    w.longest_rows = length;
  }
  ++w.runs;
  w.rows_flagged += length;
}

std::string run_summary(const DataWarning& w, std::int64_t min_run) {
  std::string s = w.channel + ": " + std::to_string(w.runs) + (w.runs == 1 ? " run" : " runs") +
                  " of >= " + std::to_string(min_run) + " identical samples";
  return s;
}

std::string run_location(const DataWarning& w) {
  std::string s = ", first at row " + std::to_string(w.first_row) + " (" +
                  std::to_string(w.first_rows) + " rows)";
  if (w.runs > 1) {
    s += ", longest at row " + std::to_string(w.longest_row) + " (" +
         std::to_string(w.longest_rows) + " rows); " + std::to_string(w.rows_flagged) +
         " rows in all";
  }
  return s;
}

void check_min_run(std::int64_t min_run, const char* what) {
  if (!(min_run >= 2)) {
    throw Error(std::string(what) + " run threshold must be >= 2 rows, got " +
                std::to_string(min_run));
  }
}

/// Checks 1..max_axes equal-length non-empty axes; returns the per-axis means of the raw values.
std::vector<double> raw_means(const std::vector<std::span<const double>>& axes,
                              const std::vector<std::string>& names, double to_si,
                              std::size_t min_axes, std::size_t max_axes, const char* what) {
  if (!(axes.size() >= min_axes && axes.size() <= max_axes) || names.size() != axes.size()) {
    throw Error(std::string(what) + " unit check: needs " + std::to_string(min_axes) + ".." +
                std::to_string(max_axes) + " axes with one name each, got " +
                std::to_string(axes.size()) + " axes and " + std::to_string(names.size()) +
                " names");
  }
  if (!(to_si > 0 && std::isfinite(to_si))) {
    throw Error(std::string(what) + " unit check: the unit factor must be > 0");
  }
  std::vector<double> means;
  for (const auto& a : axes) {
    if (a.empty() || a.size() != axes[0].size()) {
      throw Error(std::string(what) + " unit check: the axes must be non-empty and equally long");
    }
    double sum = 0;
    for (const double v : a) sum += v;
    means.push_back(sum / static_cast<double>(a.size()) / to_si);
  }
  return means;
}

/// Validates the inputs of the *_sums unit checks (see raw_means for the in-memory ones).
void check_sums(std::size_t axes, const std::vector<std::string>& names, std::int64_t rows,
                double to_si, std::size_t min_axes, std::size_t max_axes, const char* what) {
  if (!(axes >= min_axes && axes <= max_axes) || names.size() != axes) {
    throw Error(std::string(what) + " unit check: needs " + std::to_string(min_axes) + ".." +
                std::to_string(max_axes) + " axes with one name each, got " +
                std::to_string(axes) + " axes and " + std::to_string(names.size()) + " names");
  }
  if (!(to_si > 0 && std::isfinite(to_si))) {
    throw Error(std::string(what) + " unit check: the unit factor must be > 0");
  }
  if (!(rows >= 1)) throw Error(std::string(what) + " unit check: the axes must be non-empty");
}

std::string join_names(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : "+") + n;
  return s;
}

/// The first candidate unit (other than the declared one), nearest the declared factor in
/// log scale, for which raw * f is plausible.
template <std::size_t N, class Plausible>
std::string likely_unit(const char* const (&names)[N], double to_si, double raw,
                        Plausible plausible) {
  std::vector<std::pair<const char*, double>> order;  // name, factor to SI
  for (const char* name : names) {
    const double f = parse_unit(name).factor;
    if (std::abs(f / to_si - 1.0) > kSameFactor) order.emplace_back(name, f);
  }
  std::stable_sort(order.begin(), order.end(), [&](const auto& a, const auto& b) {
    return std::abs(std::log(a.second / to_si)) < std::abs(std::log(b.second / to_si));
  });
  for (const auto& [name, f] : order) {
    if (plausible(raw * f)) return name;
  }
  return "";
}

}  // namespace

std::string to_string(DataWarningKind kind) {
  switch (kind) {
    case DataWarningKind::saturation:
      return "saturation";
    case DataWarningKind::stuck:
      return "stuck";
    case DataWarningKind::unit:
      return "unit";
    case DataWarningKind::outlier:
      return "outlier";
  }
  return "unknown";
}

namespace {

/// The least and greatest finite values (INFINITY and -INFINITY when there are none), the
/// values a front-to-back std::min / std::max scan keeps. Four independent lanes, since one
/// chain of min and max was most of the saturation check's time; a value equal to another is
/// the same double except for -0.0 and +0.0, where the scan keeps the first seen: a zero bound
/// is found again by the plain scan.
std::pair<double, double> finite_range(std::span<const double> values) {
  const auto scan = [&] {
    double lo = INFINITY;
    double hi = -INFINITY;
    for (const double v : values) {
      if (!std::isfinite(v)) continue;
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    return std::pair{lo, hi};
  };
  constexpr std::size_t kLanes = 4;
  double lo[kLanes] = {INFINITY, INFINITY, INFINITY, INFINITY};
  double hi[kLanes] = {-INFINITY, -INFINITY, -INFINITY, -INFINITY};
  const std::size_t n = values.size();
  std::size_t i = 0;
  for (; i + kLanes <= n; i += kLanes) {
    for (std::size_t k = 0; k < kLanes; ++k) {
      const double v = values[i + k];
      const bool finite = std::isfinite(v);
      lo[k] = std::min(lo[k], finite ? v : INFINITY);
      hi[k] = std::max(hi[k], finite ? v : -INFINITY);
    }
  }
  for (; i < n; ++i) {
    const double v = values[i];
    if (!std::isfinite(v)) continue;
    lo[0] = std::min(lo[0], v);
    hi[0] = std::max(hi[0], v);
  }
  for (std::size_t k = 1; k < kLanes; ++k) {
    lo[0] = std::min(lo[0], lo[k]);
    hi[0] = std::max(hi[0], hi[k]);
  }
  if (lo[0] == 0 || hi[0] == 0) return scan();
  return {lo[0], hi[0]};
}

/// Adds saturation's run (at lo, at hi, or both) to its warnings.
void add_saturation_run(DataWarning& at_lo, DataWarning& at_hi, std::int64_t start,
                        std::int64_t length, double v) {
  if (v == at_lo.value) add_run(at_lo, start, length);
  if (v == at_hi.value) add_run(at_hi, start, length);
}

void finish_saturation(DataWarning& at_lo, DataWarning& at_hi, const DataCheckOptions& options,
                       std::vector<DataWarning>& out) {
  for (DataWarning* w : {&at_lo, &at_hi}) {
    if (w->runs == 0) continue;
    w->message = run_summary(*w, options.saturation_min_run) + " at the channel " +
                 (w == &at_lo ? "minimum " : "maximum ") + format_value(w->value) +
                 " (saturation: the signal was clipped at the sensor's range)" + run_location(*w);
    out.push_back(std::move(*w));
  }
}

void add_stuck_run(DataWarning& w, std::int64_t start, std::int64_t length, double v) {
  if (w.runs == 0 || length > w.longest_rows) w.value = v;
  add_run(w, start, length);
}

std::optional<DataWarning> finish_stuck(DataWarning& w, const DataCheckOptions& options) {
  if (w.runs == 0) return std::nullopt;
  w.message = run_summary(w, options.stuck_min_run) + " (stuck sensor?), longest value " +
              format_value(w.value) + run_location(w);
  return std::move(w);
}

}  // namespace

std::vector<DataWarning> check_saturation(std::span<const double> values,
                                          const std::string& channel,
                                          const DataCheckOptions& options) {
  check_min_run(options.saturation_min_run, "saturation");
  std::vector<DataWarning> out;
  const auto [lo, hi] = finite_range(values);
  if (!(lo < hi)) return out;  // empty, all non-finite, or constant
  DataWarning at_lo = make_warning(DataWarningKind::saturation, channel, lo);
  DataWarning at_hi = make_warning(DataWarningKind::saturation, channel, hi);
  for_each_run(values, options.saturation_min_run, [&](std::int64_t s, std::int64_t n, double v) {
    add_saturation_run(at_lo, at_hi, s, n, v);
  });
  finish_saturation(at_lo, at_hi, options, out);
  return out;
}

std::optional<DataWarning> check_stuck(std::span<const double> values, const std::string& channel,
                                       const DataCheckOptions& options) {
  check_min_run(options.stuck_min_run, "stuck-sensor");
  DataWarning w = make_warning(DataWarningKind::stuck, channel, 0.0);
  for_each_run(values, options.stuck_min_run,
               [&](std::int64_t s, std::int64_t n, double v) { add_stuck_run(w, s, n, v); });
  return finish_stuck(w, options);
}

std::vector<DataWarning> check_runs(std::span<const double> values, const std::string& channel,
                                    const DataCheckOptions& options) {
  // check_saturation then check_stuck, in one pass over the runs: both look at the same maximal
  // runs, each keeping those of its own length.
  check_min_run(options.saturation_min_run, "saturation");
  check_min_run(options.stuck_min_run, "stuck-sensor");
  std::vector<DataWarning> out;
  const auto [lo, hi] = finite_range(values);
  const bool saturation = lo < hi;  // otherwise empty, all non-finite, or constant
  DataWarning at_lo = make_warning(DataWarningKind::saturation, channel, lo);
  DataWarning at_hi = make_warning(DataWarningKind::saturation, channel, hi);
  DataWarning stuck = make_warning(DataWarningKind::stuck, channel, 0.0);
  const std::int64_t shortest =
      saturation ? std::min(options.saturation_min_run, options.stuck_min_run)
                 : options.stuck_min_run;
  for_each_run(values, shortest, [&](std::int64_t s, std::int64_t n, double v) {
    if (saturation && n >= options.saturation_min_run) add_saturation_run(at_lo, at_hi, s, n, v);
    if (n >= options.stuck_min_run) add_stuck_run(stuck, s, n, v);
  });
  if (saturation) finish_saturation(at_lo, at_hi, options, out);
  if (auto w = finish_stuck(stuck, options)) out.push_back(std::move(*w));
  return out;
}

std::optional<double> whole_run_value(const std::vector<DataWarning>& run_warnings,
                                      std::int64_t rows) {
  for (const DataWarning& w : run_warnings) {
    if (w.kind == DataWarningKind::stuck && w.longest_rows == rows) return w.value;
  }
  return std::nullopt;
}

std::string constant_channel_text(const std::string& channel, const std::string& how) {
  return "channel " + channel + " is constant (" + how +
         "): a stuck sensor, or precision lost (e.g. a large offset stored as float32)";
}

std::optional<DataWarning> check_gyro_unit(const std::vector<std::span<const double>>& axes_si,
                                           const std::vector<std::string>& names,
                                           const std::string& declared_unit, double to_si) {
  raw_means(axes_si, names, to_si, 1, 3, "gyro");  // validates
  std::vector<double> sums;
  for (const auto& a : axes_si) {
    double sum = 0;
    for (const double v : a) sum += v;
    sums.push_back(sum);
  }
  return check_gyro_unit_sums(sums, static_cast<std::int64_t>(axes_si[0].size()), names,
                              declared_unit, to_si);
}

std::optional<DataWarning> check_gyro_unit_sums(const std::vector<double>& sums_si,
                                                std::int64_t rows,
                                                const std::vector<std::string>& names,
                                                const std::string& declared_unit, double to_si) {
  check_sums(sums_si.size(), names, rows, to_si, 1, 3, "gyro");
  double raw = 0;
  for (const double s : sums_si) {
    const double m = s / static_cast<double>(rows) / to_si;
    raw += m * m;
  }
  raw = std::sqrt(raw);
  const double si = raw * to_si;
  if (!(si > kMaxStaticGyroRate)) return std::nullopt;  // NaN means cannot be judged: no warning
  DataWarning w = make_warning(DataWarningKind::unit, join_names(names), si);
  const auto plausible = [](double rate) { return rate <= kMaxStaticGyroRate; };
  w.likely_unit = likely_unit(kRateUnits, to_si, raw, plausible);
  if (w.likely_unit.empty()) w.likely_unit = "raw counts (LSB)";
  w.message = w.channel + ": a static gyro reading a mean rate of " + format_value(raw) + " " +
              declared_unit + " (" + format_value(si) +
              " rad/s) is implausible (more than " + format_value(kMaxStaticGyroRate) +
              " rad/s); the data look like " + w.likely_unit + ", not " + declared_unit;
  return w;
}

std::optional<DataWarning> check_accel_unit(const std::vector<std::span<const double>>& axes_si,
                                            const std::vector<std::string>& names,
                                            const std::string& declared_unit, double to_si) {
  raw_means(axes_si, names, to_si, 3, 3, "accelerometer");  // validates
  const std::size_t n = axes_si[0].size();
  double sum = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sum += std::hypot(axes_si[0][i], axes_si[1][i], axes_si[2][i]);
  }
  return check_accel_unit_sums(sum, static_cast<std::int64_t>(n), names, declared_unit, to_si);
}

std::optional<DataWarning> check_accel_unit_sums(double norm_sum_si, std::int64_t rows,
                                                 const std::vector<std::string>& names,
                                                 const std::string& declared_unit, double to_si) {
  check_sums(3, names, rows, to_si, 3, 3, "accelerometer");
  const double si = norm_sum_si / static_cast<double>(rows);
  const double in_g = si / kStandardGravity;
  if (in_g >= kAccelNormLow && in_g <= kAccelNormHigh) return std::nullopt;
  if (!std::isfinite(in_g)) return std::nullopt;  // non-finite data are the reader's business
  DataWarning w = make_warning(DataWarningKind::unit, join_names(names), si);
  const auto plausible = [](double a) {
    const double g = a / kStandardGravity;
    return g >= kAccelNormLow && g <= kAccelNormHigh;
  };
  const double raw = si / to_si;
  w.likely_unit = likely_unit(kAccelUnits, to_si, raw, plausible);
  w.message = w.channel + ": a static accelerometer reading a mean norm of " + format_value(raw) +
              " " + declared_unit + " (" + format_value(in_g) + " g) is not near 1 g; " +
              (w.likely_unit.empty() ? std::string("no common unit explains it (is it static?)")
                                     : "the data look like " + w.likely_unit + ", not " +
                                           declared_unit);
  return w;
}

RunChecker::RunChecker(std::string channel, DataCheckOptions options)
    : channel_(std::move(channel)), options_(options), lo_(INFINITY), hi_(-INFINITY) {
  check_min_run(options.saturation_min_run, "saturation");
  check_min_run(options.stuck_min_run, "stuck-sensor");
  at_lo_ = make_warning(DataWarningKind::saturation, channel_, lo_);
  at_hi_ = make_warning(DataWarningKind::saturation, channel_, hi_);
  stuck_ = make_warning(DataWarningKind::stuck, channel_, 0.0);
}

void RunChecker::close_run() {
  const std::int64_t length = row_ - run_start_;
  if (length == 0) return;
  const double v = run_value_;
  // Every value of the run has been seen, so lo_ <= v <= hi_ here; a later, smaller minimum
  // (larger maximum) resets the warning in add().
  if (length >= options_.saturation_min_run) {
    if (v == lo_) add_run(at_lo_, run_start_, length);
    if (v == hi_) add_run(at_hi_, run_start_, length);
  }
  if (length >= options_.stuck_min_run) {
    if (stuck_.runs == 0 || length > stuck_.longest_rows) stuck_.value = v;
    add_run(stuck_, run_start_, length);
  }
}

void RunChecker::add(std::span<const double> values) {
  for (const double x : values) {
    if (row_ == run_start_ || !(x == run_value_)) {  // NaN != NaN: never a run
      close_run();
      run_start_ = row_;
      run_value_ = x;
    }
    if (std::isfinite(x)) {
      if (x < lo_) {
        lo_ = x;
        at_lo_ = make_warning(DataWarningKind::saturation, channel_, lo_);
      }
      if (x > hi_) {
        hi_ = x;
        at_hi_ = make_warning(DataWarningKind::saturation, channel_, hi_);
      }
    }
    ++row_;
  }
}

std::vector<DataWarning> RunChecker::finish() {
  close_run();
  run_start_ = row_;
  std::vector<DataWarning> out;
  if (lo_ < hi_) {  // otherwise empty, all non-finite, or constant: no saturation
    for (DataWarning* w : {&at_lo_, &at_hi_}) {
      if (w->runs == 0) continue;
      w->message = run_summary(*w, options_.saturation_min_run) + " at the channel " +
                   (w == &at_lo_ ? "minimum " : "maximum ") + format_value(w->value) +
                   " (saturation: the signal was clipped at the sensor's range)" +
                   run_location(*w);
      out.push_back(*w);
    }
  }
  if (stuck_.runs > 0) {
    stuck_.message = run_summary(stuck_, options_.stuck_min_run) + " (stuck sensor?), longest value " +
                     format_value(stuck_.value) + run_location(stuck_);
    out.push_back(stuck_);
  }
  return out;
}

}  // namespace sigmatau
