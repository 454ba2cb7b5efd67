// Composition of the exact estimators and their confidence intervals, channel-parallel.
#include "sigmatau/allan_curve.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>

#include "sigmatau/error.hpp"

namespace sigmatau {

AllanCurve compute_allan_curve(const PhaseSeries& series, Statistic statistic,
                               const TauSpec& taus, double confidence_level) {
  if (!(confidence_level > 0.0 && confidence_level < 1.0)) {
    throw Error("confidence level must be between 0 and 1 (e.g. 0.683), got " +
                std::to_string(confidence_level));
  }
  const auto factors = averaging_factors(taus, statistic, series.size(), series.tau0_s());
  AllanCurve curve;
  curve.statistic = statistic;
  curve.confidence_level = confidence_level;
  for (const auto& point : compute_deviation(series, statistic, factors)) {
    curve.points.push_back({point, confidence_for(series, statistic, point, confidence_level)});
  }
  return curve;
}

std::vector<std::vector<AllanCurve>> compute_allan_curves(
    const std::vector<PhaseSeries>& channels, const std::vector<Statistic>& statistics,
    const TauSpec& taus, double confidence_level, unsigned threads) {
  std::vector<std::vector<AllanCurve>> result(channels.size(),
                                              std::vector<AllanCurve>(statistics.size()));
  // Work items are (channel, statistic) pairs so two channels still keep two cores busy.
  const std::size_t items = channels.size() * statistics.size();
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned>(std::min<std::size_t>(threads, std::max<std::size_t>(items, 1)));

  std::atomic<std::size_t> next{0};
  std::exception_ptr first_error;
  std::mutex error_mutex;
  auto worker = [&] {
    for (std::size_t i = next++; i < items; i = next++) {
      const std::size_t c = i / statistics.size();
      const std::size_t s = i % statistics.size();
      try {
        result[c][s] = compute_allan_curve(channels[c], statistics[s], taus, confidence_level);
      } catch (...) {
        std::lock_guard lock(error_mutex);
        if (!first_error) first_error = std::current_exception();
      }
    }
  };
  if (threads <= 1) {
    worker();
  } else {
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t) pool.emplace_back(worker);
    for (auto& thread : pool) thread.join();
  }
  if (first_error) std::rethrow_exception(first_error);
  return result;
}

}  // namespace sigmatau
