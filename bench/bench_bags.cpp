// Reading ROS bags through LogReader (issue 10): throughput and memory.
//
//   bench_bags [--mb M] [--mcap-mb M] [--bz2-mb M] [--db3-mb M] [--runs R] [--dir DIR] [--keep]
//
// Writes into DIR (default: the temp directory) a ROS 1 bag of about M MB of messages (default
// 1000; sensor_msgs/Imu at 200 Hz on /imu/data with a /tf message every 20th, 768 KiB chunks as
// rosbag record writes them), uncompressed and with lz4 chunks, and with bz2 chunks at --bz2-mb
// (default 200: bz2 decompresses at tens of MB/s), MCAP files of about --mcap-mb MB (default 500;
// chunks uncompressed, zstd and lz4, written by the in-memory test writer, hence the smaller
// default), rosbag2 SQLite files of about --db3-mb MB (default 300; plain and per-message zstd),
// and as a baseline the same Imu rows as a raw f64 binary log (7 channels: t and the six values).
// A size of 0 leaves that format out. Each file is read through LogReader (all six channels and the time
// column) in a child process started with posix_spawn; the child reports its own peak RSS
// (VmHWM of /proc/self/status: the high-water mark of its fresh address space; wait4's ru_maxrss
// would include the parent's, which exec carries over from a CLONE_VM spawn). Reported, as medians over R runs (default 3):
//   MB/s per core = uncompressed size of that bag / CPU time (user + system) of the child,
//   MB/s wall     = the same size / wall-clock time,
// with "uncompressed size" the size of the uncompressed file of the same format (the stored file
// for compressed bags is smaller). The files are read from the page cache (written just before):
// this measures parsing and decompression, not the disk.
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "bench_stats.hpp"
#include "ros1_bag_writer.hpp"
#include "ros2_bag_writer.hpp"
#include "sigmatau/log_reader.hpp"

extern char** environ;

namespace fs = std::filesystem;
using sigmatau::test::Ros1BagWriter;
using sigmatau::test::Ros1Imu;
namespace t2 = sigmatau::test;

namespace {

using sigmatau::bench::median;

constexpr std::int64_t kStartNs = 1700000000000000000;
constexpr std::int64_t kPeriodNs = 5000000;  // 200 Hz
/// Bytes of one ROS 1 Imu message record in a chunk (frame_id "imu_link"), for sizing only.
constexpr double kRos1MessageBytes = 380;
constexpr double kMcapMessageBytes = 360;

Ros1Imu message(std::int64_t i, std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1e-3), a(0.0, 0.02);
  Ros1Imu m;
  m.header_ns = kStartNs + i * kPeriodNs;
  m.receive_ns = m.header_ns + 300000;
  for (int k = 0; k < 3; ++k) {
    m.gyro[k] = g(rng);
    m.accel[k] = a(rng) + (k == 2 ? 9.80665 : 0.0);
  }
  return m;
}

void write_ros1(const std::string& path, std::int64_t n, Ros1BagWriter::Compression c) {
  Ros1BagWriter::Options o;
  o.compression = c;
  Ros1BagWriter w(path, o);
  const auto tf = w.add_connection("/tf", "tf2_msgs/TFMessage");
  const auto imu = w.add_connection("/imu/data", "sensor_msgs/Imu");
  std::mt19937_64 rng(7);
  for (std::int64_t i = 0; i < n; ++i) {
    const Ros1Imu m = message(i, rng);
    w.write_imu(imu, m);
    if (i % 20 == 0) w.write_message(tf, m.receive_ns, std::string(64, '\0'));
  }
  w.finish();
}

void write_binary(const std::string& path, std::int64_t n) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  std::mt19937_64 rng(7);
  for (std::int64_t i = 0; i < n; ++i) {
    const Ros1Imu m = message(i, rng);
    const double row[7] = {static_cast<double>(i) / 200.0, m.gyro[0], m.gyro[1], m.gyro[2],
                           m.accel[0], m.accel[1], m.accel[2]};
    std::fwrite(row, sizeof row, 1, f);
  }
  std::fclose(f);
}

void write_mcap(const std::string& path, std::int64_t n, const std::string& compression) {
  t2::Ros2Topic imu;
  imu.values.reserve(static_cast<std::size_t>(n));
  std::mt19937_64 rng(7);
  for (std::int64_t i = 0; i < n; ++i) {
    const Ros1Imu m = message(i, rng);
    t2::ImuValue v;
    v.header_ns = m.header_ns;
    v.receive_ns = m.receive_ns;
    std::copy(m.gyro, m.gyro + 3, v.gyro);
    std::copy(m.accel, m.accel + 3, v.accel);
    imu.values.push_back(v);
  }
  t2::McapOptions o;
  o.compression = compression;
  o.chunk_messages = 2000;  // about 700 KiB, like MCAP's default 768 KiB chunks
  o.crc = false;            // the test writer's bitwise CRC would dominate the write time
  t2::write_mcap(path, {imu}, o);
}

void write_db3(const std::string& path, std::int64_t n, bool zstd) {
  t2::Ros2Topic imu;
  imu.values.reserve(static_cast<std::size_t>(n));
  std::mt19937_64 rng(7);
  for (std::int64_t i = 0; i < n; ++i) {
    const Ros1Imu m = message(i, rng);
    t2::ImuValue v;
    v.header_ns = m.header_ns;
    v.receive_ns = m.receive_ns;
    std::copy(m.gyro, m.gyro + 3, v.gyro);
    std::copy(m.accel, m.accel + 3, v.accel);
    imu.values.push_back(v);
  }
  t2::write_db3(path, {imu}, zstd);
}

/// Child mode: read `path` through LogReader, print the rows.
int read_child(const std::string& path, bool binary) {
  sigmatau::LogOptions o;
  o.path = path;
  if (binary) {
    o.binary = sigmatau::BinaryFormat::f64;
    o.binary_channels = 7;
  } else {
    o.topic = "/imu/data";
  }
  sigmatau::LogReader reader(o);
  sigmatau::SampleBlock block;
  std::int64_t rows = 0;
  double sum = 0;
  while (reader.read_block(block)) {
    rows += block.rows();
    sum += block.values[0].back();
  }
  long hwm_kib = -1;
  if (std::FILE* status = std::fopen("/proc/self/status", "r")) {
    char line[256];
    while (std::fgets(line, sizeof line, status)) {
      if (std::sscanf(line, "VmHWM: %ld kB", &hwm_kib) == 1) break;
    }
    std::fclose(status);
  }
  std::printf("%lld %ld %g\n", static_cast<long long>(rows), hwm_kib, sum);
  return rows > 0 ? 0 : 1;
}

struct Run {
  double wall_s = 0, cpu_s = 0;
  long rss_kib = 0;
};

Run run_child(const std::string& self, const std::string& path, bool binary) {
  std::vector<std::string> args = {self, binary ? "--read-binary" : "--read", path};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error("pipe failed");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[1], STDOUT_FILENO);
  posix_spawn_file_actions_addclose(&actions, fds[0]);
  const auto t0 = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, self.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[1]);
  if (spawned != 0) throw std::runtime_error("cannot start " + self);
  std::string out;
  char buf[256];
  for (ssize_t got; (got = read(fds[0], buf, sizeof buf)) > 0;) out.append(buf, static_cast<std::size_t>(got));
  close(fds[0]);
  int status = 0;
  rusage ru{};
  wait4(pid, &status, 0, &ru);
  const auto t1 = std::chrono::steady_clock::now();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw std::runtime_error("reading " + path + " failed");
  }
  Run r;
  r.wall_s = std::chrono::duration<double>(t1 - t0).count();
  r.cpu_s = static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
            1e-6 * static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
  long long rows = 0;
  if (std::sscanf(out.c_str(), "%lld %ld", &rows, &r.rss_kib) != 2 || rows <= 0) {
    throw std::runtime_error("reading " + path + ": unexpected child output " + out);
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 3 && std::strcmp(argv[1], "--read") == 0) return read_child(argv[2], false);
  if (argc == 3 && std::strcmp(argv[1], "--read-binary") == 0) return read_child(argv[2], true);
  double mb = 1000, mcap_mb = 500, bz2_mb = 200, db3_mb = 300;
  int runs = 3;
  bool keep = false;
  fs::path dir = fs::temp_directory_path() / ("sigmatau_bench_bags_" + std::to_string(getpid()));
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--mb" && i + 1 < argc) {
      mb = std::atof(argv[++i]);
    } else if (a == "--mcap-mb" && i + 1 < argc) {
      mcap_mb = std::atof(argv[++i]);
    } else if (a == "--bz2-mb" && i + 1 < argc) {
      bz2_mb = std::atof(argv[++i]);
    } else if (a == "--db3-mb" && i + 1 < argc) {
      db3_mb = std::atof(argv[++i]);
    } else if (a == "--runs" && i + 1 < argc) {
      runs = std::max(1, std::atoi(argv[++i]));
    } else if (a == "--dir" && i + 1 < argc) {
      dir = argv[++i];
    } else if (a == "--keep") {
      keep = true;
    } else {
      std::fprintf(stderr,
                   "usage: bench_bags [--mb M] [--mcap-mb M] [--bz2-mb M] [--db3-mb M] [--runs R] "
                   "[--dir DIR] [--keep]\n");
      return 2;
    }
  }
  const std::string self = fs::canonical("/proc/self/exe").string();
  fs::create_directories(dir);
  const auto n_ros1 = static_cast<std::int64_t>(mb * 1e6 / kRos1MessageBytes);
  const auto n_mcap = static_cast<std::int64_t>(mcap_mb * 1e6 / kMcapMessageBytes);
  const auto n_bz2 = static_cast<std::int64_t>(bz2_mb * 1e6 / kRos1MessageBytes);
  const auto n_db3 = static_cast<std::int64_t>(db3_mb * 1e6 / kMcapMessageBytes);

  struct Case {
    std::string name, path, uncompressed;
    bool binary = false;
    std::int64_t messages = 0;
  };
  std::vector<Case> cases;
  const auto file = [&](const char* name) { return (dir / name).string(); };
  std::fprintf(stderr,
               "writing %lld ROS 1 messages (%lld bz2), %lld MCAP messages, %lld db3 messages into "
               "%s ...\n",
               static_cast<long long>(n_ros1), static_cast<long long>(n_bz2),
               static_cast<long long>(n_mcap), static_cast<long long>(n_db3), dir.c_str());
  if (mb > 0) {
    write_binary(file("imu.f64"), n_ros1);
    cases.push_back({"raw f64 binary log (baseline)", file("imu.f64"), file("imu.f64"), true, n_ros1});
    write_ros1(file("none.bag"), n_ros1, Ros1BagWriter::Compression::none);
    cases.push_back({"ROS 1 bag, uncompressed", file("none.bag"), file("none.bag"), false, n_ros1});
    write_ros1(file("lz4.bag"), n_ros1, Ros1BagWriter::Compression::lz4);
    cases.push_back({"ROS 1 bag, lz4", file("lz4.bag"), file("none.bag"), false, n_ros1});
  }
  if (bz2_mb > 0) {
    // bz2 is measured on its own (smaller) size: its uncompressed reference is written too.
    write_ros1(file("none_small.bag"), n_bz2, Ros1BagWriter::Compression::none);
    write_ros1(file("bz2.bag"), n_bz2, Ros1BagWriter::Compression::bz2);
    cases.push_back({"ROS 1 bag, bz2", file("bz2.bag"), file("none_small.bag"), false, n_bz2});
  }
  if (mcap_mb > 0) {
    write_mcap(file("none.mcap"), n_mcap, "");
    cases.push_back({"MCAP, uncompressed", file("none.mcap"), file("none.mcap"), false, n_mcap});
    write_mcap(file("zstd.mcap"), n_mcap, "zstd");
    cases.push_back({"MCAP, zstd", file("zstd.mcap"), file("none.mcap"), false, n_mcap});
    write_mcap(file("lz4.mcap"), n_mcap, "lz4");
    cases.push_back({"MCAP, lz4", file("lz4.mcap"), file("none.mcap"), false, n_mcap});
  }
  if (db3_mb > 0) {
    write_db3(file("none.db3"), n_db3, false);
    cases.push_back({"rosbag2 SQLite .db3", file("none.db3"), file("none.db3"), false, n_db3});
    write_db3(file("zstd.db3"), n_db3, true);
    cases.push_back({"rosbag2 SQLite .db3, per-message zstd", file("zstd.db3"), file("none.db3"),
                     false, n_db3});
  }

  std::printf("Reading through LogReader (6 channels + time), median of %d run(s), one core; "
              "files in the page cache.\n\n",
              runs);
  std::printf("| input | stored MB | uncompressed MB | messages | MB/s per core | MB/s wall | "
              "peak RSS [MiB] |\n|---|---|---|---|---|---|---|\n");
  for (const Case& c : cases) {
    std::vector<double> cpu, wall;
    long rss = 0;
    for (int r = 0; r < runs; ++r) {
      const Run run = run_child(self, c.path, c.binary);
      cpu.push_back(run.cpu_s);
      wall.push_back(run.wall_s);
      rss = std::max(rss, run.rss_kib);
    }
    const double stored = static_cast<double>(fs::file_size(c.path)) / 1e6;
    const double raw = static_cast<double>(fs::file_size(c.uncompressed)) / 1e6;
    const std::int64_t messages = c.messages;
    std::printf("| %s | %.0f | %.0f | %lld | %.0f | %.0f | %.1f |\n", c.name.c_str(), stored, raw,
                static_cast<long long>(messages), raw / median(cpu), raw / median(wall),
                static_cast<double>(rss) / 1024.0);
    std::fflush(stdout);
  }
  if (!keep) fs::remove_all(dir);
  return 0;
}
