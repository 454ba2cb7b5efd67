// Speed against error for long logs (issue 3): exact OADEV in memory and out of core against the
// single-pass stream mode at overlap densities K = 1..32, for N = 1e6, 1e7, 1e8 samples of one
// channel (white FM plus a rate random walk, like a gyro at rest), and the Welch PSD time per
// sample.
//
//   bench_long_logs OUT_PREFIX [--quick] [--runs R]
//   bench_long_logs OUT_PREFIX --stream-only N [--runs R]
//
// writes OUT_PREFIX.md and OUT_PREFIX.csv and prints the Markdown table. Each configuration runs
// in its own child process (fork), so "peak RSS" is that configuration's own high-water mark
// (getrusage ru_maxrss, which includes the generated input where the mode needs it in memory).
// Times are medians over R runs (default 3), input generation excluded, both wall-clock and CPU
// time of the process (user + system: on a shared machine wall time also counts the time other
// processes held the cores; system time counts the kernel zeroing fresh pages).
//
// What a row times (one channel, OADEV at octave taus):
//   exact in-memory   PhaseSeries::from_rate on the samples in memory, then compute_allan_curve
//                     (the sweep, which first builds its compact copy of the phase, noise
//                     identification and intervals): what `sigmatau adev` does after reading.
//                     "phase" and "values" split it: the double-double phase alone, and
//                     compute_deviation alone on that phase (sweep + compact copy, no intervals).
//   exact out-of-core PhaseSeriesBuilder into spilled (file-backed, unlinked) storage in two
//                     passes over the samples, as delivered in blocks by the generator, then
//                     compute_allan_curve_bounded: `adev --mode exact` on a file larger than
//                     --memory, without the file reading and parsing.
//   stream K=k        AllanStream::add on the blocks, then curves().
// Error columns compare each curve with the exact in-memory curve of the same data: max and
// median over taus of |dev / dev_exact - 1|, and the median and minimum over taus of
// edf / edf_exact (the price of the stride in confidence). --quick: N = 1e5 and 1e6, one run
// (a smoke test, seconds).
// --stream-only N: only the stream rows at N samples (no exact reference, no ingestion table):
// prints CPU and wall ns per sample for each K and writes every curve (m, deviation, EDF, 17
// digits) to OUT_PREFIX_stream.txt, to compare two builds of the stream mode value for value.
//
// A second table (OUT_PREFIX.md, and OUT_PREFIX_ingest.csv) gives CSV ingestion: LogReader on a
// 1e6-row, 7-column IMU CSV (time stamp + 3 gyro + 3 accel, ~78 bytes a row, in the temp
// directory, page cache warm) in MB of input per CPU second, beside the raw std::from_chars
// limit on the same bytes (no line or column handling, no storage).
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <filesystem>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "bench_stats.hpp"
#include "sigmatau/allan_curve.hpp"
#include "sigmatau/allan_out_of_core.hpp"
#include "sigmatau/allan_stream.hpp"
#include "sigmatau/log_reader.hpp"
#include "sigmatau/psd.hpp"

using namespace sigmatau;

namespace {

using sigmatau::bench::median;

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
/// CPU time of the process so far (user + system, all threads) [s].
double cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// Wall-clock and CPU time of a stretch of work, accumulated over pieces.
struct Clock {
  double wall = 0, cpu = 0;
  double w0 = 0, c0 = 0;
  void start() {
    w0 = now_s();
    c0 = cpu_s();
  }
  void stop() {
    wall += now_s() - w0;
    cpu += cpu_s() - c0;
  }
};

/// What a child reports back.
struct Measurement {
  double seconds = 0;         // whole pipeline (phase + curve with intervals), wall clock
  double cpu_seconds = 0;     // the same, CPU time
  double seconds_phase = 0;   // exact only: the phase alone (CPU)
  double seconds_values = 0;  // exact only: compute_deviation alone (CPU)
  long peak_rss_kib = 0;
  std::vector<double> dev, edf;
  std::vector<std::int64_t> m;
};

std::string serialise(const Measurement& r) {
  std::ostringstream out;
  out.precision(17);
  out << r.seconds << ' ' << r.cpu_seconds << ' ' << r.seconds_phase << ' ' << r.seconds_values
      << ' ' << r.peak_rss_kib << ' ' << r.dev.size();
  for (std::size_t i = 0; i < r.dev.size(); ++i) out << ' ' << r.m[i] << ' ' << r.dev[i] << ' ' << r.edf[i];
  return out.str();
}

Measurement parse(const std::string& text) {
  std::istringstream in(text);
  Measurement r;
  std::size_t n = 0;
  in >> r.seconds >> r.cpu_seconds >> r.seconds_phase >> r.seconds_values >> r.peak_rss_kib >> n;
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
  Clock phase, values, curve_clock;
  phase.start();
  const PhaseSeries series = PhaseSeries::from_rate(y, kTau0);
  phase.stop();
  const auto factors = averaging_factors(TauSpec{}, Statistic::oadev, series.size(), kTau0);
  values.start();
  const auto points = compute_deviation(series, Statistic::oadev, factors);
  values.stop();
  (void)points;
  // The curve as the CLI computes it: the sweep copy is built again, in fresh pages.
  series.drop_sweep_cache();
  curve_clock.start();
  const auto curve = compute_allan_curve(series, Statistic::oadev, TauSpec{}, 0.683);
  curve_clock.stop();
  r.seconds = phase.wall + curve_clock.wall;
  r.cpu_seconds = phase.cpu + curve_clock.cpu;
  r.seconds_phase = phase.cpu;
  r.seconds_values = values.cpu;
  record_curve(curve, r);
  return r;
}

Measurement run_out_of_core(std::int64_t n) {
  Measurement r;
  const PhaseStorage storage = spilled_storage();
  PhaseSeriesBuilder builder(DataKind::rate, storage);
  std::vector<double> block;
  Clock clock;
  for (int pass = 0; pass < 2; ++pass) {
    Generator gen;  // the same samples twice, as a file read twice
    for (std::int64_t i = 0; i < n; i += static_cast<std::int64_t>(kBlock)) {
      block.resize(static_cast<std::size_t>(std::min<std::int64_t>(kBlock, n - i)));
      gen.fill(block);
      clock.start();
      if (pass == 0) {
        builder.scan(block);
      } else {
        builder.append(block);
      }
      clock.stop();
    }
  }
  clock.start();
  const PhaseSeries series = builder.finish(kTau0);
  const auto curve =
      compute_allan_curve_bounded(series, Statistic::oadev, TauSpec{}, 0.683, storage);
  clock.stop();
  r.seconds = clock.wall;
  r.cpu_seconds = clock.cpu;
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
  Clock clock;
  for (std::int64_t i = 0; i < n; i += static_cast<std::int64_t>(kBlock)) {
    block.resize(static_cast<std::size_t>(std::min<std::int64_t>(kBlock, n - i)));
    gen.fill(block);
    clock.start();
    stream.add(block);
    clock.stop();
  }
  clock.start();
  const auto curve = stream.curves(0.683).front();
  clock.stop();
  r.seconds = clock.wall;
  r.cpu_seconds = clock.cpu;
  record_curve(curve, r);
  return r;
}

Measurement run_psd(std::int64_t n) {
  Measurement r;
  WelchOptions options;
  WelchAccumulator welch(1.0 / kTau0, options, n);
  Generator gen;
  std::vector<double> block;
  Clock clock;
  for (std::int64_t i = 0; i < n; i += static_cast<std::int64_t>(kBlock)) {
    block.resize(static_cast<std::size_t>(std::min<std::int64_t>(kBlock, n - i)));
    gen.fill(block);
    clock.start();
    welch.add(block);
    clock.stop();
  }
  clock.start();
  const auto psd = welch.result();
  clock.stop();
  r.seconds = clock.wall;
  r.cpu_seconds = clock.cpu;
  (void)psd;
  return r;
}

/// The CSV of the ingestion table: kIngestRows rows like a static IMU log.
constexpr int kIngestRows = 1'000'000;
std::string write_ingest_csv(const std::string& path) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> g(0.0, 1.0);
  std::string text = "t,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z\n";
  char line[256];
  for (int r = 0; r < kIngestRows; ++r) {
    const int k = std::snprintf(line, sizeof line, "%.6f,%.6f,%.6f,%.6f,%.5f,%.5f,%.5f\n",
                                1700000000.0 + r * 0.005, 1e-3 * g(rng), 1e-3 * g(rng),
                                1e-3 * g(rng), 0.01 * g(rng), 0.01 * g(rng),
                                9.81 + 0.01 * g(rng));
    text.append(line, static_cast<std::size_t>(k));
  }
  std::ofstream(path, std::ios::binary).write(text.data(), static_cast<std::streamsize>(text.size()));
  return text;
}

/// LogReader over the whole file (time column t, the six others as channels): CPU seconds.
Measurement run_ingest(const std::string& path) {
  Measurement r;
  LogOptions options;
  options.path = path;
  options.time_column = "t";
  Clock clock;
  clock.start();
  LogReader reader(options);
  SampleBlock block;
  std::int64_t rows = 0;
  while (reader.read_block(block)) rows += block.rows();
  clock.stop();
  if (rows != kIngestRows) {
    std::fprintf(stderr, "bench_long_logs: read %lld rows of %d\n", static_cast<long long>(rows),
                 kIngestRows);
    std::exit(3);
  }
  r.seconds = clock.wall;
  r.cpu_seconds = clock.cpu;
  return r;
}

/// std::from_chars over the same bytes, one delimiter skipped per number: CPU seconds.
Measurement run_from_chars(const std::string& text) {
  Measurement r;
  const char* begin = text.data() + text.find('\n') + 1;  // after the header
  const char* end = text.data() + text.size();
  Clock clock;
  clock.start();
  double sum = 0;
  for (const char* p = begin; p < end;) {
    double v = 0;
    const auto result = std::from_chars(p, end, v);
    sum += v;
    p = result.ptr + 1;
  }
  clock.stop();
  if (!(sum > 0)) std::exit(3);  // keeps the loop
  r.seconds = clock.wall;
  r.cpu_seconds = clock.cpu;
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

struct Row {
  std::int64_t n = 0;
  std::string mode;
  double ns_per_sample = 0;  // wall clock
  double ns_cpu = 0;         // CPU time
  double ns_phase = std::nan("");
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
    std::fprintf(stderr,
                 "usage: bench_long_logs OUT_PREFIX [--quick] [--runs R]\n"
                 "       bench_long_logs OUT_PREFIX --stream-only N [--runs R]\n");
    return 2;
  }
  const std::string prefix = argv[1];
  bool quick = false;
  int runs = 3;
  std::int64_t stream_only = 0;
  for (int i = 2; i < argc; ++i) {
    if (std::strcmp(argv[i], "--stream-only") == 0 && i + 1 < argc) {
      stream_only = std::max<std::int64_t>(1, std::atoll(argv[++i]));
    } else if (std::strcmp(argv[i], "--quick") == 0) {
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
  if (stream_only > 0) {
    std::ostringstream values;
    values.precision(17);
    std::printf("N %lld, median of %d run(s)\n| K | wall ns/sample | CPU ns/sample |\n|---|---|---|\n",
                static_cast<long long>(stream_only), runs);
    for (const int k : densities) {
      std::vector<double> ts, tsc;
      Measurement s;
      for (int r = 0; r < runs; ++r) {
        s = in_child([stream_only, k] { return run_stream(stream_only, k); });
        ts.push_back(s.seconds);
        tsc.push_back(s.cpu_seconds);
      }
      std::printf("| %d | %.2f | %.2f |\n", k, median(ts) / static_cast<double>(stream_only) * 1e9,
                  median(tsc) / static_cast<double>(stream_only) * 1e9);
      std::fflush(stdout);
      for (std::size_t i = 0; i < s.m.size(); ++i) {
        values << k << ' ' << s.m[i] << ' ' << s.dev[i] << ' ' << s.edf[i] << '\n';
      }
    }
    std::ofstream(prefix + "_stream.txt") << values.str();
    return 0;
  }

  std::vector<Row> rows;
  const auto per_sample = [](const std::vector<double>& seconds, std::int64_t n) {
    return median(seconds) / static_cast<double>(n) * 1e9;
  };
  /// Deviation of curve `c` from the exact curve, over the taus both have.
  const auto compare = [](const Measurement& c, const Measurement& exact, Row& row) {
    std::vector<double> rel, ratio;
    for (std::size_t i = 0; i < c.m.size(); ++i) {
      const auto it = std::find(exact.m.begin(), exact.m.end(), c.m[i]);
      if (it == exact.m.end()) continue;
      const std::size_t j = static_cast<std::size_t>(it - exact.m.begin());
      rel.push_back(std::abs(c.dev[i] / exact.dev[j] - 1.0));
      ratio.push_back(c.edf[i] / exact.edf[j]);
    }
    row.max_rel = rel.empty() ? std::nan("") : *std::max_element(rel.begin(), rel.end());
    row.median_rel = median(rel);
    row.edf_ratio = median(ratio);
    row.edf_ratio_min = ratio.empty() ? std::nan("") : *std::min_element(ratio.begin(), ratio.end());
  };
  for (const std::int64_t n : sizes) {
    std::vector<double> t, tc, tp, tv, psd_t;
    Measurement exact;
    long rss = 0;
    for (int r = 0; r < runs; ++r) {
      exact = in_child([n] { return run_exact(n); });
      t.push_back(exact.seconds);
      tc.push_back(exact.cpu_seconds);
      tp.push_back(exact.seconds_phase);
      tv.push_back(exact.seconds_values);
      rss = std::max(rss, exact.peak_rss_kib);
      psd_t.push_back(in_child([n] { return run_psd(n); }).cpu_seconds);
    }
    const double psd_ns = per_sample(psd_t, n);
    Row row;
    row.n = n;
    row.mode = "exact in-memory";
    row.ns_per_sample = per_sample(t, n);
    row.ns_cpu = per_sample(tc, n);
    row.ns_phase = per_sample(tp, n);
    row.ns_values = per_sample(tv, n);
    row.rss_mib = static_cast<double>(rss) / 1024.0;
    row.max_rel = 0;
    row.median_rel = 0;
    row.edf_ratio = 1;
    row.edf_ratio_min = 1;
    row.psd_ns = psd_ns;
    rows.push_back(row);

    std::vector<double> to, toc;
    Measurement ooc;
    long orss = 0;
    for (int r = 0; r < runs; ++r) {
      ooc = in_child([n] { return run_out_of_core(n); });
      to.push_back(ooc.seconds);
      toc.push_back(ooc.cpu_seconds);
      orss = std::max(orss, ooc.peak_rss_kib);
    }
    Row orow;
    orow.n = n;
    orow.mode = "exact out-of-core";
    orow.ns_per_sample = per_sample(to, n);
    orow.ns_cpu = per_sample(toc, n);
    orow.rss_mib = static_cast<double>(orss) / 1024.0;
    compare(ooc, exact, orow);
    orow.psd_ns = psd_ns;
    rows.push_back(orow);

    for (const int k : densities) {
      std::vector<double> ts, tsc;
      Measurement s;
      long srss = 0;
      for (int r = 0; r < runs; ++r) {
        s = in_child([n, k] { return run_stream(n, k); });
        ts.push_back(s.seconds);
        tsc.push_back(s.cpu_seconds);
        srss = std::max(srss, s.peak_rss_kib);
      }
      Row sr;
      sr.n = n;
      sr.mode = "stream K=" + std::to_string(k);
      sr.ns_per_sample = per_sample(ts, n);
      sr.ns_cpu = per_sample(tsc, n);
      sr.rss_mib = static_cast<double>(srss) / 1024.0;
      compare(s, exact, sr);
      sr.psd_ns = psd_ns;
      rows.push_back(sr);
    }
  }

  // CSV ingestion.
  const std::string csv_path =
      (std::filesystem::temp_directory_path() /
       ("sigmatau_bench_long_logs_" + std::to_string(::getpid()) + ".csv"))
          .string();
  const std::string csv_text = write_ingest_csv(csv_path);
  std::vector<double> ingest_cpu, ingest_wall, parse_cpu;
  for (int r = 0; r < std::max(runs, 3); ++r) {
    const Measurement m = in_child([&] { return run_ingest(csv_path); });
    ingest_cpu.push_back(m.cpu_seconds);
    ingest_wall.push_back(m.seconds);
    parse_cpu.push_back(in_child([&] { return run_from_chars(csv_text); }).cpu_seconds);
  }
  std::remove(csv_path.c_str());
  const double csv_mb = static_cast<double>(csv_text.size()) / 1e6;

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
     << " run(s), single-threaded; each configuration in its own process.\n\n"
     << "Columns: *wall* and *CPU* are ns per sample of the whole computation after the samples "
        "are in memory (exact: double-double phase + curve with noise identification and "
        "intervals, the sweep copy built in fresh pages; out-of-core: both passes into "
        "file-backed storage + curve; stream: one pass + curves), wall clock and process CPU "
        "time (user + system; the machine is shared, so wall time includes waiting for the "
        "cores). *phase* and *values* (exact in-memory only, CPU) split the exact path: "
        "PhaseSeries::from_rate alone, and compute_deviation alone (sweep + its compact copy, "
        "no intervals). *PSD* is the Welch PSD's CPU ns per sample on the same data. Errors "
        "and EDF ratios are against the exact in-memory curve.\n\n";
  md << "| N | mode | wall ns/sample | CPU ns/sample | phase ns/sample | values ns/sample | "
        "peak RSS [MiB] | max rel. dev. | median rel. dev. | EDF / exact (median) | "
        "EDF / exact (min) | PSD ns/sample |\n";
  md << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  csv << "n,mode,wall_ns_per_sample,cpu_ns_per_sample,phase_ns_per_sample,values_ns_per_sample,"
         "peak_rss_mib,max_rel_dev,median_rel_dev,edf_ratio_median,edf_ratio_min,"
         "psd_ns_per_sample\n";
  for (const Row& r : rows) {
    md << "| " << format(static_cast<double>(r.n), "%.0e") << " | " << r.mode << " | "
       << format(r.ns_per_sample, "%.1f") << " | " << format(r.ns_cpu, "%.1f") << " | "
       << format(r.ns_phase, "%.1f") << " | " << format(r.ns_values, "%.1f") << " | "
       << format(r.rss_mib, "%.0f") << " | " << format(r.max_rel, "%.2e") << " | "
       << format(r.median_rel, "%.2e") << " | " << format(r.edf_ratio, "%.3f") << " | "
       << format(r.edf_ratio_min, "%.3f") << " | " << format(r.psd_ns, "%.1f") << " |\n";
    csv << r.n << ',' << r.mode << ',' << format(r.ns_per_sample, "%.3f") << ','
        << format(r.ns_cpu, "%.3f") << ',' << format(r.ns_phase, "%.3f") << ','
        << format(r.ns_values, "%.3f") << ',' << format(r.rss_mib, "%.1f") << ','
        << format(r.max_rel, "%.4e") << ',' << format(r.median_rel, "%.4e") << ','
        << format(r.edf_ratio, "%.4f") << ',' << format(r.edf_ratio_min, "%.4f") << ','
        << format(r.psd_ns, "%.3f") << '\n';
  }
  std::ostringstream ingest_csv;
  md << "\nCSV ingestion, one core: LogReader on a " << kIngestRows << "-row, 7-column IMU CSV ("
     << format(csv_mb, "%.0f") << " MB; time column + 6 channels, page cache warm), median of "
     << ingest_cpu.size() << " runs, beside the raw std::from_chars limit on the same bytes.\n\n"
     << "| what | MB/s per CPU second | MB/s wall | rows/s per CPU second |\n|---|---|---|---|\n"
     << "| LogReader (CSV, time column) | " << format(csv_mb / median(ingest_cpu), "%.0f") << " | "
     << format(csv_mb / median(ingest_wall), "%.0f") << " | "
     << format(kIngestRows / median(ingest_cpu), "%.3g") << " |\n"
     << "| raw std::from_chars limit | " << format(csv_mb / median(parse_cpu), "%.0f")
     << " | - | - |\n";
  ingest_csv << "what,mb_per_cpu_second,mb_per_wall_second,rows_per_cpu_second\n"
             << "logreader_csv_time_column," << format(csv_mb / median(ingest_cpu), "%.1f") << ','
             << format(csv_mb / median(ingest_wall), "%.1f") << ','
             << format(kIngestRows / median(ingest_cpu), "%.0f") << '\n'
             << "from_chars_limit," << format(csv_mb / median(parse_cpu), "%.1f") << ",-,-\n";
  std::cout << md.str();
  std::ofstream(prefix + ".md") << md.str();
  std::ofstream(prefix + ".csv") << csv.str();
  std::ofstream(prefix + "_ingest.csv") << ingest_csv.str();
  return 0;
}
