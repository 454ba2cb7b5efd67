// Exact Allan-family deviations with Stable32's term counts (NIST SP 1065, Riley 2008).
//
// Glossary (0-based phase points x_0..x_{N-1}; m = averaging factor; tau = m tau0; s = the
// series' rate_scale(m), which turns a phase difference over m samples into the rate unit):
//   AVAR   (eqs. 6-7, 11):  sum D2^2 / (2 n) * s^2        n = N-2m (overlapping) or
//                                                          floor((N-1)/m)-1 (stride m)
//   MVAR   (eq. 14):        sum V^2 / (2 m^2 n) * s^2     n = N-3m+1
//   TVAR   (eq. 15):        tau^2 / 3 * MVAR
//   HVAR   (eqs. 17-18, 20): sum D3^2 / (6 n) * s^2       n = N-3m (overlapping) or
//                                                          floor((N-1)/m)-2 (stride m)
//   TOTVAR (eq. 25):        sum over i = 1..N-2 of (x*[i-m] - 2x*[i] + x*[i+m])^2 / (2 (N-2)) * s^2
//                           with the doubly reflected phase x*; no bias correction.
// D2, D3, V and x* are defined in allan_sums.hpp. The phase of a log with values beyond about
// 1e-100..1e100 is held divided by a power of two (phase_store.hpp value_scale), by which each
// deviation is multiplied back. With rate data the rate form of each formula
// (differences of m-sample means) is the same number: s = 1/m and the phase is in samples x unit.
#include "sigmatau/allan.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <string>

#include "allan_sums.hpp"
#include "phase_store.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau {

Statistic parse_statistic(std::string_view text) {
  static constexpr Statistic kAll[] = {Statistic::adev, Statistic::oadev, Statistic::mdev,
                                       Statistic::tdev, Statistic::hdev,  Statistic::ohdev,
                                       Statistic::totdev};
  for (const Statistic s : kAll) {
    if (text == to_string(s)) return s;
  }
  throw Error("unknown statistic \"" + std::string(text) +
              "\": expected adev, oadev, mdev, tdev, hdev, ohdev or totdev");
}

std::string_view to_string(Statistic statistic) {
  switch (statistic) {
    case Statistic::adev: return "adev";
    case Statistic::oadev: return "oadev";
    case Statistic::mdev: return "mdev";
    case Statistic::tdev: return "tdev";
    case Statistic::hdev: return "hdev";
    case Statistic::ohdev: return "ohdev";
    case Statistic::totdev: return "totdev";
  }
  return "?";
}

std::int64_t term_count(Statistic statistic, std::int64_t m, std::int64_t n_phase_points) {
  const std::int64_t N = n_phase_points;
  if (m < 1 || N < 2) return 0;
  std::int64_t n = 0;
  switch (statistic) {
    case Statistic::adev: n = (N - 1) / m - 1; break;
    case Statistic::oadev: n = N - 2 * m; break;
    case Statistic::mdev:
    case Statistic::tdev: n = N - 3 * m + 1; break;
    case Statistic::hdev: n = (N - 1) / m - 2; break;
    case Statistic::ohdev: n = N - 3 * m; break;
    // The reflected series would allow m up to N-1, but Stable32 stops at half its data points
    // (N/2 for phase input) and beyond that most of each window is reflected data.
    case Statistic::totdev: n = (2 * m <= N) ? N - 2 : 0; break;
  }
  return std::max<std::int64_t>(n, 0);
}

namespace {

/// The OADEV sums of the factors (ascending, each with OADEV terms): those already computed on
/// this series are taken from its store, the others swept and kept there. TOTDEV's interior
/// terms are exactly the OADEV terms, so a curve of each shares one sweep; the sums of a factor
/// do not depend on the other factors swept with it or on the threads (bit for bit).
std::vector<double> allan_sums(const PhaseSeries& series, std::span<const std::int64_t> factors,
                               unsigned threads) {
  if (factors.empty()) return {};
  detail::PhaseStore& store = series.store();
  std::vector<double> sums(factors.size(), 0.0);
  std::vector<std::int64_t> missing, counts;
  {
    std::lock_guard lock(store.mutex);
    for (std::size_t t = 0; t < factors.size(); ++t) {
      const auto known = store.allan_sums.find(factors[t]);
      if (known != store.allan_sums.end()) {
        sums[t] = known->second;
      } else {
        missing.push_back(factors[t]);
        counts.push_back(term_count(Statistic::oadev, factors[t], series.size()));
      }
    }
  }
  if (missing.empty()) return sums;
  const std::vector<double> swept = detail::overlapping_sums(series, 2, missing, counts, threads);
  std::lock_guard lock(store.mutex);
  for (std::size_t t = 0, k = 0; t < factors.size() && k < missing.size(); ++t) {
    if (factors[t] != missing[k]) continue;
    sums[t] = swept[k];
    store.allan_sums.emplace(missing[k], swept[k]);
    ++k;
  }
  return sums;
}

}  // namespace

std::vector<DeviationPoint> compute_deviation(const PhaseSeries& series, Statistic statistic,
                                              std::span<const std::int64_t> m, unsigned threads) {
  for (const std::int64_t factor : m) {
    if (!(factor >= 1)) {
      throw Error("averaging factor must be >= 1, got " + std::to_string(factor));
    }
  }
  const std::int64_t N = series.size();
  std::vector<std::int64_t> factors;  // distinct factors with terms, ascending
  for (const std::int64_t factor : m) {
    if (term_count(statistic, factor, N) > 0) factors.push_back(factor);
  }
  std::sort(factors.begin(), factors.end());
  factors.erase(std::unique(factors.begin(), factors.end()), factors.end());

  std::vector<std::int64_t> counts;
  for (const std::int64_t factor : factors) counts.push_back(term_count(statistic, factor, N));

  std::vector<double> sums(factors.size(), 0.0);
  switch (statistic) {
    case Statistic::oadev:
      sums = allan_sums(series, factors, threads);
      break;
    case Statistic::ohdev:
      sums = detail::overlapping_sums(series, 3, factors, counts, threads);
      break;
    case Statistic::totdev: {
      // The interior N-2m terms are the OADEV terms; the 2(m-1) others reach past an end.
      sums = allan_sums(series, factors, threads);
      for (std::size_t t = 0; t < factors.size(); ++t) {
        sums[t] += detail::total_boundary_sum(series, factors[t]);
      }
      break;
    }
    case Statistic::adev:
    case Statistic::hdev:
      for (std::size_t t = 0; t < factors.size(); ++t) {
        sums[t] = detail::strided_sum(series, statistic == Statistic::adev ? 2 : 3, factors[t],
                                      counts[t]);
      }
      break;
    case Statistic::mdev:
    case Statistic::tdev:
      sums = detail::modified_sums(series, factors, counts, threads);
      break;
  }

  const double value_scale = series.store().value_scale;
  std::vector<DeviationPoint> points;
  points.reserve(m.size());
  for (const std::int64_t factor : m) {
    const auto it = std::lower_bound(factors.begin(), factors.end(), factor);
    if (it == factors.end() || *it != factor) continue;
    const std::size_t t = static_cast<std::size_t>(it - factors.begin());
    const double md = static_cast<double>(factor);
    const double tau = md * series.tau0_s();
    const double scale = series.rate_scale(factor);
    const double mean_square = sums[t] / static_cast<double>(counts[t]);
    double variance = 0.0;
    switch (statistic) {
      case Statistic::adev:
      case Statistic::oadev:
      case Statistic::totdev: variance = mean_square / 2.0 * scale * scale; break;
      case Statistic::hdev:
      case Statistic::ohdev: variance = mean_square / 6.0 * scale * scale; break;
      case Statistic::mdev: variance = mean_square / (2.0 * md * md) * scale * scale; break;
      case Statistic::tdev:
        variance = mean_square / (2.0 * md * md) * scale * scale * (tau * tau / 3.0);
        break;
    }
    // The phase is held divided by value_scale (1 for ordinary logs; phase_store.hpp).
    points.push_back({tau, factor, counts[t], std::sqrt(variance) * value_scale});
  }
  return points;
}

}  // namespace sigmatau
