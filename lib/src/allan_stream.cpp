// Bounded-memory single-pass Allan-family deviations (see allan_stream.hpp): the driver. It cuts
// the input into chunks of kChunk samples and passes each chunk through
//   StreamPhase   (allan_stream_phase.*)   samples -> double-double phase points (and P),
//   Level         (allan_stream_levels.*)  the phase decimated to every power-of-two stride,
//   StridedTerms  (allan_stream_terms.*)   the sum of squares of each statistic and factor,
//   NoiseSums     (allan_stream_noise.*)   the lag-1 autocorrelation sums of each factor,
// and forms the curves from the sums (allan_stream_curves.*).
//
// Glossary:
//   K        overlap density (start points per tau)
//   m        averaging factor; s its stride (a power of two dividing m); q = m / s, the lag in
//            units of the stride
//   level j  the phase (and its running sum P) at multiples of 2^j: entry u is phase point u 2^j
//   x        phase points x_0 = 0, x_k = sum_{i<=k} (y_i - y0bar) in double-double, y0bar the mean
//            of the first chunk (any offset works: every difference cancels a linear phase)
//   P        P[0] = 0, P[k+1] = P[k] + x[k] (MDEV only): V(j) = P[j+3m] - 3P[j+2m] + 3P[j+m] - P[j]
//   z        the series at m for noise identification: (x[(k+1)m] - x[km]) / m for rate and
//            increment input, x[km] for phase input (as confidence.cpp's series_at)
#include "sigmatau/allan_stream.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "allan_curve_assembly.hpp"
#include "allan_stream_curves.hpp"
#include "phase_store.hpp"
#include "allan_stream_levels.hpp"
#include "allan_stream_noise.hpp"
#include "allan_stream_phase.hpp"
#include "allan_stream_terms.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/sampling_limits.hpp"

namespace sigmatau {
namespace {

using detail::Doubles;
using detail::Level;
using detail::NoiseSums;
using detail::StridedTerms;

/// Samples per internal chunk: level-0 buffers hold about this many points.
constexpr std::int64_t kChunk = 16384;
/// Largest averaging factor prepared (2^40 samples: 35 years at 1 kHz).
constexpr std::int64_t kMaxFactor = std::int64_t{1} << 40;
/// Largest lag q = m / s in stride units: taus without a large power-of-two factor (e.g. an
/// explicit odd m) would need 3 q points of memory; beyond this that is an Error.
constexpr std::int64_t kMaxLag = std::int64_t{1} << 16;
/// z values formed per NoiseSums::add call (they stay in the L1 cache until summed).
constexpr std::size_t kNoiseTile = 1024;

int difference_order(Statistic s) {
  return (s == Statistic::hdev || s == Statistic::ohdev || s == Statistic::mdev ||
          s == Statistic::tdev)
             ? 3
             : 2;
}
bool uses_running_sum(Statistic s) { return s == Statistic::mdev || s == Statistic::tdev; }
bool non_overlapping(Statistic s) { return s == Statistic::adev || s == Statistic::hdev; }
/// Series the noise sums need: identify_noise differences at most 2 times for the Allan-type
/// statistics (MDEV too), 3 times for the Hadamard ones.
int noise_orders(Statistic s) { return (s == Statistic::hdev || s == Statistic::ohdev) ? 4 : 3; }

std::int64_t largest_power_of_two_dividing(std::int64_t m) { return m & -m; }
std::int64_t power_of_two_floor(std::int64_t v) {
  std::int64_t p = 1;
  while (p * 2 <= v) p *= 2;
  return p;
}
int log2_exact(std::int64_t p) {
  int j = 0;
  while ((std::int64_t{1} << j) < p) ++j;
  return j;
}

}  // namespace

struct AllanStream::Impl {
  DataKind kind;
  double tau0_s;
  StreamSettings settings;
  bool need_p = false;
  detail::StreamPhase phase{DataKind::rate};
  std::vector<Level> levels;
  std::vector<StridedTerms> taus;
  std::vector<std::int64_t> noise_factors;  // ascending distinct m
  std::vector<NoiseSums> noise;
  std::vector<int> noise_level;
  Doubles noise_tile;           // NoiseSums::kHistory + kNoiseTile doubles of scratch
  std::int64_t samples = 0;     // values added
  std::int64_t points = 0;      // phase points emitted
  std::vector<double> pending;  // input not yet processed (less than kChunk samples)
  double value_scale = 0.0;     // the values are processed divided by it; 0 before the first chunk
  std::vector<double> scaled;   // a chunk divided by value_scale (value_scale != 1 only)
  /// Decade factors not prepared, ascending (their lag would exceed the memory bound): the
  /// odd part of 10^k is 5^k, so from 10^7 on (5^7 = 78125 > kMaxLag) on the default settings.
  std::vector<std::int64_t> left_out;

  std::int64_t stride_for(Statistic s, std::int64_t m) const {
    const std::int64_t dividing = largest_power_of_two_dividing(m);
    if (non_overlapping(s)) return dividing;
    const std::int64_t cap = power_of_two_floor(std::max<std::int64_t>(1, m / settings.density));
    return std::min(dividing, cap);
  }

  /// Integrates a chunk into level 0 (its new points, and P before each for MDEV), then feeds
  /// the coarser levels, the sums and the noise state.
  void process_chunk(std::span<const double> y) {
    // Values beyond about 1e-100..1e100 are taken divided by a power of two chosen from the
    // first chunk (phase_store.hpp value_scale_for; 1 for ordinary data, which is then
    // untouched), so that squares and sums of squares stay in range; curves() multiplies back.
    if (value_scale == 0.0) {
      double largest = 0.0;
      for (const double v : y) largest = std::max(largest, std::fabs(v));
      value_scale = std::isfinite(largest) ? detail::value_scale_for(largest) : 1.0;
    }
    if (value_scale != 1.0) {
      scaled.resize(y.size());
      for (std::size_t i = 0; i < y.size(); ++i) scaled[i] = y[i] / value_scale;
      y = scaled;
    }
    const std::size_t count = phase.points_for(y.size());
    // The new points go straight to the end of level 0 (stride 1), which holds every point.
    Level& base = levels[0];
    const std::size_t old = base.xh.size();
    base.xh.resize(old + count);
    base.xl.resize(old + count);
    double* nh = base.xh.data() + old;
    double* nl = base.xl.data() + old;
    if (!phase.integrate(y, samples, nh, nl)) {
      for (std::size_t i = 0; i < y.size(); ++i) {
        if (!std::isfinite(y[i])) {
          throw Error("sample " + std::to_string(samples + static_cast<std::int64_t>(i)) +
                      " (0-based) is not finite (" + std::to_string(y[i]) + ")");
        }
      }
      throw Error("samples are too large to process (their sum overflows)");
    }
    if (need_p) {
      base.ph.resize(old + count);
      base.pl.resize(old + count);
      phase.running_sum(nh, nl, count, base.ph.data() + old, base.pl.data() + old);
    }
    points += static_cast<std::int64_t>(count);
    samples += static_cast<std::int64_t>(y.size());
    detail::distribute_points(levels, points, static_cast<std::int64_t>(count), need_p);
    run_terms();
    feed_noise();
    trim();
  }

  /// Sums every term now complete: first the blocks that octave runs of taus on one level share,
  /// then the rest tau by tau.
  void run_terms() {
    std::vector<StridedTerms*> on_level;
    for (std::size_t j = 0; j < levels.size(); ++j) {
      on_level.clear();
      for (auto& tau : taus) {
        if (static_cast<std::size_t>(tau.level) == j) on_level.push_back(&tau);
      }
      if (on_level.size() >= 2) detail::run_octave_blocks(on_level, levels[j]);
    }
    for (auto& tau : taus) tau.run(levels[static_cast<std::size_t>(tau.level)]);
  }

  void feed_noise() {
    double* z_tile = noise_tile.data() + NoiseSums::kHistory;
    for (std::size_t i = 0; i < noise_factors.size(); ++i) {
      const std::int64_t m = noise_factors[i];
      const Level& level = levels[static_cast<std::size_t>(noise_level[i])];
      const std::int64_t q = m / level.stride;
      NoiseSums& state = noise[i];
      const std::int64_t k_end = (level.x_end() + q - 1) / q;  // first k with k q >= x_end
      if (state.next_k >= k_end) continue;
      const double* xh = level.xh.data();
      const double* xl = level.xl.data();
      const std::int64_t b = level.begin;  // level index of xh[0]
      for (std::int64_t k = state.next_k; k < k_end && state.wants_kept(); ++k) {
        state.keep(xh[k * q - b] + xl[k * q - b]);
      }
      std::int64_t k = state.next_k;
      if (kind == DataKind::rate || kind == DataKind::increment) {
        if (k == 0) ++k;  // z needs x[(k-1) m]
      }
      const double inv_m = 1.0 / static_cast<double>(m);  // as series_at
      while (k < k_end) {
        const std::int64_t count = std::min<std::int64_t>(kNoiseTile, k_end - k);
        double* out = z_tile;
        if (kind == DataKind::phase) {
          for (std::int64_t j = 0; j < count; ++j) {
            const std::int64_t u = (k + j) * q - b;
            out[j] = xh[u] + xl[u];
          }
        } else if (q == 1) {  // the common case (octave factors): contiguous, vectorised
          detail::mean_rates(xh + (k - b), xl + (k - b), static_cast<std::size_t>(count), inv_m,
                             out);
        } else {
          for (std::int64_t j = 0; j < count; ++j) {
            const std::int64_t u = (k + j) * q - b;
            out[j] = ((xh[u] - xh[u - q]) + (xl[u] - xl[u - q])) * inv_m;
          }
        }
        state.add(noise_tile.data(), static_cast<std::size_t>(count));
        k += count;
      }
      state.next_k = k_end;
    }
  }

  /// Drops level points no term or noise state will read again.
  void trim() {
    std::vector<std::int64_t> keep_from(levels.size(), std::numeric_limits<std::int64_t>::max());
    for (const auto& tau : taus) {
      auto& k = keep_from[static_cast<std::size_t>(tau.level)];
      k = std::min(k, tau.next);
    }
    for (std::size_t i = 0; i < noise_factors.size(); ++i) {
      const Level& level = levels[static_cast<std::size_t>(noise_level[i])];
      const std::int64_t q = noise_factors[i] / level.stride;
      // The last x[k m] read (the next z needs it).
      const std::int64_t last = std::max<std::int64_t>(0, noise[i].next_k - 1) * q;
      auto& k = keep_from[static_cast<std::size_t>(noise_level[i])];
      k = std::min(k, last);
    }
    detail::trim_levels(levels, keep_from);
  }

  /// The sums with MDEV's last terms, which need P[N] = P[N-1] + x[N-1] (emitted with the next
  /// point): a copy, so the stream itself is unchanged.
  std::vector<StridedTerms> finished_taus() const {
    std::vector<StridedTerms> result = taus;
    if (!need_p || points == 0) return result;
    for (auto& tau : result) {
      tau.finish_running_sum(levels[static_cast<std::size_t>(tau.level)], phase.running_total(),
                             points);
    }
    return result;
  }
};

AllanStream::AllanStream(DataKind kind, double tau0_s, const StreamSettings& settings)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  checked_interval_s(tau0_s, "sample interval tau0_s");
  if (!(settings.density >= 1 && settings.density <= (1 << 20))) {
    throw Error("--density must be an integer from 1 to 1048576, got " +
                std::to_string(settings.density));
  }
  if (settings.statistics.empty()) throw Error("stream mode needs at least one statistic");
  s.kind = kind;
  s.tau0_s = tau0_s;
  s.settings = settings;
  s.phase = detail::StreamPhase(kind);
  std::vector<std::int64_t> factors;
  switch (settings.taus.kind) {
    case TauSpec::Kind::octave:
      for (std::int64_t m = 1; m <= kMaxFactor; m *= 2) factors.push_back(m);
      break;
    case TauSpec::Kind::decade:
      for (std::int64_t decade = 1; decade <= kMaxFactor; decade *= 10) {
        for (const std::int64_t step : {1, 2, 4}) factors.push_back(step * decade);
      }
      break;
    case TauSpec::Kind::explicit_seconds:
      // Rounded and checked as the exact mode does, against the largest length prepared.
      factors = averaging_factors(settings.taus, Statistic::oadev, 4 * kMaxFactor + 1, tau0_s);
      break;
    default:
      throw Error(
          "stream mode computes octave or decade taus, or a list of seconds; "
          "\"many\" and \"all\" need --mode exact");
  }
  for (const Statistic statistic : settings.statistics) {
    if (statistic == Statistic::totdev) {
      throw Error("totdev reflects the whole record at both ends: use --mode exact");
    }
    if (uses_running_sum(statistic)) s.need_p = true;
    for (const std::int64_t m : factors) {
      StridedTerms tau;
      tau.statistic = statistic;
      tau.m = m;
      tau.stride = s.stride_for(statistic, m);
      tau.lag = m / tau.stride;
      if (tau.lag > std::max<std::int64_t>(kMaxLag, settings.density) &&
          settings.taus.kind == TauSpec::Kind::decade) {
        // The decade grid runs to kMaxFactor whatever the log: its factors beyond the bound are
        // left out here and named by factors_left_out() once the log is long enough for them.
        if (std::find(s.left_out.begin(), s.left_out.end(), m) == s.left_out.end()) {
          s.left_out.insert(std::upper_bound(s.left_out.begin(), s.left_out.end(), m), m);
        }
        continue;
      }
      if (tau.lag > std::max<std::int64_t>(kMaxLag, settings.density)) {
        throw Error("tau of " + std::to_string(m) +
                    " samples has no power-of-two factor for a bounded stream stride; use "
                    "octave or decade taus, or --mode exact");
      }
      tau.step = non_overlapping(statistic) ? tau.lag : 1;
      tau.level = log2_exact(tau.stride);
      tau.order = difference_order(statistic);
      tau.running_sum = uses_running_sum(statistic);
      s.taus.push_back(tau);
      if (std::find(s.noise_factors.begin(), s.noise_factors.end(), m) == s.noise_factors.end()) {
        s.noise_factors.push_back(m);
      }
    }
  }
  // Where few averages remain, the curves take the type at kept_noise_factor, which depends on
  // the final length: every factor it can be is identified, the powers of two below the
  // largest m (each on its own level, so it reads consecutive points and keeps none) and, if an
  // m is on the decade grid, that grid's factors below the largest such m.
  std::int64_t largest = 1, largest_decade = 1;
  for (const std::int64_t m : factors) {
    largest = std::max(largest, m);
    if (detail::on_decade_grid(m)) largest_decade = std::max(largest_decade, m);
  }
  const auto add_noise_factor = [&](std::int64_t m) {
    if (std::find(s.noise_factors.begin(), s.noise_factors.end(), m) == s.noise_factors.end()) {
      s.noise_factors.push_back(m);
    }
  };
  for (std::int64_t m = 1; m < largest; m *= 2) add_noise_factor(m);
  for (std::int64_t decade = 1; decade < largest_decade; decade *= 10) {
    for (const std::int64_t step : {1, 2, 4}) {
      if (step * decade < largest_decade) add_noise_factor(step * decade);
    }
  }
  std::sort(s.noise_factors.begin(), s.noise_factors.end());
  int top = log2_exact(power_of_two_floor(largest));
  for (const auto& tau : s.taus) top = std::max(top, tau.level);
  s.levels.resize(static_cast<std::size_t>(top) + 1);
  for (std::size_t j = 0; j < s.levels.size(); ++j) s.levels[j].stride = std::int64_t{1} << j;
  int orders = 0;
  for (const Statistic statistic : settings.statistics) {
    orders = std::max(orders, noise_orders(statistic));
  }
  s.noise.assign(s.noise_factors.size(), NoiseSums(orders));
  s.noise_tile.resize(NoiseSums::kHistory + kNoiseTile);
  for (const std::int64_t m : s.noise_factors) {
    // The coarsest level whose stride divides m (any tau of this m would do).
    int level = 0;
    while (level + 1 < static_cast<int>(s.levels.size()) &&
           m % s.levels[static_cast<std::size_t>(level) + 1].stride == 0 &&
           m / s.levels[static_cast<std::size_t>(level) + 1].stride >= 1) {
      ++level;
    }
    s.noise_level.push_back(level);
  }
}

AllanStream::~AllanStream() = default;
AllanStream::AllanStream(AllanStream&&) noexcept = default;
AllanStream& AllanStream::operator=(AllanStream&&) noexcept = default;

void AllanStream::add(std::span<const double> values) {
  // Input is processed in chunks of exactly kChunk samples (the last one at curves()), so the
  // result does not depend on how the caller splits it.
  Impl& s = *impl_;
  std::size_t i = 0;
  if (!s.pending.empty()) {
    const std::size_t take =
        std::min(values.size(), static_cast<std::size_t>(kChunk) - s.pending.size());
    s.pending.insert(s.pending.end(), values.begin(),
                     values.begin() + static_cast<std::ptrdiff_t>(take));
    i = take;
    if (s.pending.size() < static_cast<std::size_t>(kChunk)) return;
    s.process_chunk(s.pending);
    s.pending.clear();
  }
  for (; i + static_cast<std::size_t>(kChunk) <= values.size();
       i += static_cast<std::size_t>(kChunk)) {
    s.process_chunk(values.subspan(i, static_cast<std::size_t>(kChunk)));
  }
  s.pending.assign(values.begin() + static_cast<std::ptrdiff_t>(i), values.end());
}

std::int64_t AllanStream::size() const {
  const auto pending = static_cast<std::int64_t>(impl_->pending.size());
  if (pending == 0) return impl_->points;
  return impl_->points +
         static_cast<std::int64_t>(impl_->phase.points_for(static_cast<std::size_t>(pending)));
}

std::int64_t AllanStream::stride(Statistic statistic, std::int64_t m) const {
  return impl_->stride_for(statistic, m);
}

std::size_t AllanStream::memory_bytes() const {
  const Impl& s = *impl_;
  std::size_t bytes = sizeof(Impl) + s.taus.capacity() * sizeof(StridedTerms) +
                      s.noise_tile.capacity() * sizeof(double);
  for (const auto& level : s.levels) {
    bytes += sizeof(Level) + (level.xh.capacity() + level.xl.capacity() + level.ph.capacity() +
                              level.pl.capacity()) *
                                 sizeof(double);
  }
  for (const auto& noise : s.noise) bytes += noise.memory_bytes();
  bytes += s.pending.capacity() * sizeof(double);
  return bytes;
}

std::vector<std::int64_t> AllanStream::factors_left_out() const {
  const Impl& s = *impl_;
  const std::int64_t n = s.points + static_cast<std::int64_t>(s.pending.size());
  std::vector<std::int64_t> out;
  if (n < 3) return out;
  for (const std::int64_t m : s.left_out) {
    for (const Statistic statistic : s.settings.statistics) {
      if (m <= max_averaging_factor(statistic, n, s.kind)) {
        out.push_back(m);
        break;
      }
    }
  }
  return out;
}

std::vector<AllanCurve> AllanStream::curves(double confidence_level) const {
  if (!(confidence_level > 0.0 && confidence_level < 1.0)) {
    throw Error("confidence level must be between 0 and 1 (e.g. 0.683), got " +
                std::to_string(confidence_level));
  }
  // Samples still pending are processed in a copy, so the stream itself is unchanged.
  std::unique_ptr<Impl> copy;
  if (!impl_->pending.empty()) {
    copy = std::make_unique<Impl>(*impl_);
    copy->process_chunk(copy->pending);
    copy->pending.clear();
  }
  const Impl& s = copy ? *copy : *impl_;
  const std::vector<StridedTerms> taus = s.finished_taus();
  detail::StreamTotals totals{s.kind,          s.tau0_s, s.points, taus, s.noise_factors,
                              s.noise,         s.value_scale == 0.0 ? 1.0 : s.value_scale};
  std::vector<AllanCurve> result;
  for (const Statistic statistic : s.settings.statistics) {
    result.push_back(detail::stream_curve(statistic, totals, confidence_level));
  }
  return result;
}

}  // namespace sigmatau
