// Composition of the exact estimators and their confidence intervals, channel-parallel.
#include "sigmatau/allan_curve.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <span>
#include <utility>
#include <vector>
#include <string>
#include <system_error>
#include <thread>

#include "allan_curve_assembly.hpp"
#include "noise_identification.hpp"
#include "parallel_items.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau {
/// Stable32 stops identifying the noise once few non-overlapping averages K = floor((N-1)/m)
/// remain: K <= 9 for ADEV and HDEV, K <= 3 for TOTDEV, K <= 7 otherwise. Observed on every
/// Stable32 table with error bars in ../shared/data (see tests/test_confidence_reference.cpp); a
/// B1 ratio from so few averages is itself unreliable.
std::int64_t kept_noise_threshold(Statistic statistic) {
  switch (statistic) {
    case Statistic::adev:
    case Statistic::hdev: return 9;
    case Statistic::totdev: return 3;
    default: return 7;
  }
}

void detail::check_representable(Statistic statistic, const DeviationPoint& point) {
  if (std::isfinite(point.dev)) return;
  char tau[32];
  std::snprintf(tau, sizeof tau, "%.6g", point.tau_s);
  throw Error(std::string(to_string(statistic)) + " at tau = " + tau +
              " s is beyond the largest double (about 1.8e308 in its unit): the values are too "
              "large for their sample interval; express them in another unit");
}

namespace {

/// Most factors identified by the one pass (acf_first_steps), the smallest ones: the pass keeps
/// a few hundred bytes of sums per factor and visits every factor once per block of the phase,
/// and the larger factors' series are short enough to build.
constexpr std::size_t kFirstStepFactors = 64;

}  // namespace

bool detail::on_decade_grid(std::int64_t m) {
  if (m < 10) return false;
  while (m % 10 == 0) m /= 10;
  return m == 1 || m == 2 || m == 4;
}

std::int64_t kept_noise_factor(Statistic statistic, std::int64_t phase_points, std::int64_t m) {
  const std::int64_t threshold = kept_noise_threshold(statistic);
  const auto enough = [&](std::int64_t g) { return (phase_points - 1) / g > threshold; };
  std::int64_t kept = 1;
  if (detail::on_decade_grid(m)) {
    // 1, 2, 4, 10, 20, 40, ...: each step at most 2.5x, so g cannot overflow before (N-1)/g
    // falls to the threshold.
    for (std::int64_t decade = 1;; decade *= 10) {
      for (const std::int64_t step : {1, 2, 4}) {
        if (!enough(step * decade)) return kept;
        kept = step * decade;
      }
    }
  }
  // Doubling stops before (N-1)/(2 kept) falls to the threshold; 2 kept cannot overflow because
  // (N-1)/(2 kept) > threshold >= 3 bounds it by N/4.
  while (enough(2 * kept)) kept *= 2;
  return kept;
}

std::int64_t record_points(const PhaseSeries& series) {
  return series.kind() == DataKind::phase ? series.size() : series.size() - 1;
}

double totvar_bias(int alpha, std::int64_t m, const PhaseSeries& series) {
  const double points = static_cast<double>(record_points(series));
  double a = 0.0;
  if (alpha == -1) a = 1.0 / (3.0 * std::log(2.0));
  if (alpha <= -2) a = 0.75;
  return 1.0 - a * static_cast<double>(m) / points;
}

namespace detail {

AllanCurve assemble_allan_curve(const PhaseSeries& series, Statistic statistic,
                                const TauSpec& taus, double confidence_level, EdfModel edf_model,
                                const std::function<NoiseIdentification(std::int64_t)>& identify,
                                unsigned threads) {
  if (!(confidence_level > 0.0 && confidence_level < 1.0)) {
    throw Error("confidence level must be between 0 and 1 (e.g. 0.683), got " +
                std::to_string(confidence_level));
  }
  const auto factors =
      averaging_factors(taus, statistic, series.size(), series.tau0_s(), series.kind());
  if (factors.empty()) {
    throw Error("the log (" + std::to_string(series.size() - 1) + " samples) is too short for " +
                std::string(to_string(statistic)) + " at any tau");
  }
  AllanCurve curve;
  curve.statistic = statistic;
  curve.confidence_level = confidence_level;
  // Where few averages remain, the type identified at a factor that depends on the record and
  // on m alone (never on which other taus were asked for); each such factor identified once.
  std::vector<std::pair<std::int64_t, int>> kept;  // (factor, alpha)
  for (DeviationPoint point : compute_deviation(series, statistic, factors, threads)) {
    detail::check_representable(statistic, point);
    ConfidencePoint confidence;
    const std::int64_t averages = (series.size() - 1) / point.m;
    const std::int64_t kept_m = kept_noise_factor(statistic, series.size(), point.m);
    if (point.m != kept_m && averages <= kept_noise_threshold(statistic)) {
      auto it = std::find_if(kept.begin(), kept.end(),
                             [&](const auto& k) { return k.first == kept_m; });
      if (it == kept.end()) it = kept.insert(kept.end(), {kept_m, identify(kept_m).alpha});
      confidence.noise.alpha = it->second;
      confidence.noise.method = NoiseIdentification::Method::kept;
    } else {
      confidence.noise = identify(point.m);
    }
    if (statistic == Statistic::totdev) {
      point.dev /= std::sqrt(totvar_bias(confidence.noise.alpha, point.m, series));
    }
    // TOTDEV's EDF (SP 1065 Table 7) is in terms of T / tau with T the record length, which
    // Stable32 counts in data points (M for rate input); Greenhall's algorithm uses N phase points.
    const std::int64_t edf_points =
        statistic == Statistic::totdev ? record_points(series) : series.size();
    confidence.edf =
        equivalent_dof(statistic, confidence.noise.alpha, point.m, edf_points, edf_model);
    confidence.interval = chi_squared_interval(point.dev, confidence.edf, confidence_level);
    curve.points.push_back({point, confidence});
  }
  return curve;
}

}  // namespace detail

namespace {

/// The one-pass identification (acf_first_steps) of a channel's smallest factors, shared by
/// every statistic of the channel (the pass depends on the phase and the factor alone: the same
/// alpha, bit for bit, whichever statistic asks). It runs once, when a curve first asks for it
/// (after its sweep), or from the start on a thread of its own (`beside`).
class FirstSteps {
 public:
  /// The factors of every statistic in `statistics` at these taus (none when no interval is
  /// wanted).
  FirstSteps(const PhaseSeries& series, std::span<const Statistic> statistics, const TauSpec& taus,
             double confidence_level, bool beside)
      : series_(series) {
    if (confidence_level > 0.0 && confidence_level < 1.0) {
      for (const Statistic statistic : statistics) {
        const auto m = averaging_factors(taus, statistic, series.size(), series.tau0_s(),
                                         series.kind());
        factors_.insert(factors_.end(), m.begin(), m.end());
      }
    }
    std::sort(factors_.begin(), factors_.end());
    factors_.erase(std::unique(factors_.begin(), factors_.end()), factors_.end());
    if (factors_.size() > kFirstStepFactors) factors_.resize(kFirstStepFactors);
    if (beside && !factors_.empty()) {
      try {
        pending_ = std::async(std::launch::async,
                              [this] { return detail::acf_first_steps(series_, factors_); });
      } catch (const std::system_error&) {
        // no thread to be had: the pass runs when a curve first asks for it
      }
    }
  }

  /// The pass's result for m: nullopt when m is not among its factors or the pass cannot tell
  /// (the caller then builds m's averaged series). Thread-safe.
  std::optional<int> find(std::int64_t m) {
    std::call_once(once_, [this] {
      steps_ = pending_.valid() ? pending_.get() : detail::acf_first_steps(series_, factors_);
    });
    const auto known = std::lower_bound(factors_.begin(), factors_.end(), m);
    if (known == factors_.end() || *known != m) return std::nullopt;
    return steps_[static_cast<std::size_t>(known - factors_.begin())];
  }

 private:
  const PhaseSeries& series_;
  std::vector<std::int64_t> factors_;
  std::vector<std::optional<int>> steps_;
  std::once_flag once_;
  std::future<std::vector<std::optional<int>>> pending_;  // last: joined before the rest goes
};

/// compute_allan_curve, the sums on up to sweep_threads threads.
AllanCurve allan_curve(const PhaseSeries& series, Statistic statistic, const TauSpec& taus,
                       double confidence_level, EdfModel edf_model, FirstSteps& first_steps,
                       unsigned sweep_threads) {
  // One buffer for the averaged series of every tau (sized by the first, smallest m): fresh
  // pages per tau cost more in kernel zeroing than the identification itself.
  std::unique_ptr<double[]> scratch;
  std::int64_t capacity = 0;
  return detail::assemble_allan_curve(
      series, statistic, taus, confidence_level, edf_model, [&](std::int64_t m) {
        if (const std::optional<int> alpha = first_steps.find(m)) {
          return detail::acf_identification(*alpha, statistic);
        }
        const std::int64_t points = detail::averaged_series_points(series, m);
        if (points >= detail::kMinAcfPoints && points > capacity) {
          scratch.reset(new double[static_cast<std::size_t>(points)]);  // written before read
          capacity = points;
        }
        return detail::identify_noise_with(series, statistic, m, scratch.get());
      },
      sweep_threads);
}

}  // namespace

AllanCurve compute_allan_curve(const PhaseSeries& series, Statistic statistic,
                               const TauSpec& taus, double confidence_level, EdfModel edf_model) {
  FirstSteps first_steps(series, std::span(&statistic, 1), taus, confidence_level, false);
  return allan_curve(series, statistic, taus, confidence_level, edf_model, first_steps, 1);
}

std::vector<std::vector<AllanCurve>> compute_allan_curves(
    const std::vector<PhaseSeries>& channels, const std::vector<Statistic>& statistics,
    const TauSpec& taus, double confidence_level, unsigned threads, EdfModel edf_model) {
  // Fewer curves than threads: each curve's identification pass takes a spare thread.
  const unsigned workers =
      threads == 0 ? std::max(1u, std::thread::hardware_concurrency()) : threads;
  const bool beside = channels.size() * statistics.size() < workers;
  // With fewer channels than threads, each curve's sums take a second thread: the identification
  // pass runs beside them (beside), or the statistics of a channel take unequal times (MDEV's
  // sums several times OADEV's), and a thread that has finished its curves can share the
  // longest sums instead of waiting.
  const unsigned sweep_threads = channels.size() < workers ? 2u : 1u;
  std::vector<std::unique_ptr<FirstSteps>> first_steps;
  for (const PhaseSeries& channel : channels) {
    first_steps.push_back(std::make_unique<FirstSteps>(channel, statistics, taus,
                                                       confidence_level, beside));
  }
  return detail::curves_per_channel_and_statistic(
      channels.size(), statistics.size(), threads, [&](std::size_t c, std::size_t s) {
        return allan_curve(channels[c], statistics[s], taus, confidence_level, edf_model,
                           *first_steps[c], sweep_threads);
      });
}

}  // namespace sigmatau
