// Bounded-memory single-pass Allan-family deviations (see allan_stream.hpp).
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

#include "allan_dd.hpp"
#include "allan_stream_noise.hpp"
#include "allan_sums.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau {
namespace {

using detail::DoubleDouble;
using detail::NoiseState;
using detail::SumAndError;
using detail::two_sum;

/// Samples per internal chunk: level-0 buffers hold about this many points.
constexpr std::int64_t kChunk = 65536;
/// Terms per call of the lane kernel (each lane's plain-double sum stays short, as in allan_sums).
constexpr std::int64_t kKernelTerms = 2048;
/// Largest averaging factor prepared (2^40 samples: 35 years at 1 kHz).
constexpr std::int64_t kMaxFactor = std::int64_t{1} << 40;
/// Largest lag q = m / s in stride units: taus without a large power-of-two factor (e.g. an
/// explicit odd m) would need 3 q points of memory; beyond this that is an Error.
constexpr std::int64_t kMaxLag = std::int64_t{1} << 16;
/// Fewest points at m for the lag-1 ACF (confidence.cpp, Riley & Greenhall 2004).
constexpr std::int64_t kMinAcfPoints = 30;
/// Differencing stops once r1 / (1 + r1) is below this value (confidence.cpp).
constexpr double kStationaryDelta = 0.25;
/// Block means kept per factor for the B1 ratio (used only while fewer than kMinAcfPoints exist).
constexpr std::int64_t kKeptMeans = kMinAcfPoints + 1;
/// Renormalise the running double-double phase this often (as phase_series.cpp).
constexpr std::int64_t kRenormalise = 4096;

int difference_order(Statistic s) {
  return (s == Statistic::hdev || s == Statistic::ohdev || s == Statistic::mdev ||
          s == Statistic::tdev)
             ? 3
             : 2;
}
bool uses_running_sum(Statistic s) { return s == Statistic::mdev || s == Statistic::tdev; }
bool non_overlapping(Statistic s) { return s == Statistic::adev || s == Statistic::hdev; }
/// The difference order confidence.cpp identifies noise with (MDEV is an Allan variance).
int noise_order(Statistic s) { return (s == Statistic::hdev || s == Statistic::ohdev) ? 3 : 2; }

/// compute_allan_curve keeps the previous tau's noise type once floor((N-1)/m) averages are at
/// most this many (allan_curve.cpp, from Stable32).
std::int64_t stream_kept_noise_threshold(Statistic s) {
  return (s == Statistic::adev || s == Statistic::hdev) ? 9 : 7;
}

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

struct Level {
  std::int64_t stride = 1;
  std::int64_t begin = 0;  // level index of element 0 of the buffers
  detail::Doubles xh, xl, ph, pl;
  std::int64_t x_end() const { return begin + static_cast<std::int64_t>(xh.size()); }
  std::int64_t p_end() const { return begin + static_cast<std::int64_t>(ph.size()); }
};

struct TauState {
  Statistic statistic;
  std::int64_t m = 0, stride = 1, lag = 1, step = 1;
  int level = 0;
  int order = 2;
  bool running_sum = false;
  std::int64_t next = 0;  // next term start, level index
  std::int64_t terms = 0;
  DoubleDouble sum;
};

}  // namespace

struct AllanStream::Impl {
  DataKind kind;
  double tau0_s;
  StreamSettings settings;
  bool need_p = false;
  std::vector<Level> levels;
  std::vector<TauState> taus;
  std::vector<std::int64_t> noise_factors;  // ascending distinct m
  std::vector<NoiseState> noise;
  std::vector<int> noise_level;
  // Running phase.
  bool started = false;
  double offset = 0;  // y0bar (rate, increment) or x_0 (phase)
  double h = 0, l = 0;
  DoubleDouble p_run;
  std::int64_t samples = 0;  // values added
  std::int64_t points = 0;   // phase points emitted
  std::vector<double> pending;  // input not yet processed (less than kChunk samples)

  std::int64_t stride_for(Statistic s, std::int64_t m) const {
    const std::int64_t dividing = largest_power_of_two_dividing(m);
    if (non_overlapping(s)) return dividing;
    const std::int64_t cap = power_of_two_floor(std::max<std::int64_t>(1, m / settings.density));
    return std::min(dividing, cap);
  }

  /// Integrates a chunk into nh, nl (its new level-0 points) and, for MDEV, nph, npl (the
  /// running sum P before each point).
  void process_chunk(std::span<const double> y) {
    std::size_t w = 0;  // points written
    const bool adds_start = !started && kind != DataKind::phase;
    const std::size_t count = y.size() + (adds_start ? 1 : 0);
    // The new points go straight to the end of level 0 (stride 1), which holds every point.
    Level& base = levels[0];
    const std::size_t old = base.xh.size();
    base.xh.resize(old + count);
    base.xl.resize(old + count);
    double* nh = base.xh.data() + old;
    double* nl = base.xl.data() + old;
    if (!started) {
      started = true;
      if (kind == DataKind::phase) {
        offset = y[0];
      } else {
        long double total = 0;
        for (const double v : y) total += v;
        offset = static_cast<double>(total / static_cast<long double>(y.size()));
        nh[0] = 0.0;
        nl[0] = 0.0;
        w = 1;
      }
    }
    double finite_check = 0.0;
    if (kind == DataKind::phase) {
      for (std::size_t i = 0; i < y.size(); ++i) {
        const SumAndError d = two_sum(y[i], -offset);
        finite_check += d.sum * 0.0;
        nh[w + i] = d.sum;
        nl[w + i] = d.err;
      }
    } else {
      // The running double-double phase, renormalised after every kRenormalise samples of the
      // whole stream.
      std::size_t i = 0;
      while (i < y.size()) {
        const std::int64_t done = samples + static_cast<std::int64_t>(i);
        const std::size_t run = std::min<std::size_t>(
            y.size() - i, static_cast<std::size_t>(kRenormalise - done % kRenormalise));
        double hh = h, ll = l;
        SumAndError n{hh, ll};
        for (std::size_t j = i; j < i + run; ++j) {
          const SumAndError d = two_sum(y[j], -offset);
          finite_check += d.sum * 0.0;
          const SumAndError t = two_sum(hh, d.sum);
          hh = t.sum;
          ll += t.err + d.err;
          n = two_sum(hh, ll);
          nh[w + j] = n.sum;
          nl[w + j] = n.err;
        }
        i += run;
        if ((done + static_cast<std::int64_t>(run)) % kRenormalise == 0) {
          hh = n.sum;
          ll = n.err;
        }
        h = hh;
        l = ll;
      }
    }
    if (need_p) {
      base.ph.resize(old + count);
      base.pl.resize(old + count);
      double* nph = base.ph.data() + old;
      double* npl = base.pl.data() + old;
      for (std::size_t k = 0; k < count; ++k) {
        nph[k] = p_run.hi;
        npl[k] = p_run.lo;
        p_run.add(nh[k], nl[k]);
      }
    }
    points += static_cast<std::int64_t>(count);
    if (!(finite_check == 0.0) || !std::isfinite(h)) {
      for (std::size_t i = 0; i < y.size(); ++i) {
        if (!std::isfinite(y[i])) {
          throw Error("sample " + std::to_string(samples + static_cast<std::int64_t>(i)) +
                      " (0-based) is not finite (" + std::to_string(y[i]) + ")");
        }
      }
      throw Error("samples are too large to process (their sum overflows)");
    }
    samples += static_cast<std::int64_t>(y.size());
    distribute(static_cast<std::int64_t>(count));
    for (auto& tau : taus) run_terms(tau);
    feed_noise();
    trim();
  }

  /// Appends the chunk's `count` new points (already at the end of level 0) to the other levels
  /// (level j takes the points whose index is a multiple of 2^j).
  void distribute(std::int64_t count) {
    const std::int64_t first = points - count;
    const Level& base = levels[0];
    auto take = [&](detail::Doubles& to, const detail::Doubles& from, std::int64_t k0,
                    std::int64_t stride, std::size_t n) {
      const std::size_t old = to.size();
      to.resize(old + n);
      const double* src = from.data() + (k0 - base.begin);
      for (std::size_t c = 0; c < n; ++c) to[old + c] = src[static_cast<std::int64_t>(c) * stride];
    };
    for (std::size_t j = 1; j < levels.size(); ++j) {
      Level& level = levels[j];
      const std::int64_t s = level.stride;
      const std::int64_t k0 = (first + s - 1) / s * s;
      if (k0 >= points) continue;
      const auto n = static_cast<std::size_t>((points - 1 - k0) / s + 1);
      take(level.xh, base.xh, k0, s, n);
      take(level.xl, base.xl, k0, s, n);
      if (need_p) {
        take(level.ph, base.ph, k0, s, n);
        take(level.pl, base.pl, k0, s, n);
      }
    }
  }

  void run_terms(TauState& tau) {
    Level& level = levels[static_cast<std::size_t>(tau.level)];
    // P[k] is known for k < points too (it lags x by one; P[points] follows with the next point,
    // so MDEV terms end one point later than they could: harmless, finish() adds the last).
    const std::int64_t end = tau.running_sum ? level.p_end() : level.x_end();
    const std::int64_t span = static_cast<std::int64_t>(tau.order) * tau.lag;
    const double* hh = tau.running_sum ? level.ph.data() : level.xh.data();
    const double* ll = tau.running_sum ? level.pl.data() : level.xl.data();
    if (tau.step == 1) {
      while (tau.next + span < end) {
        const std::int64_t len = std::min(kKernelTerms, end - span - tau.next);
        tau.sum.add(detail::sum_squares(hh, ll, tau.order, tau.lag, tau.next - level.begin, len));
        tau.terms += len;
        tau.next += len;
      }
    } else {
      double acc = 0.0;
      for (; tau.next + span < end; tau.next += tau.step) {
        acc += detail::sum_squares(hh, ll, tau.order, tau.lag, tau.next - level.begin, 1);
        ++tau.terms;
      }
      tau.sum.add(acc);
    }
  }

  void feed_noise() {
    for (std::size_t i = 0; i < noise_factors.size(); ++i) {
      const std::int64_t m = noise_factors[i];
      const Level& level = levels[static_cast<std::size_t>(noise_level[i])];
      const std::int64_t q = m / level.stride;
      NoiseState& state = noise[i];
      const std::int64_t k_end = (level.x_end() + q - 1) / q;  // first k with k q >= x_end
      if (state.next_k >= k_end) continue;
      const double* xh = level.xh.data();
      const double* xl = level.xl.data();
      const std::int64_t b = level.begin;  // level index of xh[0]
      for (std::int64_t k = state.next_k;
           k < k_end && static_cast<std::int64_t>(state.kept.size()) <= kKeptMeans; ++k) {
        state.kept.push_back(xh[k * q - b] + xl[k * q - b]);
      }
      std::int64_t k = state.next_k;
      if (kind == DataKind::rate || kind == DataKind::increment) {
        if (k == 0) ++k;  // z needs x[(k-1) m]
      }
      if (k < k_end) {
        const std::size_t old = state.batch.size();
        state.batch.resize(old + static_cast<std::size_t>(k_end - k));
        double* out = state.batch.data() + old;
        if (kind == DataKind::phase) {
          for (std::int64_t j = 0; k + j < k_end; ++j) {
            const std::int64_t u = (k + j) * q - b;
            out[j] = xh[u] + xl[u];
          }
        } else {
          const double inv_m = 1.0 / static_cast<double>(m);  // as series_at
          const std::int64_t count = k_end - k;
          if (q == 1) {  // the common case (octave factors): contiguous, vectorised
            const double* h1 = xh + (k - b);
            const double* l1 = xl + (k - b);
            for (std::int64_t j = 0; j < count; ++j) {
              out[j] = ((h1[j] - h1[j - 1]) + (l1[j] - l1[j - 1])) * inv_m;
            }
          } else {
            for (std::int64_t j = 0; j < count; ++j) {
              const std::int64_t u = (k + j) * q - b;
              out[j] = ((xh[u] - xh[u - q]) + (xl[u] - xl[u - q])) * inv_m;
            }
          }
        }
      }
      state.next_k = k_end;
      state.flush();
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
    for (std::size_t j = 0; j < levels.size(); ++j) {
      Level& level = levels[j];
      const std::int64_t drop = std::min(keep_from[j], level.x_end()) - level.begin;
      // Amortised: move only when the dead prefix is at least half the buffer.
      if (drop <= 0 || drop * 2 < static_cast<std::int64_t>(level.xh.size())) continue;
      auto erase = [drop](detail::Doubles& v) {
        const auto n = std::min<std::size_t>(static_cast<std::size_t>(drop), v.size());
        v.erase(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(n));
      };
      erase(level.xh);
      erase(level.xl);
      erase(level.ph);
      erase(level.pl);
      level.begin += drop;
    }
  }

  /// MDEV's last term needs P[N] = P[N-1] + x[N-1], which is emitted with the next point: a
  /// temporary copy of the tau states sums it without changing the stream.
  std::vector<TauState> finished_taus() const {
    std::vector<TauState> result = taus;
    if (!need_p || points == 0) return result;
    // Levels whose stride divides N = points hold P[N] as their next entry.
    for (auto& tau : result) {
      if (!tau.running_sum) continue;
      const Level& level = levels[static_cast<std::size_t>(tau.level)];
      if (points % level.stride != 0) continue;
      Level extended = level;
      extended.ph.push_back(p_run.hi);
      extended.pl.push_back(p_run.lo);
      const std::int64_t span = 3 * tau.lag;
      const std::int64_t end = extended.p_end();
      for (; tau.next + span < end; tau.next += tau.step) {
        tau.sum.add(detail::sum_squares(extended.ph.data(), extended.pl.data(), 3, tau.lag,
                                        tau.next - extended.begin, 1));
        ++tau.terms;
      }
    }
    return result;
  }

  NoiseIdentification identify(std::size_t i, Statistic statistic) const {
    const NoiseState& state = noise[i];
    const std::int64_t m = noise_factors[i];
    NoiseIdentification result;
    const int d_max = noise_order(statistic);
    const int lowest = d_max == 3 ? -4 : -2;
    int alpha = 0;
    if (state.sums[0].n >= kMinAcfPoints) {
      result.method = NoiseIdentification::Method::lag1_acf;
      bool found = false;
      for (int d = 0; d < 4; ++d) {
        const double r1 = state.sums[d].r1();
        if (std::isnan(r1)) break;
        const double delta = r1 / (1 + r1);
        if (delta < kStationaryDelta || d >= d_max || state.sums[d].n < 3) {
          alpha = -static_cast<int>(std::lround(2 * delta)) - 2 * d +
                  (kind == DataKind::phase ? 2 : 0);
          found = true;
          break;
        }
      }
      if (!found) {
        alpha = 0;
        result.method = NoiseIdentification::Method::assumed;
      }
    } else if (state.kept.size() >= 3) {
      // The few m-sample means (or decimated phase points) as a short series at m' = 1.
      std::vector<double> z;
      if (kind == DataKind::phase) {
        z = state.kept;
      } else {
        for (std::size_t k = 1; k < state.kept.size(); ++k) {
          z.push_back((state.kept[k] - state.kept[k - 1]) / static_cast<double>(m));
        }
      }
      const PhaseSeries shortened = PhaseSeries::from_samples(z, kind, tau0_s * static_cast<double>(m));
      return identify_noise(shortened, statistic, 1);
    } else {
      result.method = NoiseIdentification::Method::assumed;
    }
    result.alpha = std::clamp(alpha, lowest, 2);
    return result;
  }
};

double strided_equivalent_dof(Statistic statistic, int alpha, std::int64_t m, std::int64_t s,
                              std::int64_t n_phase_points) {
  if (!(s >= 1 && m >= s && m % s == 0)) {
    throw Error("strided_equivalent_dof: the stride must divide m");
  }
  if (s == 1 || statistic == Statistic::adev || statistic == Statistic::hdev) {
    return equivalent_dof(statistic, alpha, m, n_phase_points);
  }
  // The strided estimator reads only the phase at multiples of s: it is the fully overlapping
  // estimator at lag q = m/s of that decimated series (N' = floor((N-1)/s) + 1 points). For the
  // modified variances (F = 1), Greenhall's kernels depend on m only through S = q, so this is
  // the strided EDF exactly; for the unmodified ones it is the same sampling of the same
  // continuous-time noise (for flicker PM the ln m of Table 3 becomes ln q: a slight
  // underestimate of the EDF).
  const std::int64_t q = m / s;
  const std::int64_t n = (n_phase_points - 1) / s + 1;
  const int d = (statistic == Statistic::ohdev) ? 3 : 2;
  const bool modified = statistic == Statistic::mdev || statistic == Statistic::tdev;
  return greenhall_edf(alpha, d, q, modified ? 1 : q, q, n);
}

AllanStream::AllanStream(DataKind kind, double tau0_s, const StreamSettings& settings)
    : impl_(std::make_unique<Impl>()) {
  Impl& s = *impl_;
  if (!(tau0_s > 0.0 && std::isfinite(tau0_s))) {
    throw Error("sample interval tau0 must be a finite number > 0 s, got " + std::to_string(tau0_s));
  }
  if (!(settings.density >= 1 && settings.density <= (1 << 20))) {
    throw Error("--density must be an integer from 1 to 1048576, got " +
                std::to_string(settings.density));
  }
  if (settings.statistics.empty()) throw Error("stream mode needs at least one statistic");
  s.kind = kind;
  s.tau0_s = tau0_s;
  s.settings = settings;
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
      throw Error("stream mode computes octave or decade taus, or a list of seconds; "
                  "\"many\" and \"all\" need --mode exact");
  }
  for (const Statistic statistic : settings.statistics) {
    if (statistic == Statistic::totdev) {
      throw Error("totdev reflects the whole record at both ends: use --mode exact");
    }
    if (uses_running_sum(statistic)) s.need_p = true;
    for (const std::int64_t m : factors) {
      TauState tau;
      tau.statistic = statistic;
      tau.m = m;
      tau.stride = s.stride_for(statistic, m);
      tau.lag = m / tau.stride;
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
  std::sort(s.noise_factors.begin(), s.noise_factors.end());
  int top = 0;
  for (const auto& tau : s.taus) top = std::max(top, tau.level);
  s.levels.resize(static_cast<std::size_t>(top) + 1);
  for (std::size_t j = 0; j < s.levels.size(); ++j) s.levels[j].stride = std::int64_t{1} << j;
  s.noise.resize(s.noise_factors.size());
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
    s.pending.insert(s.pending.end(), values.begin(), values.begin() + static_cast<std::ptrdiff_t>(take));
    i = take;
    if (s.pending.size() < static_cast<std::size_t>(kChunk)) return;
    s.process_chunk(s.pending);
    s.pending.clear();
  }
  for (; i + static_cast<std::size_t>(kChunk) <= values.size(); i += static_cast<std::size_t>(kChunk)) {
    s.process_chunk(values.subspan(i, static_cast<std::size_t>(kChunk)));
  }
  s.pending.assign(values.begin() + static_cast<std::ptrdiff_t>(i), values.end());
}

std::int64_t AllanStream::size() const {
  const auto pending = static_cast<std::int64_t>(impl_->pending.size());
  if (pending == 0) return impl_->points;
  const bool adds_start = !impl_->started && impl_->kind != DataKind::phase;
  return impl_->points + pending + (adds_start ? 1 : 0);
}

std::int64_t AllanStream::stride(Statistic statistic, std::int64_t m) const {
  return impl_->stride_for(statistic, m);
}

std::size_t AllanStream::memory_bytes() const {
  const Impl& s = *impl_;
  std::size_t bytes = sizeof(Impl) + s.taus.capacity() * sizeof(TauState) +
                      s.noise.capacity() * sizeof(NoiseState);
  for (const auto& level : s.levels) {
    bytes += sizeof(Level) + (level.xh.capacity() + level.xl.capacity() + level.ph.capacity() +
                              level.pl.capacity()) *
                                 sizeof(double);
  }
  for (const auto& noise : s.noise) {
    bytes += (noise.kept.capacity() + noise.batch.capacity() + noise.spare.capacity()) *
             sizeof(double);
  }
  bytes += s.pending.capacity() * sizeof(double);
  return bytes;
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
  const std::int64_t N = s.points;
  const std::vector<TauState> taus = s.finished_taus();
  std::vector<AllanCurve> result;
  for (const Statistic statistic : s.settings.statistics) {
    AllanCurve curve;
    curve.statistic = statistic;
    curve.confidence_level = confidence_level;
    const std::int64_t max_m = max_averaging_factor(statistic, N);
    for (const auto& tau : taus) {
      if (tau.statistic != statistic || tau.m > max_m || tau.terms <= 0) continue;
      const double md = static_cast<double>(tau.m);
      const double scale = s.kind == DataKind::rate ? 1.0 / md : 1.0 / (md * s.tau0_s);
      const double mean_square = tau.sum.value() / static_cast<double>(tau.terms);
      double variance = 0.0;
      switch (statistic) {
        case Statistic::adev:
        case Statistic::oadev: variance = mean_square / 2.0; break;
        case Statistic::hdev:
        case Statistic::ohdev: variance = mean_square / 6.0; break;
        case Statistic::mdev: variance = mean_square / (2.0 * md * md); break;
        case Statistic::tdev: {
          const double tau_s = md * s.tau0_s;
          variance = mean_square / (2.0 * md * md) * (tau_s * tau_s / 3.0);
          break;
        }
        case Statistic::totdev: break;
      }
      variance *= scale * scale;
      CurvePoint point;
      point.value = {md * s.tau0_s, tau.m, tau.terms, std::sqrt(variance)};
      const auto it = std::lower_bound(s.noise_factors.begin(), s.noise_factors.end(), tau.m);
      point.confidence.noise =
          s.identify(static_cast<std::size_t>(it - s.noise_factors.begin()), statistic);
      const std::int64_t averages = (N - 1) / tau.m;
      if (!curve.points.empty() && averages <= stream_kept_noise_threshold(statistic)) {
        point.confidence.noise.alpha = curve.points.back().confidence.noise.alpha;
        point.confidence.noise.method = NoiseIdentification::Method::previous_tau;
      }
      point.confidence.edf =
          strided_equivalent_dof(statistic, point.confidence.noise.alpha, tau.m, tau.stride, N);
      point.confidence.interval =
          chi_squared_interval(point.value.dev, point.confidence.edf, confidence_level);
      curve.points.push_back(point);
    }
    result.push_back(std::move(curve));
  }
  return result;
}

}  // namespace sigmatau
