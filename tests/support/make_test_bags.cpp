// Writes the bags of the CLI cases (tests/cli/bags.cmake) into a directory, at test time, with
// the writers in tests/support (no bag is kept in the repository):
//   imu.bag            ROS 1, lz4 chunks, indexed: /imu/data (sensor_msgs/Imu) and /tf
//   imu_unindexed.bag  the same messages, bz2 chunks, no index (a recorder that crashed)
//   imu.csv            the same Imu data as text: t [ns from the first stamp], gx..az with 17
//                      significant digits (they read back to the same doubles)
//   two_imu.bag        two sensor_msgs/Imu topics, /imu/a and /imu/b
//   truncated.bag      imu.bag cut 100 bytes into its first chunk (at byte offset 4109: the
//                      13-byte magic plus the 4096-byte bag header record rosbag pads to)
//   imu_zstd.mcap      the same Imu data as ROS 2 MCAP, zstd chunks, CDR little endian, with /tf
//   imu_lz4.mcap       lz4 chunks, CDR big endian (XCDR2), no summary (a recorder that crashed)
//   imu.db3            rosbag2 SQLite, per-message zstd
//   imu_folder/        a rosbag2 folder: metadata.yaml and three .db3 files
// (the ROS 2 files with tests/support/ros2_bag_writer.hpp)
// Data: 20000 samples at 200 Hz, white noise of 1e-3 rad/s (gyro) and 0.02 m/s^2 (accel, on
// gravity along z), a fixed seed.
// Usage: make_test_bags OUT_DIR
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "ros1_bag_writer.hpp"
#include "ros2_bag_writer.hpp"

namespace fs = std::filesystem;
using sigmatau::test::Ros1BagWriter;
using sigmatau::test::Ros1Imu;
namespace t2 = sigmatau::test;

namespace {

constexpr std::size_t kSamples = 20000;
constexpr std::int64_t kStartNs = 1700000000123456789;
constexpr std::int64_t kPeriodNs = 5000000;  // 200 Hz

std::vector<Ros1Imu> make_messages(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gyro(0.0, 1e-3), accel(0.0, 0.02);
  std::vector<Ros1Imu> m(kSamples);
  for (std::size_t i = 0; i < kSamples; ++i) {
    m[i].header_ns = kStartNs + static_cast<std::int64_t>(i) * kPeriodNs;
    m[i].receive_ns = m[i].header_ns + 400000;
    for (int k = 0; k < 3; ++k) {
      m[i].gyro[k] = gyro(rng);
      m[i].accel[k] = accel(rng) + (k == 2 ? 9.80665 : 0.0);
    }
  }
  return m;
}

void write_ros1(const std::string& path, const std::vector<Ros1Imu>& m,
                Ros1BagWriter::Compression compression, bool indexed) {
  Ros1BagWriter::Options options;
  options.compression = compression;
  options.indexed = indexed;
  options.chunk_bytes = 256 * 1024;
  Ros1BagWriter w(path, options);
  const auto tf = w.add_connection("/tf", "tf2_msgs/TFMessage");
  const auto imu = w.add_connection("/imu/data", "sensor_msgs/Imu");
  for (std::size_t i = 0; i < m.size(); ++i) {
    w.write_imu(imu, m[i]);
    if (i % 20 == 0) w.write_message(tf, m[i].receive_ns, std::string(64, '\0'));
  }
  w.finish();
}

void write_csv(const std::string& path, const std::vector<Ros1Imu>& m) {
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + path);
  std::fprintf(f, "t,gx,gy,gz,ax,ay,az\n");
  for (const Ros1Imu& x : m) {
    std::fprintf(f, "%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                 static_cast<long long>(x.header_ns - m[0].header_ns), x.gyro[0], x.gyro[1],
                 x.gyro[2], x.accel[0], x.accel[1], x.accel[2]);
  }
  std::fclose(f);
}

/// The same messages as ROS 2 topics: /imu/data and a /tf declared with another type.
std::vector<t2::Ros2Topic> ros2_topics(const std::vector<Ros1Imu>& m, t2::CdrKind cdr) {
  t2::Ros2Topic imu;
  imu.name = "/imu/data";
  imu.cdr = cdr;
  for (const Ros1Imu& x : m) {
    t2::ImuValue v;
    v.header_ns = x.header_ns;
    v.receive_ns = x.receive_ns;
    for (int k = 0; k < 3; ++k) {
      v.gyro[k] = x.gyro[k];
      v.accel[k] = x.accel[k];
    }
    imu.values.push_back(v);
  }
  t2::Ros2Topic tf;
  tf.name = "/tf";
  tf.type = "tf2_msgs/msg/TFMessage";
  tf.values.assign(imu.values.begin(), imu.values.begin() + 50);
  return {imu, tf};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_test_bags OUT_DIR\n";
    return 2;
  }
  try {
    const fs::path dir = argv[1];
    fs::create_directories(dir);
    const auto m = make_messages(42);
    write_ros1((dir / "imu.bag").string(), m, Ros1BagWriter::Compression::lz4, true);
    write_ros1((dir / "imu_unindexed.bag").string(), m, Ros1BagWriter::Compression::bz2, false);
    write_csv((dir / "imu.csv").string(), m);
    {
      Ros1BagWriter w((dir / "two_imu.bag").string(), {});
      const auto a = w.add_connection("/imu/a", "sensor_msgs/Imu");
      const auto b = w.add_connection("/imu/b", "sensor_msgs/Imu");
      for (std::size_t i = 0; i < 100; ++i) {
        w.write_imu(a, m[i]);
        w.write_imu(b, m[i]);
      }
      w.finish();
    }
    {
      std::ifstream in(dir / "imu.bag", std::ios::binary);
      std::string bytes(4109 + 100, '\0');
      in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
      std::ofstream(dir / "truncated.bag", std::ios::binary | std::ios::trunc)
          .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    }
    t2::McapOptions zstd;
    zstd.compression = "zstd";
    zstd.chunk_messages = 500;
    t2::write_mcap(dir / "imu_zstd.mcap", ros2_topics(m, t2::CdrKind::xcdr1_le), zstd);
    t2::McapOptions lz4;
    lz4.compression = "lz4";
    lz4.chunk_messages = 500;
    lz4.summary = false;
    lz4.footer = false;
    t2::write_mcap(dir / "imu_lz4.mcap", ros2_topics(m, t2::CdrKind::xcdr2_be), lz4);
    t2::write_db3(dir / "imu.db3", ros2_topics(m, t2::CdrKind::xcdr1_le), true);
    fs::remove_all(dir / "imu_folder");
    t2::write_rosbag2_folder(dir / "imu_folder", "sqlite3", ros2_topics(m, t2::CdrKind::xcdr1_le),
                             3);
  } catch (const std::exception& e) {
    std::cerr << "make_test_bags: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
