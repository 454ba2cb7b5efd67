// Outlier (spike) check: fixed blocks by row index, each with its median and a robust sigma from
// a strided sample (see sigmatau/data_checks.hpp, OutlierOptions, for the method and its numbers).
//
// Glossary: m = block median; s = robust sigma; k = threshold [sigma]; window = the rows a
// block's m and s come from (the block itself, or for the last partial block the last
// block_rows rows); sample = every stride-th finite value of the window.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "sigmatau/data_checks.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau {
namespace {

/// Largest sample taken from a window for m and s [values]: 1024 gives s a standard error of
/// 2.8 % on Gaussian noise (q90), and two nth_element on it per 4096 rows cost ~4 ns a row.
constexpr std::size_t kMaxSample = 1024;
/// Fewest rows a channel needs to be checked at all: below this, q90 rests on too few values
/// (its standard error is ~11 % at 64) for a threshold meant to be far in the tail.
constexpr std::int64_t kMinRows = 64;
/// Quantile of |x - m| that gives s, and the standard normal's |z| at that quantile
/// (Phi^-1(0.95) = 1.6448536...), so that s = sigma on Gaussian noise.
constexpr double kScaleQuantile = 0.9;
constexpr double kScaleQuantileZ = 1.6448536269514722;

std::string format_value(double v, const std::string& unit) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  if (!unit.empty()) s << ' ' << unit;
  return s.str();
}

std::string format_sigma(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v;
  return s.str();
}

}  // namespace

OutlierChecker::OutlierChecker(std::string channel, OutlierOptions options, std::string unit,
                               double to_si)
    : channel_(std::move(channel)), options_(options), unit_(std::move(unit)), to_si_(to_si) {
  if (!(options_.block_rows >= kMinRows)) {
    throw Error("outlier check: the block must be >= " + std::to_string(kMinRows) +
                " rows, got " + std::to_string(options_.block_rows));
  }
  if (!(options_.threshold_sigma > 0 && std::isfinite(options_.threshold_sigma))) {
    throw Error("outlier check: the threshold must be > 0 sigma");
  }
  if (!(to_si_ > 0 && std::isfinite(to_si_))) {
    throw Error("outlier check: the unit factor must be > 0");
  }
  const auto rows = static_cast<std::size_t>(options_.block_rows);
  block_.reserve(rows);
  previous_.reserve(rows);
  sample_.reserve(std::min(rows, kMaxSample * 2));
  found_.kind = DataWarningKind::outlier;
  found_.channel = channel_;
}

void OutlierChecker::check_block(std::span<const double> window, std::size_t first,
                                 std::int64_t first_row) {
  // m and s from every stride-th finite value of the window.
  const std::size_t stride = std::max<std::size_t>(1, window.size() / kMaxSample);
  sample_.clear();
  for (std::size_t i = 0; i < window.size(); i += stride) {
    if (std::isfinite(window[i])) sample_.push_back(window[i]);
  }
  if (sample_.empty()) return;
  const auto middle = sample_.begin() + static_cast<std::ptrdiff_t>(sample_.size() / 2);
  std::nth_element(sample_.begin(), middle, sample_.end());
  const double m = *middle;
  double d_min = INFINITY;
  for (double& v : sample_) {
    v = std::abs(v - m);
    if (v > 0 && v < d_min) d_min = v;
  }
  if (d_min == INFINITY) return;  // one value only: s = 0, nothing can be told apart
  const auto q = std::min(sample_.size() - 1,
                          static_cast<std::size_t>(kScaleQuantile * static_cast<double>(sample_.size())));
  std::nth_element(sample_.begin(), sample_.begin() + static_cast<std::ptrdiff_t>(q), sample_.end());
  const double s = std::max(sample_[q] / kScaleQuantileZ, d_min);
  const double limit = options_.threshold_sigma * s;
  for (std::size_t i = first; i < window.size(); ++i) {
    const double x = window[i];
    const double d = std::abs(x - m);
    if (!(d > limit) || !std::isfinite(x)) continue;  // NaN compares false: never flagged
    const std::int64_t row = first_row + static_cast<std::int64_t>(i - first);
    const double sigmas = d / s;
    if (found_.runs == 0) {
      found_.first_row = row;
      found_.first_rows = 1;
      found_.first_value = x;
    }
    if (sigmas > found_.largest_sigma) {
      found_.largest_sigma = sigmas;
      found_.longest_row = row;
      found_.longest_rows = 1;
      found_.value = x;
    }
    ++found_.runs;
    ++found_.rows_flagged;
  }
}

void OutlierChecker::push(double x) {
  block_.push_back(x);
  if (static_cast<std::int64_t>(block_.size()) < options_.block_rows) return;
  check_block(block_, 0, row_ + 1 - options_.block_rows);
  std::swap(block_, previous_);
  block_.clear();
}

void OutlierChecker::add(std::span<const double> values) {
  for (const double x : values) {
    if (options_.differences) {
      const double last = last_;
      last_ = x;
      if (!have_last_) {
        have_last_ = true;
        continue;
      }
      push(x - last);
    } else {
      push(x);
    }
    ++row_;
  }
}

std::optional<DataWarning> OutlierChecker::finish() {
  const std::size_t tail = block_.size();
  if (tail > 0) {
    const std::int64_t first_row = row_ - static_cast<std::int64_t>(tail);
    if (!previous_.empty()) {
      // The tail's m and s from the last block_rows rows: the previous block's end, then it.
      std::vector<double> window(previous_.begin() + static_cast<std::ptrdiff_t>(tail),
                                 previous_.end());
      window.insert(window.end(), block_.begin(), block_.end());
      check_block(window, window.size() - tail, first_row);
    } else if (static_cast<std::int64_t>(tail) >= kMinRows) {
      check_block(block_, 0, first_row);
    }
    block_.clear();
  }
  previous_.clear();
  if (found_.runs == 0) return std::nullopt;
  // A difference at series row r is x[r + 1] - x[r]: it is reported at the later row, r + 1.
  const std::int64_t shift = options_.differences ? 1 : 0;
  DataWarning w = found_;
  w.first_row += shift;
  w.longest_row += shift;
  const std::string what =
      options_.differences ? (w.runs == 1 ? " difference" : " differences") +
                                 std::string(" of consecutive samples")
                           : (w.runs == 1 ? " sample" : " samples");
  w.message = w.channel + ": " + std::to_string(w.runs) + what + " beyond " +
              format_sigma(options_.threshold_sigma) + " robust sigma of their " +
              std::to_string(options_.block_rows) +
              "-row block (outliers or spikes: they raise the Allan deviation at short taus and "
              "the white-noise level N); largest " +
              format_sigma(w.largest_sigma) + " sigma (" + format_value(w.value / to_si_, unit_) +
              ") at row " + std::to_string(w.longest_row) + ", first at row " +
              std::to_string(w.first_row) + " (" + format_value(w.first_value / to_si_, unit_) +
              ")";
  return w;
}

std::optional<DataWarning> check_outliers(std::span<const double> values,
                                          const std::string& channel,
                                          const OutlierOptions& options, const std::string& unit,
                                          double to_si) {
  OutlierChecker checker(channel, options, unit, to_si);
  checker.add(values);
  return checker.finish();
}

}  // namespace sigmatau
