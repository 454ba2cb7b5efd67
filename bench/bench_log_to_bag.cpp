// A raw 6-channel f32 log (rows gx gy gz ax ay az, rad/s and m/s^2, as `sigmatau simulate
// --format f32 --sensors gyro,accel` writes) as a ROS 1 bag of sensor_msgs/Imu on /imu/data,
// uncompressed chunks of rosbag's 768 KiB: the input of bench/speed_vs_numpy.py's `analyze`
// run on a ROS bag (issue 25: "65 M values, f32 binary or a ROS bag").
//
//   bench_log_to_bag IN.f32 RATE_HZ OUT.bag [--unindexed]
//
// --unindexed leaves the index out (index_pos 0), as a recorder that crashed does.
// The stamps are 1.7e9 s + i / RATE_HZ (header and receive time alike).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <stdexcept>
#include <string>

#include "ros1_bag_writer.hpp"

int main(int argc, char** argv) {
  const bool unindexed = argc == 5 && std::string(argv[4]) == "--unindexed";
  if (argc != 4 && !unindexed) {
    std::fprintf(stderr, "usage: bench_log_to_bag IN.f32 RATE_HZ OUT.bag [--unindexed]\n");
    return 2;
  }
  try {
    const double rate = std::strtod(argv[2], nullptr);
    if (!(rate > 0)) throw std::runtime_error("RATE_HZ must be > 0");
    std::ifstream in(argv[1], std::ios::binary);
    if (!in) throw std::runtime_error(std::string("cannot read ") + argv[1]);
    sigmatau::test::Ros1BagWriter::Options options;
    options.indexed = !unindexed;
    sigmatau::test::Ros1BagWriter writer(argv[3], options);
    const auto imu = writer.add_connection("/imu/data", "sensor_msgs/Imu");
    constexpr std::int64_t kStartNs = 1700000000000000000;
    float row[6];
    std::int64_t i = 0;
    while (in.read(reinterpret_cast<char*>(row), sizeof row)) {
      sigmatau::test::Ros1Imu m;
      m.header_ns = kStartNs + std::llround(static_cast<double>(i) * 1e9 / rate);
      m.receive_ns = m.header_ns;
      for (int k = 0; k < 3; ++k) {
        m.gyro[k] = row[k];
        m.accel[k] = row[3 + k];
      }
      writer.write_imu(imu, m);
      ++i;
    }
    if (in.gcount() != 0) throw std::runtime_error("the log ends inside a row of 6 floats");
    writer.finish();
    std::fprintf(stderr, "%lld messages\n", static_cast<long long>(i));
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_log_to_bag: %s\n", e.what());
    return 1;
  }
}
