// Log reader throughput [MB/s of input] beside the raw std::from_chars limit on the same bytes.
//
// Input: a synthetic IMU log written once to the temp directory, 7 columns like a real static
// log: epoch time in s with 6 decimals, 3 gyro values (rad/s, ~1e-3, 6 decimals) and 3 accel
// values (m/s^2, ~9.8, 5 decimals); ~78 bytes per row. The same values are also written as TSV,
// whitespace text, gzip (when the `gzip` command exists) and raw f32.
//
// Run: build-*/bench/bench_log_reader [--benchmark_filter=...]; the "bytes_per_second" column
// is the number to report. No pass/fail: this measures, it does not judge.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "sigmatau/log_reader.hpp"

namespace {

/// Rows of the synthetic log: 400k rows ~ 31 MB of CSV, large against the 4 MiB read buffer and
/// small enough for a shared 2-core machine.
constexpr int kRows = 400000;

struct Files {
  std::string csv, tsv, txt, gz, f32;
  std::string csv_text;  // kept in memory for the from_chars limit
  bool have_gz = false;
  Files() = default;
  Files(Files&&) = default;
  ~Files() {  // the temp files go with the process
    for (const auto* p : {&csv, &tsv, &txt, &gz, &f32}) {
      if (!p->empty()) std::remove(p->c_str());
    }
  }
};

std::string write_text(const std::string& path, char delimiter, std::string* keep) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::string text = "t,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z\n";
  if (delimiter != ',') {
    for (char& c : text) {
      if (c == ',') c = delimiter;
    }
  }
  text.reserve(static_cast<std::size_t>(kRows) * 80);
  char line[256];
  for (int r = 0; r < kRows; ++r) {
    const double t = 1700000000.0 + r * 0.005;
    const int n = std::snprintf(line, sizeof line, "%.6f%c%.6f%c%.6f%c%.6f%c%.5f%c%.5f%c%.5f\n", t,
                                delimiter, 1e-3 * noise(rng), delimiter, 1e-3 * noise(rng),
                                delimiter, 1e-3 * noise(rng), delimiter, 0.01 * noise(rng),
                                delimiter, 0.01 * noise(rng), delimiter, 9.81 + 0.01 * noise(rng));
    text.append(line, static_cast<std::size_t>(n));
  }
  std::ofstream(path, std::ios::binary)
      .write(text.data(), static_cast<std::streamsize>(text.size()));
  if (keep) *keep = std::move(text);
  return path;
}

const Files& files() {
  static const Files f = [] {
    Files out;
    const auto dir = std::filesystem::temp_directory_path();
    const std::string base = (dir / ("sigmatau_bench_log_" + std::to_string(::getpid()))).string();
    out.csv = write_text(base + ".csv", ',', &out.csv_text);
    out.tsv = write_text(base + ".tsv", '\t', nullptr);
    out.txt = write_text(base + ".txt", ' ', nullptr);
    out.gz = base + ".csv.gz";
    out.have_gz =
        std::system(("gzip -1 -c " + out.csv + " > " + out.gz + " 2>/dev/null").c_str()) == 0;
    out.f32 = base + ".f32";
    std::vector<float> values(static_cast<std::size_t>(kRows) * 6);
    std::mt19937 rng(7);
    std::normal_distribution<float> noise(0.0f, 1.0f);
    for (float& v : values) v = noise(rng);
    std::ofstream(out.f32, std::ios::binary)
        .write(reinterpret_cast<const char*>(values.data()),
               static_cast<std::streamsize>(values.size() * sizeof(float)));
    return out;
  }();
  return f;
}

void read_all(benchmark::State& state, const sigmatau::LogOptions& options) {
  const auto bytes = static_cast<std::int64_t>(std::filesystem::file_size(options.path));
  std::int64_t rows = 0;
  for (auto _ : state) {
    sigmatau::LogReader reader(options);
    sigmatau::SampleBlock block;
    while (reader.read_block(block)) rows += block.rows();
    benchmark::DoNotOptimize(block);
  }
  state.SetBytesProcessed(bytes * state.iterations());
  state.counters["rows/s"] =
      benchmark::Counter(static_cast<double>(rows), benchmark::Counter::kIsRate);
}

/// The raw limit: from_chars over the CSV bytes, stepping over one delimiter per number, no
/// line handling, no column bookkeeping, no storage.
void BM_from_chars_limit(benchmark::State& state) {
  const std::string& text = files().csv_text;
  const char* begin = text.data() + text.find('\n') + 1;  // skip the header
  const char* end = text.data() + text.size();
  for (auto _ : state) {
    double sum = 0;
    for (const char* p = begin; p < end;) {
      double v = 0;
      const auto r = std::from_chars(p, end, v);
      sum += v;
      p = r.ptr + 1;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(end - begin) * state.iterations());
}
BENCHMARK(BM_from_chars_limit)->Unit(benchmark::kMillisecond);

void BM_read_csv_time_column(benchmark::State& state) {
  sigmatau::LogOptions o;
  o.path = files().csv;
  o.time_column = "t";
  read_all(state, o);
}
BENCHMARK(BM_read_csv_time_column)->Unit(benchmark::kMillisecond);

void BM_read_csv_all_columns(benchmark::State& state) {
  sigmatau::LogOptions o;
  o.path = files().csv;
  read_all(state, o);
}
BENCHMARK(BM_read_csv_all_columns)->Unit(benchmark::kMillisecond);

void BM_read_csv_buffer_bytes(benchmark::State& state) {
  sigmatau::LogOptions o;
  o.path = files().csv;
  o.time_column = "t";
  o.read_buffer_bytes = state.range(0);
  read_all(state, o);
}
BENCHMARK(BM_read_csv_buffer_bytes)
    ->Arg(64 << 10)
    ->Arg(1 << 20)
    ->Arg(16 << 20)
    ->Unit(benchmark::kMillisecond);

void BM_read_tsv(benchmark::State& state) {
  sigmatau::LogOptions o;
  o.path = files().tsv;
  o.time_column = "t";
  read_all(state, o);
}
BENCHMARK(BM_read_tsv)->Unit(benchmark::kMillisecond);

void BM_read_whitespace(benchmark::State& state) {
  sigmatau::LogOptions o;
  o.path = files().txt;
  o.time_column = "t";
  read_all(state, o);
}
BENCHMARK(BM_read_whitespace)->Unit(benchmark::kMillisecond);

/// Throughput in compressed bytes/s (the file as stored).
void BM_read_csv_gzip(benchmark::State& state) {
  if (!files().have_gz) {
    state.SkipWithError("no gzip command to make the input");
    return;
  }
  sigmatau::LogOptions o;
  o.path = files().gz;
  o.time_column = "t";
  read_all(state, o);
}
BENCHMARK(BM_read_csv_gzip)->Unit(benchmark::kMillisecond);

void BM_read_binary_f32(benchmark::State& state) {
  sigmatau::LogOptions o;
  o.path = files().f32;
  o.binary = sigmatau::BinaryFormat::f32;
  o.binary_channels = 6;
  read_all(state, o);
}
BENCHMARK(BM_read_binary_f32)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
