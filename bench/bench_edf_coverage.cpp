// Coverage of the chi-squared intervals on simulated white FM (independent rate samples, as
// IMUs and the simulator produce), with each EDF model of `adev --edf greenhall|discrete`: how
// often the true deviation lies outside the nominal interval. For each run, M unit-variance
// normal rate samples at tau0 = 1 s; the deviation at m of ADEV, OADEV, HDEV and OHDEV, whose
// true value for this noise is 1/sqrt(m) for all four (AVAR = HVAR = sigma^2/m). The interval is
// chi_squared_interval with the EDF of equivalent_dof(statistic, alpha, m, N, model), with alpha
// either the one compute_allan_curve identifies (what `sigmatau adev` prints) or the true 0.
// Reported: the fraction of runs outside, split below/above, with its binomial standard error
// sqrt(p (1 - p) / runs), and Greenhall's EDF over the exact discrete EDF (discrete_edf), both
// at alpha 0. `discrete` is discrete_edf while m (d + 1) <= 100, Greenhall beyond.
// A plain program (not Google Benchmark): it measures coverage, not speed. Usage:
//   bench_edf_coverage [RUNS=4000] [SAMPLES=1000,10000,100000] [M=1,2,4,16] [CONFIDENCE=0.99]
// Run r (1-based) of a length M draws from std::mt19937_64 seeded with std::seed_seq{M, r}
// through std::normal_distribution, so the table is reproducible with the same standard library
// (libstdc++ here).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "sigmatau/allan_curve.hpp"
#include "sigmatau/confidence.hpp"
#include "sigmatau/phase_series.hpp"
#include "sigmatau/taus.hpp"

namespace {

using namespace sigmatau;

constexpr Statistic kStatistics[] = {Statistic::adev, Statistic::oadev, Statistic::hdev,
                                     Statistic::ohdev};
constexpr EdfModel kModels[] = {EdfModel::greenhall, EdfModel::discrete};
constexpr int kWhiteFm = 0;  // alpha of white FM (angle random walk)

std::vector<std::int64_t> parse_list(const std::string& text) {
  std::vector<std::int64_t> out;
  std::stringstream ss(text);
  for (std::string item; std::getline(ss, item, ',');) out.push_back(std::stoll(item));
  return out;
}

/// Misses of one (statistic, m, EDF model, alpha source) cell over the runs.
struct Cell {
  int below = 0;  // truth below the interval (the estimate came out high)
  int above = 0;  // truth above the interval
};

/// equivalent_dof, cached: the discrete model costs O(min(N, 64 k m)) per call.
class EdfCache {
 public:
  double operator()(Statistic statistic, int alpha, std::int64_t m, std::int64_t n,
                    EdfModel model) {
    const auto key =
        std::make_tuple(static_cast<int>(statistic), alpha, m, n, static_cast<int>(model));
    auto it = cache_.find(key);
    if (it == cache_.end())
      it = cache_.emplace(key, equivalent_dof(statistic, alpha, m, n, model)).first;
    return it->second;
  }

 private:
  std::map<std::tuple<int, int, std::int64_t, std::int64_t, int>, double> cache_;
};

}  // namespace

int main(int argc, char** argv) {
  const int runs = argc > 1 ? std::stoi(argv[1]) : 4000;
  const std::vector<std::int64_t> lengths = parse_list(argc > 2 ? argv[2] : "1000,10000,100000");
  const std::vector<std::int64_t> factors = parse_list(argc > 3 ? argv[3] : "1,2,4,16");
  const double confidence = argc > 4 ? std::stod(argv[4]) : 0.99;
  if (runs < 1 || lengths.empty() || factors.empty() || !(confidence > 0 && confidence < 1)) {
    std::cerr << "usage: bench_edf_coverage [RUNS=4000] [SAMPLES=1000,10000,100000] "
                 "[M=1,2,4,16] [CONFIDENCE=0.99]\n";
    return 2;
  }
  TauSpec taus;
  taus.kind = TauSpec::Kind::explicit_seconds;
  for (const std::int64_t m : factors) taus.seconds.push_back(static_cast<double>(m));

  std::printf("White FM, %d runs per length, nominal %.4g %% intervals; truth 1/sqrt(m).\n", runs,
              100 * confidence);
  std::printf(
      "Each cell: %% of runs whose truth lies outside the interval, +- its binomial "
      "standard error (%% with the truth below / above it).\nGreenhall/exact: Greenhall's "
      "EDF at alpha 0 over discrete_edf(statistic, 0, m, N).\n\n");
  std::printf(
      "| samples M | statistic | m | Greenhall/exact | greenhall, identified alpha | "
      "greenhall, alpha 0 | discrete, identified alpha | discrete, alpha 0 |\n"
      "|---|---|---|---|---|---|---|---|\n");
  EdfCache edf;
  for (const std::int64_t samples : lengths) {
    const std::int64_t n = samples + 1;  // phase points
    // (statistic, m, model, 0 identified alpha / 1 true alpha)
    std::map<std::tuple<int, std::int64_t, int, int>, Cell> cells;
    std::vector<double> y(static_cast<std::size_t>(samples));
    for (int run = 0; run < runs; ++run) {
      std::seed_seq seed{static_cast<std::uint64_t>(samples), static_cast<std::uint64_t>(run + 1)};
      std::mt19937_64 rng(seed);
      std::normal_distribution<double> normal(0.0, 1.0);
      for (double& v : y) v = normal(rng);
      const PhaseSeries series = PhaseSeries::from_rate(y, 1.0);
      for (const Statistic statistic : kStatistics) {
        const AllanCurve curve = compute_allan_curve(series, statistic, taus, confidence);
        for (const CurvePoint& p : curve.points) {
          const double truth = 1.0 / std::sqrt(static_cast<double>(p.value.m));
          for (const EdfModel model : kModels) {
            for (int source = 0; source < 2; ++source) {
              const int alpha = source == 0 ? p.confidence.noise.alpha : kWhiteFm;
              const double dof = edf(statistic, alpha, p.value.m, n, model);
              const Interval interval = chi_squared_interval(p.value.dev, dof, confidence);
              Cell& c =
                  cells[{static_cast<int>(statistic), p.value.m, static_cast<int>(model), source}];
              if (truth < interval.low) ++c.below;
              if (truth > interval.high) ++c.above;
            }
          }
        }
      }
    }
    for (const Statistic statistic : kStatistics) {
      for (const std::int64_t m : factors) {
        if (!cells.contains({static_cast<int>(statistic), m, 0, 0})) continue;  // out of reach
        std::printf("| %lld | %s | %lld | %.3f |", static_cast<long long>(samples),
                    std::string(to_string(statistic)).c_str(), static_cast<long long>(m),
                    edf(statistic, kWhiteFm, m, n, EdfModel::greenhall) /
                        discrete_edf(statistic, kWhiteFm, m, n));
        for (const EdfModel model : kModels) {
          for (int source = 0; source < 2; ++source) {
            const Cell& c =
                cells.at({static_cast<int>(statistic), m, static_cast<int>(model), source});
            const double r = runs;
            const double p = (c.below + c.above) / r;
            std::printf(" %.2f +- %.2f (%.2f / %.2f) |", 100 * p, 100 * std::sqrt(p * (1 - p) / r),
                        100 * c.below / r, 100 * c.above / r);
          }
        }
        std::printf("\n");
      }
    }
    std::fflush(stdout);
  }
  return 0;
}
