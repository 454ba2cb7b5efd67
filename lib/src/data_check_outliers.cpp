// Outlier (spike) check: fixed blocks by row index, each with its median and a robust sigma from
// a strided sample (see sigmatau/data_checks.hpp, OutlierOptions, for the method and its numbers).
//
// Glossary: m = block median; s = robust sigma; k = threshold [sigma]; window = the rows a
// block's m and s come from (the block itself, or for the last partial block the last
// block_rows rows); sample = every stride-th finite value of the window.
#include <algorithm>
#include <cmath>
#include <numbers>
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
/// |z| of the standard normal at which P(|Z| <= z) = q, by bisection on erfc (exact to ~1e-15;
/// run once per checker). q = 0.9 gives 1.6448536..., q = 0.5 gives 0.6744897... (1 / 1.4826).
double normal_abs_quantile(double q) {
  double lo = 0, hi = 40;
  for (int i = 0; i < 200 && lo < hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (std::erfc(mid / std::numbers::sqrt2) > 1 - q ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

void check_quantile(double q) {
  if (!(q >= 0.5 && q < 1)) {
    throw Error("outlier check: the scale quantile must be in [0.5, 1), got " + std::to_string(q));
  }
}

/// Ranges shorter than this go to std::nth_element (quickselect's levels cost more there).
constexpr std::size_t kSelectDirect = 48;
/// Levels of quickselect before std::nth_element takes over (a bound on the worst case).
constexpr int kSelectLevels = 48;

/// The k-th smallest of the finite values v (0-based: the value std::nth_element would put at
/// position k), v left as it is. Quickselect whose partition has no data-dependent branch: each
/// value is written to both ends of a scratch array and the ends advance by the comparisons, so
/// a level costs about one cycle a value instead of a mispredicted branch every other value.
/// The k-th order statistic is one value, so the result is nth_element's whatever the path.
double kth_smallest(std::span<const double> v, std::size_t k) {
  thread_local std::vector<double> scratch[2];
  const std::size_t size = v.size();
  for (auto& s : scratch) {
    if (s.size() < size) s.resize(size);
  }
  const double* in = v.data();  // the values left, in v or in scratch[1 - next]
  int next = 0;                 // the scratch array this level writes
  std::size_t n = size;
  for (int level = 0; n > kSelectDirect && level < kSelectLevels; ++level, next = 1 - next) {
    double* const out = scratch[next].data();
    const double a = in[0], b = in[n / 2], c = in[n - 1];
    const double pivot = std::max(std::min(a, b), std::min(std::max(a, b), c));  // median of 3
    std::size_t below = 0;  // out[0, below): values < pivot
    std::size_t above = 0;  // out[n - above, n): values > pivot
    for (std::size_t i = 0; i < n; ++i) {
      const double x = in[i];
      out[below] = x;
      below += x < pivot ? 1 : 0;
      out[n - 1 - above] = x;
      above += x > pivot ? 1 : 0;
    }
    if (k < below) {
      in = out;
      n = below;
    } else if (k >= n - above) {
      k -= n - above;
      in = out + (n - above);
      n = above;
    } else {
      return pivot;  // k falls among the values equal to the pivot
    }
  }
  double* const out = scratch[next].data();
  std::copy(in, in + n, out);
  std::nth_element(out, out + k, out + n);
  return out[k];
}

/// m and s of `window` (see OutlierScale); `sample` is scratch.
OutlierScale scale_of(std::span<const double> window, double q, double z,
                      std::vector<double>& sample) {
  const std::size_t stride = std::max<std::size_t>(1, window.size() / kMaxSample);
  sample.clear();
  for (std::size_t i = 0; i < window.size(); i += stride) {
    if (std::isfinite(window[i])) sample.push_back(window[i]);
  }
  if (sample.empty()) return {};
  const double m = kth_smallest(sample, sample.size() / 2);
  double d_min = INFINITY;
  for (double& v : sample) {
    v = std::abs(v - m);
    if (v > 0 && v < d_min) d_min = v;
  }
  if (d_min == INFINITY) return {m, 0.0};  // one value only: nothing can be told apart
  const auto k =
      std::min(sample.size() - 1, static_cast<std::size_t>(q * static_cast<double>(sample.size())));
  return {m, std::max(kth_smallest(sample, k) / z, d_min)};
}

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
    : channel_(std::move(channel)),
      options_(options),
      quantile_z_(1),
      unit_(std::move(unit)),
      to_si_(to_si) {
  if (!(options_.block_rows >= kMinRows)) {
    throw Error("outlier check: the block must be >= " + std::to_string(kMinRows) + " rows, got " +
                std::to_string(options_.block_rows));
  }
  if (!(options_.threshold_sigma > 0 && std::isfinite(options_.threshold_sigma))) {
    throw Error("outlier check: the threshold must be > 0 sigma");
  }
  if (!(to_si_ > 0 && std::isfinite(to_si_))) {
    throw Error("outlier check: the unit factor must be > 0");
  }
  check_quantile(options_.scale_quantile);
  quantile_z_ = normal_abs_quantile(options_.scale_quantile);
  const auto rows = static_cast<std::size_t>(options_.block_rows);
  block_.reserve(rows);
  previous_.reserve(rows);
  sample_.reserve(std::min(rows, kMaxSample * 2));
  found_.kind = DataWarningKind::outlier;
  found_.channel = channel_;
}

void OutlierChecker::check_block(std::span<const double> window, std::size_t first,
                                 std::int64_t first_row) {
  const auto [m, s] = scale_of(window, options_.scale_quantile, quantile_z_, sample_);
  if (!(s > 0)) return;
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

void OutlierChecker::push(std::span<const double> values) {
  const auto rows = static_cast<std::size_t>(options_.block_rows);
  while (!values.empty()) {
    const std::size_t n = std::min(values.size(), rows - block_.size());
    block_.insert(block_.end(), values.begin(), values.begin() + static_cast<std::ptrdiff_t>(n));
    values = values.subspan(n);
    row_ += static_cast<std::int64_t>(n);
    if (block_.size() < rows) return;
    check_block(block_, 0, row_ - options_.block_rows);
    std::swap(block_, previous_);
    block_.clear();
  }
}

void OutlierChecker::add(std::span<const double> values) {
  if (!options_.differences) {
    push(values);
    return;
  }
  // Differences in pieces of at most 4096, through a small buffer.
  double buffer[4096];
  while (!values.empty()) {
    std::size_t n = 0;
    std::size_t i = 0;
    for (; i < values.size() && n < std::size(buffer); ++i) {
      if (have_last_) buffer[n++] = values[i] - last_;
      last_ = values[i];
      have_last_ = true;
    }
    push(std::span<const double>(buffer, n));
    values = values.subspan(i);
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
  const std::string what = options_.differences ? (w.runs == 1 ? " difference" : " differences") +
                                                      std::string(" of consecutive samples")
                                                : (w.runs == 1 ? " sample" : " samples");
  // Phase data: a difference is a frequency sample, and a spike in it a step in the phase.
  const std::string effect =
      options_.differences
          ? "steps in the phase, spikes in the frequency: they raise the deviation at short taus"
          : "outliers or spikes: they raise the Allan deviation at short taus and the white-noise "
            "level N";
  w.message = w.channel + ": " + std::to_string(w.runs) + what + " beyond " +
              format_sigma(options_.threshold_sigma) + " robust sigma of their " +
              std::to_string(options_.block_rows) +
              "-row block (" + effect + "); largest " +
              format_sigma(w.largest_sigma) + " sigma (" + format_value(w.value / to_si_, unit_) +
              ") at row " + std::to_string(w.longest_row) + ", first at row " +
              std::to_string(w.first_row) + " (" + format_value(w.first_value / to_si_, unit_) +
              ")";
  return w;
}

OutlierScale outlier_scale(std::span<const double> window, double scale_quantile) {
  check_quantile(scale_quantile);
  std::vector<double> sample;
  return scale_of(window, scale_quantile, normal_abs_quantile(scale_quantile), sample);
}

std::optional<DataWarning> check_outliers(std::span<const double> values,
                                          const std::string& channel, const OutlierOptions& options,
                                          const std::string& unit, double to_si) {
  OutlierChecker checker(channel, options, unit, to_si);
  checker.add(values);
  return checker.finish();
}

}  // namespace sigmatau
