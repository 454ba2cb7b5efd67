// One channel in integrated ("phase") form, held in double-double.
//
// Glossary (NIST SP 1065 notation):
//   y_1..y_M   rate (or increment) samples, M of them, every tau0 seconds
//   ybar       their mean, removed before integration (changes no Allan-family statistic)
//   x_0..x_{N-1}  phase points, N = M + 1, x_0 = 0, x_k = sum_{i<=k} (y_i - ybar)
//   hi, lo     the double-double phase: x_k = hi[k] + lo[k] to ~2^-104 relative
//
// Scale: a log whose largest |value| is outside about 1e-100..1e100 is integrated divided by a
// power of two s (phase_store.hpp value_scale_for), so that its squares neither overflow (from
// about 1e154) nor become subnormal (below about 1e-154); the estimators multiply deviations by
// s. Division by a power of two is exact, and s = 1 for ordinary logs, which are held bit for bit
// as before.
//
// Every y_i - ybar is split exactly into two doubles (TwoSum) and added to the running
// double-double sum, so the stored phase carries no rounding error of practical size, whatever the
// offset of the data, the length of the log or the size of the phase (random walks).
// The clones of mean_block (simd_clones.hpp) give the same bits only without contraction.
#if defined(__clang__)
#pragma STDC FP_CONTRACT OFF
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif

#include "sigmatau/phase_series.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "allan_dd.hpp"
#include "phase_store.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/sampling_limits.hpp"
#include "simd_clones.hpp"

namespace sigmatau {
namespace {

/// Samples per block of the mean computation: each block is summed in plain double in kLanes
/// independent lanes (vectorisable) and the block totals are carried in double-double, so the
/// rounding error of the mean is that of a sum of kMeanBlock / kLanes terms.
constexpr std::int64_t kMeanBlock = 4096;
constexpr int kLanes = 8;
/// Samples between renormalisations of the running double-double phase (see Prefix).
constexpr std::int64_t kPrefixBlock = 4096;

static_assert(kMeanBlock % kLanes == 0, "lane of sample i is i mod kLanes");

void check_tau0(double tau0_s) { checked_interval_s(tau0_s, "sample interval tau0_s"); }

/// The largest |v| (v finite), in kLanes lanes so that the loop vectorises.
double largest_magnitude(std::span<const double> v, double largest) {
  double lane[kLanes] = {};
  const std::size_t n = v.size() - v.size() % kLanes;
  for (std::size_t i = 0; i < n; i += kLanes) {
    for (int k = 0; k < kLanes; ++k) {
      const double a = std::fabs(v[i + static_cast<std::size_t>(k)]);
      lane[k] = a > lane[k] ? a : lane[k];
    }
  }
  for (std::size_t i = n; i < v.size(); ++i) largest = std::max(largest, std::fabs(v[i]));
  for (const double a : lane) largest = std::max(largest, a);
  return largest;
}

/// v / s into out (s a power of two: exact; divided, not multiplied by 1/s, which overflows
/// for s below 2^-1024).
void divide(std::span<const double> v, double s, std::vector<double>& out) {
  out.resize(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = v[i] / s;
}

/// Names the first non-finite value of v (index first + i in the whole log).
[[noreturn]] void throw_non_finite(std::span<const double> v, std::int64_t first, const char* what) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) {
      throw Error(std::string(what) + " sample " + std::to_string(first + static_cast<std::int64_t>(i)) +
                  " (0-based) is not finite (" + std::to_string(v[i]) + ")");
    }
  }
  throw Error(std::string(what) + " samples are too large to process (their sum overflows)");
}

/// One whole block of kMeanBlock samples into the lanes (lane = index mod kLanes): s and e the
/// exact split of y_i - y0 summed, c the finite check (stays 0 unless a value is Inf or NaN),
/// big the largest |y_i|. The lanes are locals, so they stay in registers and the loop
/// vectorises; each lane's additions are those of a scalar loop, in its order.
SIGMATAU_SIMD_CLONES
void mean_block(const double* p, double y0, double* s, double* e, double* c, double* big) {
  double ls[kLanes], le[kLanes], lc[kLanes], lb[kLanes];
  for (int k = 0; k < kLanes; ++k) {
    ls[k] = s[k];
    le[k] = e[k];
    lc[k] = c[k];
    lb[k] = big[k];
  }
  for (std::int64_t j = 0; j < kMeanBlock; j += kLanes) {
    for (int k = 0; k < kLanes; ++k) {
      const double y = p[j + k];
      const detail::SumAndError d = detail::two_sum(y, -y0);
      ls[k] += d.sum;
      le[k] += d.err;
      lc[k] += d.sum * 0.0;
      const double a = std::fabs(y);
      lb[k] = a > lb[k] ? a : lb[k];
    }
  }
  for (int k = 0; k < kLanes; ++k) {
    s[k] = ls[k];
    e[k] = le[k];
    c[k] = lc[k];
    big[k] = lb[k];
  }
}

/// Mean of y computed as y_0 + mean(y_i - y_0), with the differences split exactly and summed in
/// blocks of kMeanBlock samples (kLanes plain-double lanes, lane = index mod kLanes; block totals
/// in double-double): exact for constant data (the mean is then y_0 itself), accurate otherwise.
/// Fed in pieces of any size, the order of every addition is that of one call on the whole log.
struct MeanAccumulator {
  std::int64_t count = 0;
  double y0 = 0.0;
  double s[kLanes] = {};
  double e[kLanes] = {};
  detail::DoubleDouble total;

  void flush() {
    for (int k = 0; k < kLanes; ++k) {
      total.add(s[k], e[k]);
      s[k] = 0.0;
      e[k] = 0.0;
    }
  }

  /// Adds y (samples count.. of the log) and raises `largest` to the largest |y_i|. Throws
  /// Error naming the first non-finite sample.
  void add(std::span<const double> y, const char* what, double& largest) {
    if (y.empty()) return;
    if (count == 0) y0 = y[0];
    const double* p = y.data();
    const std::int64_t n = static_cast<std::int64_t>(y.size());
    double finite_check = 0.0;  // stays 0 unless a sample (or a difference) is Inf or NaN
    double c[kLanes] = {};
    double big[kLanes] = {};
    std::int64_t i = 0;
    while (i < n) {
      const std::int64_t offset = count % kMeanBlock;
      const std::int64_t len = std::min(n - i, kMeanBlock - offset);
      if (offset == 0 && len == kMeanBlock) {
        mean_block(p + i, y0, s, e, c, big);
      } else {
        for (std::int64_t j = 0; j < len; ++j) {
          const int k = static_cast<int>((offset + j) % kLanes);
          const detail::SumAndError d = detail::two_sum(p[i + j], -y0);
          s[k] += d.sum;
          e[k] += d.err;
          c[k] += d.sum * 0.0;
          largest = std::max(largest, std::fabs(p[i + j]));
        }
      }
      i += len;
      count += len;
      if (count % kMeanBlock == 0) flush();
    }
    for (int k = 0; k < kLanes; ++k) finite_check += c[k];
    if (!(finite_check == 0.0)) throw_non_finite(y, count - n, what);
    for (const double a : big) largest = std::max(largest, a);
  }

  /// The mean of everything added; Error if the sum overflowed.
  double mean(std::span<const double> last, const char* what) {
    if (count == 0) return 0.0;
    if (count % kMeanBlock != 0) flush();
    if (!std::isfinite(total.hi)) throw_non_finite(last, 0, what);
    const double n = static_cast<double>(count);
    return y0 + (total.hi / n + total.lo / n);
  }
};

/// Cascaded double-double prefix: h is the running sum of the rounded increments and l collects
/// the exact rounding errors (of y_i - ybar and of each addition to h). Only h + s is on the
/// dependency chain, so this runs at the latency of one addition per sample; (h, l) is
/// renormalised after every kPrefixBlock samples so that l stays within a few thousand ulps of
/// h, where its own rounding is ~2^-106 relative. Each stored pair is normalised.
struct Prefix {
  double ybar = 0.0;
  double h = 0.0;
  double l = 0.0;
  std::int64_t count = 0;  // samples integrated so far; the next goes to point count + 1

  void add(std::span<const double> y, double* hi, double* lo) {
    // h and l in locals: as members, every store to hi and lo (which might alias them, for all
    // the compiler knows) would send them through memory on the serial chain.
    double run_h = h;
    double run_l = l;
    const double* p = y.data();
    const std::int64_t n = static_cast<std::int64_t>(y.size());
    std::int64_t i = 0;
    while (i < n) {
      const std::int64_t len = std::min(n - i, kPrefixBlock - count % kPrefixBlock);
      double* hs = hi + count + 1;
      double* ls = lo + count + 1;
      const double* ys = p + i;
      for (std::int64_t j = 0; j < len; ++j) {
        const detail::SumAndError d = detail::two_sum(ys[j], -ybar);  // y_i - ybar, exactly
        const detail::SumAndError t = detail::two_sum(run_h, d.sum);
        run_h = t.sum;
        run_l += t.err + d.err;
        const detail::SumAndError s = detail::two_sum(run_h, run_l);
        hs[j] = s.sum;
        ls[j] = s.err;
      }
      i += len;
      count += len;
      if (count % kPrefixBlock == 0) {
        const detail::SumAndError s = detail::two_sum(run_h, run_l);
        run_h = s.sum;
        run_l = s.err;
      }
    }
    h = run_h;
    l = run_l;
  }
};

}  // namespace

struct PhaseSeriesBuilder::State {
  DataKind kind;
  PhaseStorage storage;
  MeanAccumulator mean;
  double x0 = 0.0;  // phase input: the first point
  double last = 0.0;
  bool appending = false;
  std::shared_ptr<detail::PhaseStore> store;
  Prefix prefix;
  std::int64_t appended = 0;
  double largest = 0.0;   // largest |value| seen by pass 1
  double scale = 1.0;     // value_scale_for(largest), chosen when pass 2 starts
  std::vector<double> scaled;  // pass 2's values divided by scale (scale != 1 only)
};

PhaseSeriesBuilder::PhaseSeriesBuilder(DataKind kind, PhaseStorage storage)
    : state_(std::make_unique<State>()) {
  state_->kind = kind;
  state_->storage = std::move(storage);
}
PhaseSeriesBuilder::~PhaseSeriesBuilder() = default;
PhaseSeriesBuilder::PhaseSeriesBuilder(PhaseSeriesBuilder&&) noexcept = default;
PhaseSeriesBuilder& PhaseSeriesBuilder::operator=(PhaseSeriesBuilder&&) noexcept = default;

std::int64_t PhaseSeriesBuilder::samples() const { return state_->mean.count; }

void PhaseSeriesBuilder::scan(std::span<const double> values) {
  State& st = *state_;
  if (st.appending) throw Error("PhaseSeriesBuilder: scan() after append()");
  if (values.empty()) return;
  if (st.kind == DataKind::phase) {
    if (st.mean.count == 0) {
      st.x0 = values[0];
      if (!std::isfinite(st.x0)) throw_non_finite(values, 0, "phase");
    }
    // Finite values only (their differences from x0 are formed after scaling, so values of
    // opposite sign near the largest double do not overflow).
    double finite_check = 0.0;
    for (const double v : values) finite_check += v * 0.0;
    if (!(finite_check == 0.0)) throw_non_finite(values, st.mean.count, "phase");
    st.mean.count += static_cast<std::int64_t>(values.size());
    st.largest = largest_magnitude(values, st.largest);
  } else {
    st.mean.add(values, "rate", st.largest);  // and the largest |value|, in the same pass
  }
  st.last = values.back();
}

void PhaseSeriesBuilder::append(std::span<const double> values) {
  State& st = *state_;
  const std::int64_t total = st.mean.count;
  if (!st.appending) {
    st.appending = true;
    st.scale = detail::value_scale_for(st.largest);
    if (st.kind != DataKind::phase) {
      const double last[1] = {st.last};
      st.prefix.ybar = st.mean.mean(last, "rate") / st.scale;
    }
    const std::int64_t points = st.kind == DataKind::phase ? total : total + 1;
    st.store = std::make_shared<detail::PhaseStore>();
    st.store->storage = st.storage;
    st.store->hi = detail::DoubleBuffer(static_cast<std::size_t>(points), st.storage);
    st.store->lo = detail::DoubleBuffer(static_cast<std::size_t>(points), st.storage);
    if (st.kind != DataKind::phase && points > 0) {
      st.store->hi.data()[0] = 0.0;
      st.store->lo.data()[0] = 0.0;
    }
  }
  const std::int64_t n = static_cast<std::int64_t>(values.size());
  if (st.appended + n > total) {
    throw Error("PhaseSeriesBuilder: pass 2 delivered more samples (" +
                std::to_string(st.appended + n) + ") than pass 1 (" + std::to_string(total) + ")");
  }
  if (st.scale != 1.0) {
    divide(values, st.scale, st.scaled);
    values = st.scaled;
  }
  double* hi = st.store->hi.data();
  double* lo = st.store->lo.data();
  if (st.kind == DataKind::phase) {
    const double x0 = st.x0 / st.scale;
    for (std::int64_t k = 0; k < n; ++k) {
      const detail::SumAndError d = detail::two_sum(values[k], -x0);  // x_k - x_0, exactly
      hi[st.appended + k] = d.sum;
      lo[st.appended + k] = d.err;
    }
  } else {
    st.prefix.add(values, hi, lo);
  }
  st.appended += n;
  // File-backed storage: keep the resident set within its budget even if the watchdog thread
  // is starved (the writes here can outrun it by gigabytes on a loaded machine).
  if (st.store->hi.spilled()) detail::enforce_spill_budget();
}

PhaseSeries PhaseSeriesBuilder::finish(double tau0_s) {
  check_tau0(tau0_s);
  State& st = *state_;
  if (!st.appending) append({});
  if (st.appended != st.mean.count) {
    throw Error("PhaseSeriesBuilder: pass 2 delivered " + std::to_string(st.appended) +
                " samples, pass 1 " + std::to_string(st.mean.count));
  }
  PhaseSeries series(st.kind, tau0_s);
  series.mean_rate_ = st.kind == DataKind::phase ? 0.0 : st.prefix.ybar * st.scale;
  if (st.kind == DataKind::increment) series.mean_rate_ /= tau0_s;  // per sample -> per s
  st.store->value_scale = st.scale;
  series.store_ = std::move(st.store);
  series.hi_ = series.store_->hi.data();
  series.lo_ = series.store_->lo.data();
  series.size_ = static_cast<std::int64_t>(series.store_->hi.size());
  st.appending = false;
  st.mean = MeanAccumulator{};
  st.appended = 0;
  st.largest = 0.0;
  st.scale = 1.0;
  st.scaled = {};
  return series;
}

double detail::value_scale_for(double largest, double unscaled_min, double unscaled_max) {
  if (largest == 0.0 || (largest >= unscaled_min && largest <= unscaled_max)) return 1.0;
  return std::ldexp(1.0, std::ilogb(largest));
}

bool PhaseSeries::spilled() const { return store_ && store_->hi.spilled(); }

void PhaseSeries::recycle(std::vector<double>&& memory) const {
  if (!store_) return;
  std::lock_guard lock(store_->mutex);
  if (store_->compact || spilled() || memory.capacity() < static_cast<std::size_t>(size_)) return;
  store_->recycled = std::move(memory);
}

void PhaseSeries::drop_sweep_cache() const {
  if (!store_) return;
  std::lock_guard lock(store_->mutex);
  store_->compact.reset();
}

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

namespace {
PhaseSeries build(std::span<const double> values, DataKind kind, double tau0_s,
                  const PhaseStorage& storage) {
  check_tau0(tau0_s);
  PhaseSeriesBuilder builder(kind, storage);
  builder.scan(values);
  builder.append(values);
  return builder.finish(tau0_s);
}
}  // namespace

PhaseSeries PhaseSeries::from_rate(std::span<const double> y, double tau0_s,
                                   const PhaseStorage& storage) {
  return build(y, DataKind::rate, tau0_s, storage);
}

PhaseSeries PhaseSeries::from_increments(std::span<const double> increments, double tau0_s,
                                         const PhaseStorage& storage) {
  return build(increments, DataKind::increment, tau0_s, storage);
}

PhaseSeries PhaseSeries::from_phase(std::span<const double> x, double tau0_s,
                                    const PhaseStorage& storage) {
  return build(x, DataKind::phase, tau0_s, storage);
}

PhaseSeries PhaseSeries::from_samples(std::span<const double> values, DataKind kind,
                                      double tau0_s, const PhaseStorage& storage) {
  switch (kind) {
    case DataKind::rate: return from_rate(values, tau0_s, storage);
    case DataKind::increment: return from_increments(values, tau0_s, storage);
    case DataKind::phase: return from_phase(values, tau0_s, storage);
  }
  throw Error("unknown data kind");
}

double PhaseSeries::rate_scale(std::int64_t m) const {
  const double md = static_cast<double>(m);
  return kind_ == DataKind::rate ? 1.0 / md : 1.0 / (md * tau0_s_);
}

}  // namespace sigmatau
