// Writes the seed corpus of fuzz_bag into a directory: small bags (12 Imu messages and a non-Imu
// topic) of every format and compression, each prefixed with the harness's option byte. Run by
// scripts/fuzz.sh.   Usage: make_bag_seeds OUT_DIR
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>

#include "ros1_bag_writer.hpp"
#include "ros2_bag_writer.hpp"

namespace fs = std::filesystem;
namespace t = sigmatau::test;

namespace {

/// Copies `file` to DIR/<name>.<flags in hex> with the option byte in front, and removes it.
void seed(const fs::path& dir, const fs::path& file, const std::string& name, unsigned char flags) {
  std::ifstream in(file, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), {});
  char hex[8];
  std::snprintf(hex, sizeof hex, "%02x", flags);
  std::ofstream out(dir / (name + "." + hex), std::ios::binary);
  out.put(static_cast<char>(flags));
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_bag_seeds OUT_DIR\n";
    return 2;
  }
  const fs::path dir = argv[1];
  fs::create_directories(dir);
  const fs::path tmp = dir / "tmp.bin";
  const auto values = t::make_imu_values(12, 3);
  using C = t::Ros1BagWriter::Compression;
  int i = 0;
  for (const C c : {C::none, C::bz2, C::lz4}) {
    for (const bool indexed : {true, false}) {
      {
        t::Ros1BagWriter::Options o;
        o.compression = c;
        o.indexed = indexed;
        o.chunk_bytes = 2000;  // several chunks
        t::Ros1BagWriter w(tmp.string(), o);
        const auto tf = w.add_connection("/tf", "tf2_msgs/TFMessage");
        const auto imu = w.add_connection("/imu/data", "sensor_msgs/Imu");
        for (const auto& v : values) {
          t::Ros1Imu m;
          m.header_ns = v.header_ns;
          m.receive_ns = v.receive_ns;
          std::copy(v.gyro, v.gyro + 3, m.gyro);
          std::copy(v.accel, v.accel + 3, m.accel);
          w.write_imu(imu, m);
          w.write_message(tf, v.receive_ns, "tf");
        }
        w.finish();
      }
      seed(dir, tmp, "ros1_" + std::to_string(i), 0x00);
      seed(dir, tmp, "ros1_" + std::to_string(i++), 0x5c);
    }
  }
  t::Ros2Topic imu;
  imu.values = values;
  t::Ros2Topic tf = imu;
  tf.name = "/tf";
  tf.type = "tf2_msgs/msg/TFMessage";
  for (const char* codec : {"", "zstd", "lz4"}) {
    t::McapOptions o;
    o.compression = codec;
    o.chunk_messages = 5;
    t::write_mcap(tmp, {imu, tf}, o);
    seed(dir, tmp, std::string("mcap_") + (*codec ? codec : "none"), 0x01);
    seed(dir, tmp, std::string("mcap_") + (*codec ? codec : "none"), 0x65);
  }
  t::McapOptions crashed;
  crashed.summary = false;
  crashed.footer = false;
  imu.cdr = t::CdrKind::xcdr2_be;
  t::write_mcap(tmp, {imu}, crashed);
  seed(dir, tmp, "mcap_crashed", 0x11);
  t::write_db3(tmp, {imu, tf}, false);
  seed(dir, tmp, "db3", 0x02);
  t::write_db3(tmp, {imu}, true);
  seed(dir, tmp, "db3_zstd", 0x46);
  fs::remove(tmp);
  return 0;
}
