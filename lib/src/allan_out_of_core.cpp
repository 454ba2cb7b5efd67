// Exact Allan-family curves out of core (see allan_out_of_core.hpp).
//
// Two pieces mirror code elsewhere so that the results stay identical bit for bit:
// - identify_noise_bounded repeats the lag-1 ACF method of confidence.cpp (identify_noise) on a
//   series held in a DoubleBuffer (spilled when asked) instead of a std::vector; the B1 branch
//   (fewer than kMinAcfPoints points) and short series go to identify_noise itself.
// - compute_allan_curve_bounded repeats compute_allan_curve (allan_curve.cpp) with that
//   identification. tests/test_allan_out_of_core.cpp compares both with the in-memory path.
#include "sigmatau/allan_out_of_core.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <thread>

#include "phase_spill.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau {
namespace {

// The constants of confidence.cpp's identification.
constexpr std::int64_t kMinAcfPoints = 30;
constexpr double kStationaryDelta = 0.25;
constexpr int kAssumedAlpha = 0;
/// Series of up to resident_bytes / kInMemoryShare bytes (16 MiB by default) go to
/// identify_noise unchanged, in a std::vector.
constexpr std::int64_t kInMemoryShare = 16;

int difference_order(Statistic statistic) {
  return (statistic == Statistic::hdev || statistic == Statistic::ohdev) ? 3 : 2;
}
int lowest_alpha(Statistic statistic) { return difference_order(statistic) == 3 ? -4 : -2; }

/// Stable32's "previous tau's noise type" threshold (allan_curve.cpp kept_noise_threshold).
std::int64_t curve_kept_noise_threshold(Statistic statistic) {
  switch (statistic) {
    case Statistic::adev:
    case Statistic::hdev: return 9;
    case Statistic::totdev: return 3;
    default: return 7;
  }
}

/// Lag-1 autocorrelation of z[0..n) (confidence.cpp), NaN for a constant series.
double lag1_autocorrelation(const double* z, std::size_t n) {
  long double mean = 0;
  for (std::size_t i = 0; i < n; ++i) mean += z[i];
  mean /= static_cast<long double>(n);
  long double num = 0, den = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const long double a = z[i] - mean;
    den += a * a;
    if (i + 1 < n) num += a * (z[i + 1] - mean);
  }
  if (!(den > 0)) return std::numeric_limits<double>::quiet_NaN();
  return static_cast<double>(num / den);
}

/// identify_by_acf of confidence.cpp on z[0..n), which it overwrites.
bool identify_by_acf(double* z, std::size_t n, bool phase_input, int d_max, int& alpha) {
  for (int d = 0;; ++d) {
    const double r1 = lag1_autocorrelation(z, n);
    if (std::isnan(r1)) return false;
    const double delta = r1 / (1 + r1);
    if (delta < kStationaryDelta || d >= d_max || n < 3) {
      const int p = -static_cast<int>(std::lround(2 * delta)) - 2 * d;
      alpha = p + (phase_input ? 2 : 0);
      return true;
    }
    for (std::size_t i = 0; i + 1 < n; ++i) z[i] = z[i + 1] - z[i];
    --n;
  }
}

}  // namespace

NoiseIdentification identify_noise_bounded(const PhaseSeries& series, Statistic statistic,
                                           std::int64_t m, const PhaseStorage& storage) {
  const std::int64_t N = series.size();
  const bool phase_input = series.kind() == DataKind::phase;
  const std::int64_t points = phase_input ? (m >= 1 ? (N - 1) / m + 1 : 0) : (m >= 1 ? (N - 1) / m : 0);
  const std::int64_t in_memory_points = storage.resident_bytes / kInMemoryShare / 8;
  if (!(m >= 1) || m >= N || points < kMinAcfPoints || points <= in_memory_points) {
    return identify_noise(series, statistic, m);
  }
  // series_at of confidence.cpp, into the buffer.
  detail::DoubleBuffer z(static_cast<std::size_t>(points), storage);
  double* out = z.data();
  if (phase_input) {
    for (std::int64_t k = 0, i = 0; k < N; k += m, ++i) out[i] = series.x(k);
  } else {
    const double inv_m = 1.0 / static_cast<double>(m);
    for (std::int64_t k = 0; k < points; ++k) out[k] = series.window_sum(k * m, m) * inv_m;
  }
  NoiseIdentification result;
  result.method = NoiseIdentification::Method::lag1_acf;
  int alpha = kAssumedAlpha;
  if (!identify_by_acf(out, static_cast<std::size_t>(points), phase_input,
                       difference_order(statistic), alpha)) {
    alpha = kAssumedAlpha;
    result.method = NoiseIdentification::Method::assumed;
  }
  result.alpha = std::clamp(alpha, lowest_alpha(statistic), 2);
  return result;
}

AllanCurve compute_allan_curve_bounded(const PhaseSeries& series, Statistic statistic,
                                       const TauSpec& taus, double confidence_level,
                                       const PhaseStorage& storage) {
  if (!(confidence_level > 0.0 && confidence_level < 1.0)) {
    throw Error("confidence level must be between 0 and 1 (e.g. 0.683), got " +
                std::to_string(confidence_level));
  }
  const auto factors = averaging_factors(taus, statistic, series.size(), series.tau0_s());
  if (factors.empty()) {
    throw Error("the log (" + std::to_string(series.size() - 1) + " samples) is too short for " +
                std::string(to_string(statistic)) + " at any tau");
  }
  AllanCurve curve;
  curve.statistic = statistic;
  curve.confidence_level = confidence_level;
  for (DeviationPoint point : compute_deviation(series, statistic, factors)) {
    ConfidencePoint confidence;
    confidence.noise = identify_noise_bounded(series, statistic, point.m, storage);
    const std::int64_t averages = (series.size() - 1) / point.m;
    if (!curve.points.empty() && averages <= curve_kept_noise_threshold(statistic)) {
      confidence.noise.alpha = curve.points.back().confidence.noise.alpha;
      confidence.noise.method = NoiseIdentification::Method::previous_tau;
    }
    if (statistic == Statistic::totdev) {
      point.dev /= std::sqrt(totvar_bias(confidence.noise.alpha, point.m, series));
    }
    const std::int64_t edf_points =
        statistic == Statistic::totdev ? record_points(series) : series.size();
    confidence.edf = equivalent_dof(statistic, confidence.noise.alpha, point.m, edf_points);
    confidence.interval = chi_squared_interval(point.dev, confidence.edf, confidence_level);
    curve.points.push_back({point, confidence});
  }
  return curve;
}

namespace {

/// One read pass over the log: calls each(block) for every block (values already in SI).
TimingReport read_pass(const LogOptions& log, double to_si,
                       const std::function<void(std::int64_t, std::int64_t)>& progress,
                       const std::function<void(SampleBlock&)>& each,
                       std::vector<std::string>* names) {
  LogReader reader(log);
  if (names) *names = reader.channel_names();
  SampleBlock block;
  while (reader.read_block(block)) {
    if (to_si != 1.0) {
      for (auto& channel : block.values) {
        for (double& v : channel) v *= to_si;
      }
    }
    each(block);
    if (progress) progress(reader.bytes_read(), reader.total_bytes());
  }
  return reader.timing();
}

}  // namespace

OutOfCoreResult compute_allan_curves_out_of_core(
    const LogOptions& log, DataKind kind, double to_si,
    const std::function<double(const TimingReport&)>& rate_hz,
    const std::vector<Statistic>& statistics, const TauSpec& taus, double confidence_level,
    const OutOfCoreSettings& settings) {
  if (log.path == "-") {
    throw Error("exact out-of-core mode reads the log twice and needs a file, not stdin "
                "(use --mode stream for a pipe)");
  }
  OutOfCoreResult result;
  unsigned threads = settings.threads;
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());

  // Channel names and the rate come from the first full pass (the first group's pass 1).
  std::size_t channels = 0;
  double tau0_s = 0;
  std::size_t group_begin = 0;
  do {
    std::vector<PhaseSeriesBuilder> builders;
    const bool first = group_begin == 0;
    std::size_t group_end = 0;
    auto scan = [&](SampleBlock& block) {
      if (builders.empty()) {
        channels = block.values.size();
        group_end = std::min<std::size_t>(channels, group_begin + threads);
        for (std::size_t c = group_begin; c < group_end; ++c) {
          builders.emplace_back(kind, settings.storage);
        }
      }
      for (std::size_t c = group_begin; c < group_end; ++c) builders[c - group_begin].scan(block.values[c]);
    };
    const TimingReport timing = read_pass(log, to_si, settings.progress, scan,
                                          first ? &result.channel_names : nullptr);
    if (builders.empty()) {
      throw ParseError(log.path, 0, 0, "no samples: the input holds no data rows");
    }
    if (first) {
      result.timing = timing;
      result.rate_hz = rate_hz(timing);
      tau0_s = 1.0 / result.rate_hz;
      result.samples = builders.front().samples();
      result.curves.assign(channels, {});
    } else if (builders.front().samples() != result.samples) {
      throw Error(log.path + " changed while it was read (" + std::to_string(result.samples) +
                  " samples, then " + std::to_string(builders.front().samples()) + ")");
    }
    auto append = [&](SampleBlock& block) {
      for (std::size_t c = group_begin; c < group_end; ++c) builders[c - group_begin].append(block.values[c]);
    };
    read_pass(log, to_si, settings.progress, append, nullptr);
    std::vector<PhaseSeries> series;
    for (auto& b : builders) {
      try {
        series.push_back(b.finish(tau0_s));
      } catch (const Error& e) {
        throw Error(log.path + " changed while it was read: " + e.what());
      }
    }
    builders.clear();

    // One worker per channel of the group; each computes that channel's statistics in turn.
    std::exception_ptr first_error;
    std::mutex error_mutex;
    std::atomic<std::size_t> next{0};
    const std::size_t items = series.size() * statistics.size();
    auto worker = [&] {
      for (std::size_t i = next++; i < items; i = next++) {
        const std::size_t c = i / statistics.size();
        const std::size_t s = i % statistics.size();
        try {
          AllanCurve curve = compute_allan_curve_bounded(series[c], statistics[s], taus,
                                                         confidence_level, settings.storage);
          std::lock_guard lock(error_mutex);
          auto& slot = result.curves[group_begin + c];
          if (slot.size() < statistics.size()) slot.resize(statistics.size());
          slot[s] = std::move(curve);
        } catch (...) {
          std::lock_guard lock(error_mutex);
          if (!first_error) first_error = std::current_exception();
        }
      }
    };
    const unsigned n_workers = static_cast<unsigned>(std::min<std::size_t>(threads, items));
    if (n_workers <= 1) {
      worker();
    } else {
      std::vector<std::thread> pool;
      for (unsigned t = 0; t < n_workers; ++t) pool.emplace_back(worker);
      for (auto& thread : pool) thread.join();
    }
    if (first_error) std::rethrow_exception(first_error);
    group_begin = group_end;
  } while (group_begin < channels);
  return result;
}

}  // namespace sigmatau
