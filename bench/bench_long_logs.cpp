// Speed against error for long logs (issue 3): exact in-memory OADEV against the single-pass
// stream mode at overlap densities K = 1..32, for N = 1e6, 1e7, 1e8 samples of one channel
// (white FM plus a rate random walk, like a gyro at rest), and the Welch PSD time per sample.
//
//   bench_long_logs OUT_PREFIX [--quick] [--runs R]
//
// writes OUT_PREFIX.md and OUT_PREFIX.csv and prints the Markdown table. Each configuration runs
// in its own child process (fork), so "peak RSS" is that configuration's own high-water mark
// (getrusage ru_maxrss, which includes the generated input where the mode needs it in memory).
// Times are medians over R runs (default 3) of wall-clock time, input generation excluded.
// Error columns compare each stream curve with the exact curve of the same data: max and median
// over taus of |dev / dev_exact - 1|, and the median over taus of edf / edf_exact (the price of
// the stride in confidence). --quick: N = 1e5 and 1e6, one run (a smoke test, seconds).
// Exact out-of-core mode is not implemented yet (see README): its row says so.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "sigmatau/allan_curve.hpp"
#include "sigmatau/allan_stream.hpp"
#include "sigmatau/psd.hpp"

using namespace sigmatau;

namespace {

constexpr double kTau0 = 0.01;                // 100 Hz
constexpr std::size_t kBlock = 1 << 16;       // samples generated per block
constexpr std::uint64_t kSeed = 20240603;

/// Deterministic block generator: white FM (sigma 1e-2) plus a slow rate random walk on an offset.
struct Generator {
  std::mt19937_64 rng{kSeed};
  std::normal_distribution<double> g{0.0, 1.0};
  double walk = 0.0;
  void fill(std::vector<double>& y) {
    for (auto& v : y) {
      walk += 1e-5 * g(rng);
      v = 0.02 + 1e-2 * g(rng) + walk;
    }
  }
};

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

/// What a child reports back.
struct Measurement {
  double seconds = 0;         // whole pipeline (curve with intervals)
  double seconds_values = 0;  // exact only: phase + deviations, no noise identification
  long peak_rss_kib = 0;
  std::vector<double> dev, edf;
  std::vector<std::int64_t> m;
};

std::string serialise(const Measurement& r) {
  std::ostringstream out;
  out.precision(17);
  out << r.seconds << ' ' << r.seconds_values << ' ' << r.peak_rss_kib << ' ' << r.dev.size();
  for (std::size_t i = 0; i < r.dev.size(); ++i) out << ' ' << r.m[i] << ' ' << r.dev[i] << ' ' << r.edf[i];
  return out.str();
}

Measurement parse(const std::string& text) {
  std::istringstream in(text);
  Measurement r;
  std::size_t n = 0;
  in >> r.seconds >> r.seconds_values >> r.peak_rss_kib >> n;
  r.dev.resize(n);
  r.edf.resize(n);
  r.m.resize(n);
  for (std::size_t i = 0; i < n; ++i) in >> r.m[i] >> r.dev[i] >> r.edf[i];
  return r;
}

long peak_rss_kib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;
}

void record_curve(const AllanCurve& curve, Measurement& r) {
  for (const auto& p : curve.points) {
    r.m.push_back(p.value.m);
    r.dev.push_back(p.value.dev);
    r.edf.push_back(p.confidence.edf);
  }
}

Measurement run_exact(std::int64_t n) {
  Measurement r;
  std::vector<double> y(static_cast<std::size_t>(n));
  Generator gen;
  for (std::size_t i = 0; i < y.size(); i += kBlock) {
    std::vector<double> block(std::min(kBlock, y.size() - i));
    gen.fill(block);
    std::copy(block.begin(), block.end(), y.begin() + static_cast<std::ptrdiff_t>(i));
  }
  const double t0 = now_s();
  const PhaseSeries series = PhaseSeries::from_rate(y, kTau0);
  const auto factors = averaging_factors(TauSpec{}, Statistic::oadev, series.size(), kTau0);
  const auto values = compute_deviation(series, Statistic::oadev, factors);
  const double t1 = now_s();
  const auto curve = compute_allan_curve(series, Statistic::oadev, TauSpec{}, 0.683);
  const double t2 = now_s();
  r.seconds_values = t1 - t0;
  r.seconds = (t1 - t0) + (t2 - t1);
  (void)values;
  record_curve(curve, r);
  return r;
}

Measurement run_stream(std::int64_t n, int density) {
  Measurement r;
  StreamSettings settings;
  settings.density = density;
  AllanStream stream(DataKind::rate, kTau0, settings);
  Generator gen;
  std::vector<double> block;
  double busy = 0;
  for (std::int64_t i = 0; i < n; i += static_cast<std::int64_t>(kBlock)) {
    block.resize(static_cast<std::size_t>(std::min<std::int64_t>(kBlock, n - i)));
    gen.fill(block);
    const double t0 = now_s();
    stream.add(block);
    busy += now_s() - t0;
  }
  const double t0 = now_s();
  const auto curve = stream.curves(0.683).front();
  busy += now_s() - t0;
  r.seconds = busy;
  record_curve(curve, r);
  return r;
}

Measurement run_psd(std::int64_t n) {
  Measurement r;
  WelchOptions options;
  WelchAccumulator welch(1.0 / kTau0, options, n);
  Generator gen;
  std::vector<double> block;
  double busy = 0;
  for (std::int64_t i = 0; i < n; i += static_cast<std::int64_t>(kBlock)) {
    block.resize(static_cast<std::size_t>(std::min<std::int64_t>(kBlock, n - i)));
    gen.fill(block);
    const double t0 = now_s();
    welch.add(block);
    busy += now_s() - t0;
  }
  const double t0 = now_s();
  const auto psd = welch.result();
  busy += now_s() - t0;
  r.seconds = busy;
  (void)psd;
  return r;
}

/// Runs `what` in a child process and returns its measurement (peak RSS of the child).
template <class F>
Measurement in_child(F what) {
  int fd[2];
  if (pipe(fd) != 0) {
    std::perror("pipe");
    std::exit(3);
  }
  const pid_t pid = fork();
  if (pid == 0) {
    close(fd[0]);
    Measurement r = what();
    r.peak_rss_kib = peak_rss_kib();
    const std::string text = serialise(r);
    std::size_t done = 0;
    while (done < text.size()) {
      const ssize_t k = write(fd[1], text.data() + done, text.size() - done);
      if (k <= 0) break;
      done += static_cast<std::size_t>(k);
    }
    close(fd[1]);
    _exit(0);
  }
  close(fd[1]);
  std::string text;
  char buffer[4096];
  for (ssize_t k; (k = read(fd[0], buffer, sizeof buffer)) > 0;) text.append(buffer, static_cast<std::size_t>(k));
  close(fd[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || text.empty()) {
    std::fprintf(stderr, "bench_long_logs: a child failed\n");
    std::exit(3);
  }
  return parse(text);
}

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t k = v.size() / 2;
  return v.size() % 2 ? v[k] : 0.5 * (v[k - 1] + v[k]);
}

struct Row {
  std::int64_t n = 0;
  std::string mode;
  double ns_per_sample = 0;
  double ns_values = std::nan("");
  double rss_mib = 0;
  double max_rel = std::nan(""), median_rel = std::nan(""), edf_ratio = std::nan("");
  double edf_ratio_min = std::nan("");
  double psd_ns = std::nan("");
};

std::string format(double v, const char* spec) {
  if (std::isnan(v)) return "-";
  char text[64];
  std::snprintf(text, sizeof text, spec, v);
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') {
    std::fprintf(stderr, "usage: bench_long_logs OUT_PREFIX [--quick] [--runs R]\n");
    return 2;
  }
  const std::string prefix = argv[1];
  bool quick = false;
  int runs = 3;
  for (int i = 2; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0) {
      quick = true;
      runs = 1;
    } else if (std::strcmp(argv[i], "--runs") == 0 && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else {
      std::fprintf(stderr, "bench_long_logs: unknown option %s\n", argv[i]);
      return 2;
    }
  }
  const std::vector<std::int64_t> sizes =
      quick ? std::vector<std::int64_t>{100'000, 1'000'000}
            : std::vector<std::int64_t>{1'000'000, 10'000'000, 100'000'000};
  const int densities[] = {1, 2, 4, 8, 16, 32};

  std::vector<Row> rows;
  for (const std::int64_t n : sizes) {
    std::vector<double> t, tv, psd_t;
    Measurement exact;
    long rss = 0;
    for (int r = 0; r < runs; ++r) {
      exact = in_child([n] { return run_exact(n); });
      t.push_back(exact.seconds);
      tv.push_back(exact.seconds_values);
      rss = std::max(rss, exact.peak_rss_kib);
      psd_t.push_back(in_child([n] { return run_psd(n); }).seconds);
    }
    const double psd_ns = median(psd_t) / static_cast<double>(n) * 1e9;
    Row row;
    row.n = n;
    row.mode = "exact in-memory";
    row.ns_per_sample = median(t) / static_cast<double>(n) * 1e9;
    row.ns_values = median(tv) / static_cast<double>(n) * 1e9;
    row.rss_mib = static_cast<double>(rss) / 1024.0;
    row.max_rel = 0;
    row.median_rel = 0;
    row.edf_ratio = 1;
    row.edf_ratio_min = 1;
    row.psd_ns = psd_ns;
    rows.push_back(row);
    Row ooc;
    ooc.n = n;
    ooc.mode = "exact out-of-core (not implemented)";
    ooc.ns_per_sample = std::nan("");
    ooc.rss_mib = std::nan("");
    rows.push_back(ooc);
    for (const int k : densities) {
      std::vector<double> ts;
      Measurement s;
      long srss = 0;
      for (int r = 0; r < runs; ++r) {
        s = in_child([n, k] { return run_stream(n, k); });
        ts.push_back(s.seconds);
        srss = std::max(srss, s.peak_rss_kib);
      }
      Row sr;
      sr.n = n;
      sr.mode = "stream K=" + std::to_string(k);
      sr.ns_per_sample = median(ts) / static_cast<double>(n) * 1e9;
      sr.rss_mib = static_cast<double>(srss) / 1024.0;
      std::vector<double> rel, ratio;
      for (std::size_t i = 0; i < s.m.size(); ++i) {
        const auto it = std::find(exact.m.begin(), exact.m.end(), s.m[i]);
        if (it == exact.m.end()) continue;
        const std::size_t j = static_cast<std::size_t>(it - exact.m.begin());
        rel.push_back(std::abs(s.dev[i] / exact.dev[j] - 1.0));
        ratio.push_back(s.edf[i] / exact.edf[j]);
      }
      sr.max_rel = rel.empty() ? std::nan("") : *std::max_element(rel.begin(), rel.end());
      sr.median_rel = median(rel);
      sr.edf_ratio = median(ratio);
      sr.edf_ratio_min = ratio.empty() ? std::nan("") : *std::min_element(ratio.begin(), ratio.end());
      sr.psd_ns = psd_ns;
      rows.push_back(sr);
    }
  }

  char host[256] = "unknown";
  gethostname(host, sizeof host);
  std::string cpu = "unknown CPU";
  {
    std::ifstream info("/proc/cpuinfo");
    for (std::string line; std::getline(info, line);) {
      if (line.rfind("model name", 0) == 0) {
        cpu = line.substr(line.find(':') + 2);
        break;
      }
    }
  }
  std::ostringstream md, csv;
  md << "OADEV at octave taus, one channel, 100 Hz white FM + rate random walk; " << cpu << ", "
     << sysconf(_SC_NPROCESSORS_ONLN) << " cores (" << host << "); median of " << runs
     << " run(s), single-threaded; each configuration in its own process.\n\n";
  md << "| N | mode | ns/sample | ns/sample (values only) | peak RSS [MiB] | max rel. dev. | "
        "median rel. dev. | EDF / exact (median) | EDF / exact (min) | PSD ns/sample |\n";
  md << "|---|---|---|---|---|---|---|---|---|---|\n";
  csv << "n,mode,ns_per_sample,ns_per_sample_values,peak_rss_mib,max_rel_dev,median_rel_dev,"
         "edf_ratio_median,edf_ratio_min,psd_ns_per_sample\n";
  for (const Row& r : rows) {
    md << "| " << format(static_cast<double>(r.n), "%.0e") << " | " << r.mode << " | "
       << format(r.ns_per_sample, "%.1f") << " | " << format(r.ns_values, "%.1f") << " | "
       << format(r.rss_mib, "%.0f") << " | " << format(r.max_rel, "%.2e") << " | "
       << format(r.median_rel, "%.2e") << " | " << format(r.edf_ratio, "%.3f") << " | "
       << format(r.edf_ratio_min, "%.3f") << " | " << format(r.psd_ns, "%.1f") << " |\n";
    csv << r.n << ',' << r.mode << ',' << format(r.ns_per_sample, "%.3f") << ','
        << format(r.ns_values, "%.3f") << ',' << format(r.rss_mib, "%.1f") << ','
        << format(r.max_rel, "%.4e") << ',' << format(r.median_rel, "%.4e") << ','
        << format(r.edf_ratio, "%.4f") << ',' << format(r.edf_ratio_min, "%.4f") << ','
        << format(r.psd_ns, "%.3f") << '\n';
  }
  std::cout << md.str();
  std::ofstream(prefix + ".md") << md.str();
  std::ofstream(prefix + ".csv") << csv.str();
  return 0;
}
