// adev: an explicit --taus list with several statistics, each computing the taus it can reach.
#include "adev_taus.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>

#include "sigmatau/error.hpp"

namespace sigmatau::cli {

/// Explicit --taus with several statistics: each statistic gets the asked taus it can reach on
/// `n_phase_points`; the ones it cannot are noted on stderr. A tau that no statistic reaches
/// stays in every list, so that averaging_factors reports it as before (exit 2).
std::vector<TauSpec> taus_per_statistic(const TauSpec& taus, const std::vector<Statistic>& stats,
                                        std::int64_t n_phase_points, double tau0_s,
                                        DataKind kind, const std::string& input) {
  std::vector<TauSpec> specs(stats.size(), taus);
  if (taus.kind != TauSpec::Kind::explicit_seconds || stats.size() < 2) return specs;
  for (auto& spec : specs) spec.seconds.clear();
  std::vector<std::string> skipped(stats.size());
  for (const double seconds : taus.seconds) {
    const double m = std::round(seconds / tau0_s);
    std::vector<bool> reach(stats.size());
    bool any = false;
    for (std::size_t s = 0; s < stats.size(); ++s) {
      reach[s] = m <= static_cast<double>(max_averaging_factor(stats[s], n_phase_points, kind));
      any = any || reach[s];
    }
    for (std::size_t s = 0; s < stats.size(); ++s) {
      if (reach[s] || !any) {
        specs[s].seconds.push_back(seconds);
      } else {
        char text[40];
        std::snprintf(text, sizeof text, "%g", seconds);
        skipped[s] += (skipped[s].empty() ? "" : ", ") + std::string(text);
      }
    }
  }
  for (std::size_t s = 0; s < stats.size(); ++s) {
    if (skipped[s].empty()) continue;
    const std::int64_t max_m = max_averaging_factor(stats[s], n_phase_points, kind);
    std::cerr << "sigmatau: note: " << input << ": " << to_string(stats[s])
              << " skips tau " << skipped[s] << " s: its longest on this log is "
              << static_cast<double>(max_m) * tau0_s << " s (m = " << max_m << ")\n";
  }
  return specs;
}

/// Stream mode leaves out the asked taus a statistic cannot reach (it knows the length only at
/// the end): the same note as taus_per_statistic, from the curves; an asked tau that is in no
/// curve at all is an Error, as in exact mode.
void note_stream_skipped(const TauSpec& taus, const std::vector<Statistic>& stats,
                         const std::vector<std::vector<AllanCurve>>& curves, double rate_hz,
                         const std::string& input) {
  if (taus.kind != TauSpec::Kind::explicit_seconds || curves.empty()) return;
  std::vector<std::string> skipped(stats.size());
  for (const double seconds : taus.seconds) {
    const auto m = static_cast<std::int64_t>(std::llround(seconds * rate_hz));
    std::vector<bool> has(stats.size(), false);
    bool any = false;
    for (std::size_t s = 0; s < stats.size(); ++s) {
      for (const auto& p : curves.front()[s].points) has[s] = has[s] || p.value.m == m;
      any = any || has[s];
    }
    char text[40];
    std::snprintf(text, sizeof text, "%g", seconds);
    if (!any) {
      throw Error("tau " + std::string(text) + " s is too long for " +
                  (stats.size() == 1 ? std::string(to_string(stats.front()))
                                     : std::string("every statistic asked")) +
                  " on this log (stream mode)");
    }
    for (std::size_t s = 0; s < stats.size(); ++s) {
      if (!has[s]) skipped[s] += (skipped[s].empty() ? "" : ", ") + std::string(text);
    }
  }
  for (std::size_t s = 0; s < stats.size(); ++s) {
    if (skipped[s].empty()) continue;
    std::cerr << "sigmatau: note: " << input << ": " << to_string(stats[s]) << " skips tau "
              << skipped[s] << " s: too long for it on this log\n";
  }
}

/// compute_allan_curves with the taus of taus_per_statistic.
std::vector<std::vector<AllanCurve>> curves_per_statistic(const std::vector<PhaseSeries>& series,
                                                          const std::vector<Statistic>& stats,
                                                          const TauSpec& taus, double ci,
                                                          unsigned threads, EdfModel edf_model,
                                                          const std::string& input) {
  const std::vector<TauSpec> specs = taus_per_statistic(
      taus, stats, static_cast<std::int64_t>(series.front().size()), series.front().tau0_s(),
      series.front().kind(), input);
  return curves_for_specs(specs, stats, [&](const std::vector<Statistic>& some, const TauSpec& t) {
    return compute_allan_curves(series, some, t, ci, threads, edf_model);
  });
}

std::vector<std::vector<AllanCurve>> curves_for_specs(const std::vector<TauSpec>& specs,
                                                      const std::vector<Statistic>& stats,
                                                      const CurveComputer& compute) {
  bool same = true;
  for (const auto& spec : specs) same = same && spec.seconds == specs.front().seconds;
  if (same) return compute(stats, specs.front());
  std::vector<std::vector<AllanCurve>> curves;
  for (std::size_t s = 0; s < stats.size(); ++s) {
    auto one = compute({stats[s]}, specs[s]);
    curves.resize(one.size());
    for (std::size_t c = 0; c < one.size(); ++c) curves[c].push_back(std::move(one[c].front()));
  }
  return curves;
}

}  // namespace sigmatau::cli
