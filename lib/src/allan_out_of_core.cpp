// Exact Allan-family curves out of core (see allan_out_of_core.hpp).
//
// The noise identification (noise_identification.hpp) and the curve assembly
// (allan_curve_assembly.hpp) are those of the in-memory path; only the averaged series of the
// identification lives in spillable storage here, so the results are identical bit for bit
// (tests/test_allan_out_of_core.cpp compares both).
#include "sigmatau/allan_out_of_core.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "allan_curve_assembly.hpp"
#include "noise_identification.hpp"
#include "parallel_items.hpp"
#include "phase_spill.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau {
namespace {

/// Series of up to resident_bytes / kInMemoryShare bytes (16 MiB by default) go to
/// identify_noise unchanged, in a std::vector.
constexpr std::int64_t kInMemoryShare = 16;

}  // namespace

NoiseIdentification identify_noise_bounded(const PhaseSeries& series, Statistic statistic,
                                           std::int64_t m, const PhaseStorage& storage) {
  if (!(m >= 1) || m >= series.size()) return identify_noise(series, statistic, m);
  const std::int64_t points = detail::averaged_series_points(series, m);
  const std::int64_t in_memory_points = storage.resident_bytes / kInMemoryShare / 8;
  if (points < detail::kMinAcfPoints || points <= in_memory_points) {
    return identify_noise(series, statistic, m);
  }
  detail::DoubleBuffer z(static_cast<std::size_t>(points), storage);
  detail::fill_averaged_series(series, m, z.data());
  return detail::identify_noise_by_acf(z.data(), static_cast<std::size_t>(points),
                                       series.kind() == DataKind::phase, statistic);
}

AllanCurve compute_allan_curve_bounded(const PhaseSeries& series, Statistic statistic,
                                       const TauSpec& taus, double confidence_level,
                                       const PhaseStorage& storage, EdfModel edf_model) {
  return detail::assemble_allan_curve(
      series, statistic, taus, confidence_level, edf_model,
      [&](std::int64_t m) { return identify_noise_bounded(series, statistic, m, storage); });
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
  const auto same_for_all = [&](std::int64_t, double) {
    return std::vector<TauSpec>(statistics.size(), taus);
  };
  return compute_allan_curves_out_of_core(log, kind, to_si, rate_hz, statistics, same_for_all,
                                          confidence_level, settings);
}

OutOfCoreResult compute_allan_curves_out_of_core(
    const LogOptions& log, DataKind kind, double to_si,
    const std::function<double(const TimingReport&)>& rate_hz,
    const std::vector<Statistic>& statistics, const TausForLength& taus_for,
    double confidence_level, const OutOfCoreSettings& settings) {
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
  std::vector<TauSpec> taus;  // per statistic, once the length is known
  std::size_t group_begin = 0;
  int pass = 0;
  // "pass 2 of 4 (phase, channels 1-2 of 3)"; the first pass, before the channels are known,
  // is "pass 1 (scan)".
  auto announce = [&](const char* what, std::size_t begin, std::size_t end) {
    if (!settings.stage) return;
    ++pass;
    if (channels == 0) {
      settings.stage("pass " + std::to_string(pass) + " (" + what + ")");
      return;
    }
    const std::size_t groups = (channels + threads - 1) / threads;
    settings.stage("pass " + std::to_string(pass) + " of " + std::to_string(2 * groups) + " (" +
                   what + ", channels " + std::to_string(begin + 1) + "-" + std::to_string(end) +
                   " of " + std::to_string(channels) + ")");
  };
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
      if (first && settings.first_pass_block) settings.first_pass_block(result.channel_names, block);
    };
    announce("scan", group_begin, std::min<std::size_t>(channels, group_begin + threads));
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
      // A phase series has one point more than the rate or increment samples it integrates.
      const std::int64_t phase_points = result.samples + (kind == DataKind::phase ? 0 : 1);
      taus = taus_for(phase_points, tau0_s);
      if (taus.size() != statistics.size()) {
        throw std::logic_error("taus_for returned " + std::to_string(taus.size()) +
                               " tau lists for " + std::to_string(statistics.size()) +
                               " statistics");
      }
    } else if (builders.front().samples() != result.samples) {
      throw Error(log.path + " changed while it was read (" + std::to_string(result.samples) +
                  " samples, then " + std::to_string(builders.front().samples()) + ")");
    }
    auto append = [&](SampleBlock& block) {
      for (std::size_t c = group_begin; c < group_end; ++c) builders[c - group_begin].append(block.values[c]);
    };
    announce("phase", group_begin, group_end);
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

    // (channel, statistic) items of the group on the pool.
    std::mutex result_mutex;
    detail::for_each_item_parallel(
        series.size() * statistics.size(), threads, [&](std::size_t i) {
          const std::size_t c = i / statistics.size();
          const std::size_t s = i % statistics.size();
          AllanCurve curve = compute_allan_curve_bounded(series[c], statistics[s], taus[s],
                                                         confidence_level, settings.storage,
                                                         settings.edf_model);
          std::lock_guard lock(result_mutex);
          auto& slot = result.curves[group_begin + c];
          if (slot.size() < statistics.size()) slot.resize(statistics.size());
          slot[s] = std::move(curve);
        });
    group_begin = group_end;
  } while (group_begin < channels);
  return result;
}

}  // namespace sigmatau
