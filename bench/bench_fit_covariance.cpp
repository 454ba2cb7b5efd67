// Cost and error of the OAVAR covariance basis (lib/src/fit_covariance*.cpp): the lag sums by
// closed-form correlations and discrete Gauss quadrature against the previous FFT path
// (length 8 (m_a + m_b), kept as tests/support/fit_covariance_fft.cpp). A plain program (not
// Google Benchmark): it measures speed, memory and error together. Usage:
//   bench_fit_covariance [RUNS=5]            markdown report on stdout
//   bench_fit_covariance basis SAMPLES [old] one basis at octave factors (for /usr/bin/time -v)
// Sections: (1) the layouts of bench_fit_accuracy (octave taus): build time new vs old and the
// largest change of each lag sum; (2) the old path's flicker / Gauss-Markov error against the
// new (every lag) and against an FFT 4x longer; (3) bag lengths: time and peak RSS.
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "../lib/src/fit_covariance_lags.hpp"
#include "../lib/src/fit_internal.hpp"
#include "../tests/support/fit_covariance_fft.hpp"
#include "sigmatau/taus.hpp"

namespace {

using namespace sigmatau;
using namespace sigmatau::detail;
using Clock = std::chrono::steady_clock;

const char* const kNames[] = {"Q", "N", "B", "K", "GM"};

double peak_rss_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

std::vector<std::int64_t> octave_factors(std::int64_t samples, double tau0) {
  return averaging_factors(TauSpec{}, Statistic::oadev, samples + 1, tau0);
}

/// Every pair's lag sums by one path.
std::vector<LagSums> all_sums(const std::vector<std::int64_t>& m, std::int64_t n_phase, double tau0,
                              std::optional<double> gm, bool old_path,
                              std::int64_t lag_factor = 8) {
  std::vector<LagSums> out;
  for (std::size_t b = 0; b < m.size(); ++b) {
    for (std::size_t a = 0; a <= b; ++a) {
      out.push_back(old_path ? covariance_lag_sums_fft(m[a], m[b], n_phase, tau0, gm, lag_factor)
                             : covariance_lag_sums(PairCorrelation(m[a], m[b], tau0, gm ? std::vector<double>{*gm} : std::vector<double>{}), n_phase));
    }
  }
  return out;
}

/// Every lag summed one by one with the new path's correlations (its quadrature's reference),
/// accumulated in long double so that 4 million additions do not hide the quadrature's error.
LagSums direct_lag_sums(const PairCorrelation& corr, std::int64_t n_phase) {
  const std::int64_t na = n_phase - 2 * corr.ma(), nb = n_phase - 2 * corr.mb();
  const int t = corr.terms();
  std::vector<long double> cc(static_cast<std::size_t>(t * t)), c1(static_cast<std::size_t>(t));
  std::vector<double> c(static_cast<std::size_t>(t));
  for (std::int64_t lag = -(na - 1); lag <= nb - 1; ++lag) {
    corr.evaluate(static_cast<double>(lag), c);
    const auto w =
        static_cast<long double>(std::min(na, nb - lag) - std::max<std::int64_t>(0, -lag));
    for (std::size_t i = 0; i < c.size(); ++i) {
      c1[i] += w * c[i];
      for (std::size_t j = 0; j < c.size(); ++j) cc[i * c.size() + j] += w * c[i] * c[j];
    }
  }
  LagSums s{Eigen::MatrixXd::Zero(t, t), Eigen::VectorXd::Zero(t)};
  for (int i = 0; i < t; ++i) {
    s.c1(i) = static_cast<double>(c1[static_cast<std::size_t>(i)]);
    for (int j = 0; j < t; ++j) {
      s.cc(i, j) = static_cast<double>(cc[static_cast<std::size_t>(i * t + j)]);
    }
  }
  return s;
}

/// Largest change of each lag sum between two paths over all pairs: diagonal sums relative to
/// themselves, cross sums to the geometric mean of the two diagonals, ramp sums sum w c to
/// sqrt(n_a n_b sum w c^2) (the Cauchy-Schwarz bound of their size).
struct Change {
  double value = 0;
  std::int64_t ma = 0, mb = 0;
};
void report_changes(const std::vector<std::int64_t>& m, std::int64_t n_phase,
                    const std::vector<LagSums>& ref, const std::vector<LagSums>& x, int terms) {
  std::vector<std::vector<Change>> cc(static_cast<std::size_t>(terms),
                                      std::vector<Change>(static_cast<std::size_t>(terms)));
  std::vector<Change> c1(static_cast<std::size_t>(terms));
  std::size_t k = 0;
  for (std::size_t b = 0; b < m.size(); ++b) {
    for (std::size_t a = 0; a <= b; ++a, ++k) {
      const LagSums& r = ref[k];
      for (int i = 0; i < terms; ++i) {
        for (int j = 0; j <= i; ++j) {
          const double scale = std::sqrt(std::abs(r.cc(i, i) * r.cc(j, j)));
          const double v = std::abs(x[k].cc(i, j) - r.cc(i, j)) / scale;
          auto& c = cc[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
          if (v > c.value) c = {v, m[a], m[b]};
        }
        const double nn =
            static_cast<double>(n_phase - 2 * m[a]) * static_cast<double>(n_phase - 2 * m[b]);
        const double v = std::abs(x[k].c1(i) - r.c1(i)) / std::sqrt(nn * std::abs(r.cc(i, i)));
        if (v > c1[static_cast<std::size_t>(i)].value)
          c1[static_cast<std::size_t>(i)] = {v, m[a], m[b]};
      }
    }
  }
  std::printf("| sum | max change | at (m_a, m_b) |\n|---|---|---|\n");
  for (int i = 0; i < terms; ++i) {
    for (int j = 0; j <= i; ++j) {
      const auto& c = cc[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)];
      std::printf("| %s,%s | %.2e | (%lld, %lld) |\n", kNames[j], kNames[i], c.value,
                  static_cast<long long>(c.ma), static_cast<long long>(c.mb));
    }
  }
  for (int i = 0; i < terms; ++i) {
    const auto& c = c1[static_cast<std::size_t>(i)];
    std::printf("| R,%s | %.2e | (%lld, %lld) |\n", kNames[i], c.value,
                static_cast<long long>(c.ma), static_cast<long long>(c.mb));
  }
}

int basis_only(std::int64_t samples, bool old_path) {
  const double tau0 = 0.005;
  const auto m = octave_factors(samples, tau0);
  const auto t0 = Clock::now();
  double checksum = 0;
  if (old_path) {
    for (const auto& s : all_sums(m, samples + 1, tau0, std::nullopt, true)) checksum += s.cc(1, 1);
  } else {
    const CovarianceBasis basis = build_covariance_basis(m, samples + 1, tau0, {});
    for (const auto& h : basis.h) checksum += h(1, 1);
  }
  const double s = std::chrono::duration<double>(Clock::now() - t0).count();
  std::printf(
      "%s basis, %lld samples, %zu factors to %lld: %.3f s, peak RSS %.1f MiB (checksum %g)\n",
      old_path ? "old" : "new", static_cast<long long>(samples), m.size(),
      static_cast<long long>(m.back()), s, peak_rss_mib(), checksum);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 2 && std::string(argv[1]) == "basis") {
    return basis_only(std::atoll(argv[2]), argc > 3 && std::string(argv[3]) == "old");
  }
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  const int runs = argc > 1 ? std::atoi(argv[1]) : 5;
  std::printf("# OAVAR covariance basis: closed-form lag sums vs the previous FFT path\n\n");
  std::printf("Median of %d runs (old path: of %d), `nice -n 10` on a shared 2-core machine.\n\n",
              runs, std::max(1, runs / 2));

  struct Layout {
    const char* name;
    double rate_hz, hours;
  };
  const Layout layouts[] = {
      {"100 Hz, 2 h", 100, 2}, {"200 Hz, 2 h", 200, 2}, {"100 Hz, 3 h", 100, 3}};
  std::printf("## 1. bench_fit_accuracy layouts (octave taus, five linear terms)\n\n");
  for (const auto& layout : layouts) {
    const double tau0 = 1 / layout.rate_hz;
    const auto samples =
        static_cast<std::int64_t>(std::llround(layout.hours * 3600 * layout.rate_hz));
    const auto m = octave_factors(samples, tau0);
    std::vector<double> t_new, t_old;
    for (int r = 0; r < runs; ++r) {
      const auto t0 = Clock::now();
      const CovarianceBasis basis = build_covariance_basis(m, samples + 1, tau0, {});
      t_new.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    }
    const double rss_new = peak_rss_mib();
    std::vector<LagSums> old_sums;
    for (int r = 0; r < std::max(1, runs / 2); ++r) {
      const auto t0 = Clock::now();
      old_sums = all_sums(m, samples + 1, tau0, std::nullopt, true);
      t_old.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    }
    const auto new_sums = all_sums(m, samples + 1, tau0, std::nullopt, false);
    std::printf(
        "### %s (%lld samples, %zu factors to %lld)\n\nnew %.1f ms, old %.0f ms; peak RSS "
        "after the new runs %.1f MiB, after the old %.1f MiB.\nChange of the lag sums "
        "(old to new; the basis elements are these over 2 n_a n_b, Q,Q plus the same "
        "fourth-cumulant term in both):\n\n",
        layout.name, static_cast<long long>(samples), m.size(), static_cast<long long>(m.back()),
        median(t_new), median(t_old), rss_new, peak_rss_mib());
    report_changes(m, samples + 1, old_sums, new_sums, kLagTerms);
    std::printf("\n");
  }

  std::printf(
      "## 2. Error of the old path (window 8 (m_a + m_b)) for B and GM, and of the new one\n\n"
      "N = 2^21 samples, tau0 = 0.01 s; GM tau_c = 10 s (a = 1e-3). Relative difference of the "
      "diagonal sums B,B and GM,GM (and the worst cross sum of B with Q, N, K) against the new "
      "path: `old` the FFT of length 8 (m_a + m_b), `old x4` of length 32 (m_a + m_b) (- where "
      "that FFT would exceed 2^22 points); `every lag` is the new path against the direct sum "
      "of its own correlations over all 2N lags (the quadrature's error).\n\n"
      "| m_a | m_b | B,B old | B,B old x4 | worst B,x old | GM,GM old | GM,GM old x4 | B,B every "
      "lag | GM,GM every lag |\n|---|---|---|---|---|---|---|---|---|\n");
  const std::int64_t n_phase = (std::int64_t{1} << 21) + 1;
  const double tau0 = 0.01;
  const std::optional<double> gm = tau0 / 10.0;
  for (const auto& [ma, mb] :
       std::vector<std::pair<std::int64_t, std::int64_t>>{{1, 1},
                                                          {1, 4},
                                                          {16, 16},
                                                          {16, 64},
                                                          {256, 256},
                                                          {256, 1024},
                                                          {4096, 4096},
                                                          {4096, 16384},
                                                          {16384, 16384},
                                                          {16384, 65536},
                                                          {65536, 65536},
                                                          {262144, 262144}}) {
    const PairCorrelation corr(ma, mb, tau0, gm ? std::vector<double>{*gm} : std::vector<double>{});
    const LagSums fresh = covariance_lag_sums(corr, n_phase);
    const LagSums old8 = covariance_lag_sums_fft(ma, mb, n_phase, tau0, gm, 8);
    const bool x4 = 32 * (ma + mb) <= (std::int64_t{1} << 22);
    const LagSums old32 = x4 ? covariance_lag_sums_fft(ma, mb, n_phase, tau0, gm, 32) : old8;
    const LagSums direct = direct_lag_sums(corr, n_phase);
    const auto rel = [&](const LagSums& x, int i, int j) {
      return std::abs(x.cc(i, j) - fresh.cc(i, j)) /
             std::sqrt(std::abs(fresh.cc(i, i) * fresh.cc(j, j)));
    };
    double worst = 0;
    for (const int j : {0, 1, 3}) worst = std::max(worst, rel(old8, 2, j));
    char b32[32] = "-", g32[32] = "-";
    if (x4) {
      std::snprintf(b32, sizeof b32, "%.2e", rel(old32, 2, 2));
      std::snprintf(g32, sizeof g32, "%.2e", rel(old32, 4, 4));
    }
    std::printf("| %lld | %lld | %.2e | %s | %.2e | %.2e | %s | %.1e | %.1e |\n",
                static_cast<long long>(ma), static_cast<long long>(mb), rel(old8, 2, 2), b32, worst,
                rel(old8, 4, 4), g32, rel(direct, 2, 2), rel(direct, 4, 4));
  }

  std::printf(
      "\n## 3. Bag lengths (tau0 = 5 ms, octave factors)\n\n| samples | factors | new basis "
      "(median) | peak RSS of the process |\n|---|---|---|---|\n");
  for (const std::int64_t samples :
       {std::int64_t{1} << 22, std::int64_t{27000000}, std::int64_t{1} << 25}) {
    const auto m = octave_factors(samples, 0.005);
    std::vector<double> t;
    for (int r = 0; r < std::max(1, runs / 2); ++r) {
      const auto t0 = Clock::now();
      const CovarianceBasis basis = build_covariance_basis(m, samples + 1, 0.005, {});
      t.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    }
    std::printf("| %lld | %zu to %lld | %.1f ms | %.1f MiB |\n", static_cast<long long>(samples),
                m.size(), static_cast<long long>(m.back()), median(t), peak_rss_mib());
  }
  return 0;
}
