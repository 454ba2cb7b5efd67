// The bounded-memory analyze chain (run_analysis_bounded) writes the same results.json and filter
// files as the in-memory one (run_analysis), bit for bit; and its streaming pieces (RunChecker,
// WarmupBlockSums) equal their whole-array counterparts whatever the block sizes.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "sigmatau/analysis.hpp"
#include "sigmatau/data_checks.hpp"
#include "sigmatau/units.hpp"
#include "sigmatau/warmup.hpp"
#include "temp_dir.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

/// Feeds `x` to `add` in pieces of random length 1..max_piece.
template <class Add>
void in_pieces(const std::vector<double>& x, std::size_t max_piece, std::uint64_t seed, Add add) {
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::size_t> length(1, max_piece);
  std::size_t i = 0;
  while (i < x.size()) {
    const std::size_t n = std::min(length(rng), x.size() - i);
    add(std::span<const double>(x.data() + i, n));
    i += n;
  }
}

std::vector<std::string> messages(const std::vector<DataWarning>& warnings) {
  std::vector<std::string> out;
  for (const auto& w : warnings) out.push_back(w.message);
  return out;
}

/// A static IMU log at 100 Hz with what the chain reports on: a warm-up transient on gx, a
/// clipped stretch on gy (at its maximum), a stuck stretch on gz, an accelerometer written in g
/// (declared m/s^2 below: a unit warning) and a temperature column without a sensor role.
void write_log(const std::string& path, std::int64_t rows) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::ofstream out(path);
  out << "t,gx,gy,gz,ax,ay,az,temp\n";
  char line[512];
  for (std::int64_t i = 0; i < rows; ++i) {
    const double t = static_cast<double>(i) / 100.0;
    double gx = 0.01 * noise(rng) + 0.5 * std::exp(-t / 20.0);  // settles over ~100 s
    double gy = 0.01 * noise(rng);
    double gz = 0.01 * noise(rng);
    if (i >= 5000 && i < 5012) gy = 0.25;   // clipped: 12 rows at the channel maximum
    if (i >= 9000 && i < 9080) gz = 0.003;  // stuck: 80 identical rows
    const double ax = 0.002 * noise(rng), ay = 0.002 * noise(rng), az = 1.0 + 0.002 * noise(rng);
    std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", t, gx, gy,
                  gz, ax, ay, az, 25.0 + 0.01 * noise(rng));
    out << line;
  }
}

/// The channels the CLI would pick (roles by name), gyro declared in deg/s.
std::vector<BoundedChannel> choose(const std::vector<std::string>& names, DataKind kind) {
  std::vector<BoundedChannel> out;
  for (std::size_t c = 0; c < names.size(); ++c) {
    BoundedChannel b;
    b.column = c;
    b.name = names[c];
    b.role = classify_channel(names[c]);
    if (b.role && b.role->sensor == Sensor::gyro) {
      b.input_unit = kind == DataKind::rate ? "deg/s" : "deg";
      b.to_si = parse_unit(b.input_unit).factor;
    }
    out.push_back(b);
  }
  return out;
}

/// run_analysis on the log read into memory, channels chosen and scaled as `choose` says.
AnalysisOutput in_memory(const LogOptions& log, DataKind kind, const AnalysisOptions& options) {
  Log read = read_log(log);
  AnalysisInput input;
  input.path = log.path;
  input.kind = kind;
  input.rate_hz = read.timing.rate_hz;
  input.timing = read.timing;
  for (const auto& b : choose(read.channel_names, kind)) {
    AnalysisChannel channel;
    channel.name = b.name;
    channel.role = b.role;
    channel.values = read.channels[b.column];
    if (b.to_si != 1) {
      for (double& v : channel.values) v *= b.to_si;
    }
    input.input_units.push_back(b.input_unit);
    input.channels.push_back(std::move(channel));
  }
  return run_analysis(std::move(input), options);
}

AnalysisOutput bounded(const LogOptions& log, DataKind kind, const AnalysisOptions& options,
                       const std::string& temp_dir) {
  BoundedAnalysisSource source;
  source.log = log;
  source.channels = [&](const std::vector<std::string>& names) { return choose(names, kind); };
  source.rate_hz = [](const TimingReport& timing) { return timing.rate_hz; };
  source.storage.directory = temp_dir;
  source.storage.resident_bytes = std::int64_t{1} << 20;  // 1 MiB: forces the spilled code paths
  AnalysisInput input;
  input.path = log.path;
  input.kind = kind;
  return run_analysis_bounded(source, std::move(input), options);
}

}  // namespace

TEST_CASE("RunChecker in pieces gives check_runs' warnings, bit for bit") {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<double> x(20000);
  for (auto& v : x) v = std::round(noise(rng) * 4.0);  // quantized: many short chance runs
  SUBCASE("clipped at both extremes, and stuck") {
    for (int i = 100; i < 110; ++i) x[i] = 30;   // maximum, 10 rows
    for (int i = 700; i < 706; ++i) x[i] = 30;   // again, 6 rows
    for (int i = 900; i < 920; ++i) x[i] = -30;  // minimum
    for (int i = 5000; i < 5070; ++i) x[i] = 2;  // stuck, 70 rows
  }
  SUBCASE("a run at an early minimum, then a lower one (the early run must be dropped)") {
    for (int i = 50; i < 60; ++i) x[i] = -20;
    for (int i = 8000; i < 8007; ++i) x[i] = -25;
  }
  SUBCASE("non-finite values and signed zeros") {
    for (int i = 10; i < 20; ++i) x[i] = NAN;
    for (int i = 30; i < 90; ++i) x[i] = INFINITY;
    for (int i = 200; i < 260; ++i) x[i] = (i % 2) ? 0.0 : -0.0;
  }
  SUBCASE("constant") { std::fill(x.begin(), x.end(), 1.5); }
  const auto whole = messages(check_runs(x, "c"));
  for (std::size_t max_piece : {1, 7, 1000, 30000}) {
    RunChecker checker("c");
    in_pieces(x, max_piece, max_piece, [&](std::span<const double> p) { checker.add(p); });
    CHECK(messages(checker.finish()) == whole);
  }
}

TEST_CASE("WarmupBlockSums in pieces gives detect_warmup's block means") {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<double> x(123457);  // not a multiple of the block count: a tail is left out
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] = noise(rng) + 30.0 * std::exp(-static_cast<double>(i) / 4000.0);
  }
  WarmupBlockSums whole(static_cast<std::int64_t>(x.size()));
  whole.add(x);
  WarmupBlockSums pieces(static_cast<std::int64_t>(x.size()));
  in_pieces(x, 5000, 9, [&](std::span<const double> p) { pieces.add(p); });
  CHECK(pieces.blocks().block_samples == whole.blocks().block_samples);
  CHECK(pieces.blocks().means == whole.blocks().means);  // exact: the same sums, same order
  const WarmupDecision d = decide_warmup({pieces.blocks()}, 100.0);
  CHECK(d.trim_samples > 0);
  CHECK(d.trim_samples == detect_warmup({x}, 100.0).trim_samples);
}

TEST_CASE("the bounded analysis writes the in-memory analysis' results, bit for bit") {
  test::TempDir dir("analysis_bounded");
  const std::string path = dir.file("imu.csv").string();
  write_log(path, 30000);  // 300 s
  LogOptions log;
  log.path = path;
  log.time_column = "t";
  log.read_buffer_bytes = 100000;  // many reader blocks
  AnalysisOptions options;
  options.created_utc = "fixed";
  options.spec = std::nullopt;
  DataKind kind = DataKind::rate;
  SUBCASE("rate, automatic trim, two statistics, dynamic windows, one thread") {
    options.statistics = {Statistic::oadev, Statistic::mdev};
    options.dynamic_windows = 4;
    options.threads = 1;
  }
  SUBCASE("rate, two threads (channel groups of two), filter rates") {
    options.threads = 2;
    options.filter_rates_hz = {50.0, 200.0};
  }
  SUBCASE("increments, fixed trim") {
    kind = DataKind::increment;
    options.trim = TrimMode::fixed;
    options.trim_s = 12.5;
    options.threads = 2;
    options.dynamic_windows = 3;
  }
  SUBCASE("phase, automatic trim (the warm-up sees phase differences)") {
    kind = DataKind::phase;
    options.threads = 2;
  }
  SUBCASE("phase, no trim") {
    kind = DataKind::phase;
    options.trim = TrimMode::none;
    options.statistics = {Statistic::oadev, Statistic::hdev};
  }
  const AnalysisOutput memory = in_memory(log, kind, options);
  const AnalysisOutput disk = bounded(log, kind, options, dir.file("").string());
  CHECK(disk.results_json == memory.results_json);
  CHECK(disk.filter_files == memory.filter_files);
  CHECK(disk.warnings == memory.warnings);
  if (kind == DataKind::rate && options.trim == TrimMode::automatic) {
    // The case exercises what pass 1 and pass 2 stream: the trim and every data check.
    CHECK(memory.results_json.find("warm-up transient") != std::string::npos);
    bool saturation = false, stuck = false, unit = false;
    for (const auto& w : memory.warnings) {
      saturation |= w.find("saturation") != std::string::npos;
      stuck |= w.find("stuck") != std::string::npos;
      unit |= w.find("look like g") != std::string::npos;
    }
    CHECK(saturation);
    CHECK(stuck);
    CHECK(unit);
  }
}

TEST_CASE("the bounded analysis refuses stdin and --gaps split") {
  AnalysisOptions options;
  BoundedAnalysisSource source;
  source.log.path = "-";
  CHECK_THROWS_WITH_AS(run_analysis_bounded(source, AnalysisInput{}, options),
                       doctest::Contains("not stdin"), Error);
  source.log.path = "x.csv";
  source.log.gaps = GapPolicy::split;
  CHECK_THROWS_WITH_AS(run_analysis_bounded(source, AnalysisInput{}, options),
                       doctest::Contains("--gaps split"), Error);
}
