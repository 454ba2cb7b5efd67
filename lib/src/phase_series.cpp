// One channel in integrated ("phase") form, held in double-double.
//
// Glossary (NIST SP 1065 notation):
//   y_1..y_M   rate (or increment) samples, M of them, every tau0 seconds
//   ybar       their mean, removed before integration (changes no Allan-family statistic)
//   x_0..x_{N-1}  phase points, N = M + 1, x_0 = 0, x_k = sum_{i<=k} (y_i - ybar)
//   hi, lo     the double-double phase: x_k = hi[k] + lo[k] to ~2^-104 relative
//
// Every y_i - ybar is split exactly into two doubles (TwoSum) and added to the running
// double-double sum, so the stored phase carries no rounding error of practical size, whatever the
// offset of the data, the length of the log or the size of the phase (random walks).
#include "sigmatau/phase_series.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "allan_dd.hpp"
#include "sigmatau/error.hpp"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace sigmatau {
namespace {

/// Samples per block of the mean computation: each block is summed in plain double in kLanes
/// independent lanes (vectorisable) and the block totals are carried in double-double, so the
/// rounding error of the mean is that of a sum of kMeanBlock / kLanes terms.
constexpr std::size_t kMeanBlock = 4096;
constexpr std::size_t kLanes = 8;
/// Samples between renormalisations of the running double-double phase (see from_rate).
constexpr std::size_t kPrefixBlock = 4096;

/// Sizes `v` to n elements, first asking Linux for transparent huge pages where it is in
/// "madvise" mode: a 1e8-sample phase is 1.6 GB, and faulting it in 4 KiB pages costs more than
/// computing it on a VM. Only a hint; elsewhere (or if refused) this is a plain resize.
void allocate(std::vector<double>& v, std::size_t n) {
  v.reserve(n);
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHugePage = std::uintptr_t{1} << 21;
  const auto begin = reinterpret_cast<std::uintptr_t>(v.data());
  const std::uintptr_t first = (begin + kHugePage - 1) & ~(kHugePage - 1);
  const std::uintptr_t last = (begin + n * sizeof(double)) & ~(kHugePage - 1);
  if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#endif
  v.resize(n);
}

void check_tau0(double tau0_s) {
  if (!(tau0_s > 0.0 && std::isfinite(tau0_s))) {
    throw Error("sample interval tau0 must be a finite number > 0 s, got " + std::to_string(tau0_s));
  }
}

[[noreturn]] void throw_non_finite(std::span<const double> v, const char* what) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) {
      throw Error(std::string(what) + " sample " + std::to_string(i) +
                  " (0-based) is not finite (" + std::to_string(v[i]) + ")");
    }
  }
  throw Error(std::string(what) + " samples are too large to process (their sum overflows)");
}

/// Mean of y computed as y_0 + mean(y_i - y_0), with the differences split exactly and summed in
/// blocks: exact for constant data (the mean is then y_0 itself), accurate otherwise. Throws
/// Error naming the first non-finite sample.
double accurate_mean(std::span<const double> y, const char* what) {
  if (y.empty()) return 0.0;
  const double y0 = y[0];
  detail::DoubleDouble total;
  double finite_check = 0.0;  // stays 0 unless a sample (or a difference) is Inf or NaN
  for (std::size_t b = 0; b < y.size(); b += kMeanBlock) {
    const std::size_t end = std::min(y.size(), b + kMeanBlock);
    double s[kLanes] = {};
    double e[kLanes] = {};
    double c[kLanes] = {};
    std::size_t i = b;
    for (; i + kLanes <= end; i += kLanes) {
      for (std::size_t k = 0; k < kLanes; ++k) {
        const detail::SumAndError d = detail::two_sum(y[i + k], -y0);
        s[k] += d.sum;
        e[k] += d.err;
        c[k] += d.sum * 0.0;
      }
    }
    for (std::size_t k = 0; i < end; ++i, ++k) {
      const detail::SumAndError d = detail::two_sum(y[i], -y0);
      s[k] += d.sum;
      e[k] += d.err;
      c[k] += d.sum * 0.0;
    }
    for (std::size_t k = 0; k < kLanes; ++k) {
      total.add(s[k], e[k]);
      finite_check += c[k];
    }
  }
  if (!(finite_check == 0.0) || !std::isfinite(total.hi)) throw_non_finite(y, what);
  const double n = static_cast<double>(y.size());
  return y0 + (total.hi / n + total.lo / n);
}

}  // namespace

DataKind parse_data_kind(std::string_view text) {
  if (text == "rate") return DataKind::rate;
  if (text == "increment") return DataKind::increment;
  if (text == "phase") return DataKind::phase;
  throw Error("data kind must be rate, increment or phase, got \"" + std::string(text) + "\"");
}

std::string_view to_string(DataKind kind) {
  switch (kind) {
    case DataKind::rate: return "rate";
    case DataKind::increment: return "increment";
    case DataKind::phase: return "phase";
  }
  return "?";
}

PhaseSeries PhaseSeries::from_rate(std::span<const double> y, double tau0_s) {
  check_tau0(tau0_s);
  PhaseSeries series(DataKind::rate, tau0_s);
  const double ybar = accurate_mean(y, "rate");
  series.mean_rate_ = ybar;
  allocate(series.hi_, y.size() + 1);
  allocate(series.lo_, y.size() + 1);
  double* hi = series.hi_.data();
  double* lo = series.lo_.data();
  hi[0] = 0.0;
  lo[0] = 0.0;
  // Cascaded double-double prefix: h is the running sum of the rounded increments and l collects
  // the exact rounding errors (of y_i - ybar and of each addition to h). Only h + s is on the
  // dependency chain, so this runs at the latency of one addition per sample; (h, l) is
  // renormalised every kPrefixBlock samples so that l stays within a few thousand ulps of h,
  // where its own rounding is ~2^-106 relative. Each stored pair is normalised.
  double h = 0.0;
  double l = 0.0;
  for (std::size_t b = 0; b < y.size(); b += kPrefixBlock) {
    const std::size_t end = std::min(y.size(), b + kPrefixBlock);
    for (std::size_t i = b; i < end; ++i) {
      const detail::SumAndError d = detail::two_sum(y[i], -ybar);  // y_i - ybar, exactly
      const detail::SumAndError t = detail::two_sum(h, d.sum);
      h = t.sum;
      l += t.err + d.err;
      const detail::SumAndError n = detail::two_sum(h, l);
      hi[i + 1] = n.sum;
      lo[i + 1] = n.err;
    }
    const detail::SumAndError n = detail::two_sum(h, l);
    h = n.sum;
    l = n.err;
  }
  return series;
}

PhaseSeries PhaseSeries::from_increments(std::span<const double> increments, double tau0_s) {
  PhaseSeries series = from_rate(increments, tau0_s);
  series.kind_ = DataKind::increment;
  series.mean_rate_ /= tau0_s;  // mean increment per sample -> mean rate [input unit / s]
  return series;
}

PhaseSeries PhaseSeries::from_phase(std::span<const double> x, double tau0_s) {
  check_tau0(tau0_s);
  PhaseSeries series(DataKind::phase, tau0_s);
  allocate(series.hi_, x.size());
  allocate(series.lo_, x.size());
  if (x.empty()) return series;
  const double x0 = x[0];
  if (!std::isfinite(x0)) throw_non_finite(x, "phase");
  double finite_check = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k) {
    const detail::SumAndError d = detail::two_sum(x[k], -x0);  // x_k - x_0, exactly
    series.hi_[k] = d.sum;
    series.lo_[k] = d.err;
    finite_check += d.sum * 0.0;
  }
  if (!(finite_check == 0.0)) throw_non_finite(x, "phase");
  return series;
}

PhaseSeries PhaseSeries::from_samples(std::span<const double> values, DataKind kind,
                                      double tau0_s) {
  switch (kind) {
    case DataKind::rate: return from_rate(values, tau0_s);
    case DataKind::increment: return from_increments(values, tau0_s);
    case DataKind::phase: return from_phase(values, tau0_s);
  }
  throw Error("unknown data kind");
}

double PhaseSeries::rate_scale(std::int64_t m) const {
  const double md = static_cast<double>(m);
  return kind_ == DataKind::rate ? 1.0 / md : 1.0 / (md * tau0_s_);
}

}  // namespace sigmatau
