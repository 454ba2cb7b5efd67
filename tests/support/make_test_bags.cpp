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
//   shuffled.bag       400 Imu messages, uncompressed, 8 KiB chunks: message 100 arrives 4 messages
//                      late and 250/251 swap (2 messages reordered, the worst 20 ms late)
//   bad_crc.mcap       the Imu data in uncompressed MCAP chunks, one byte of chunk 0's data flipped
//   brotli.mcap        an MCAP whose chunks name the compression "brotli"
//   zz9.bag            a ROS 1 bag whose chunks name the compression "zz9"
//   bad_length.mcap    an MCAP whose second chunk record claims a length of 2^40 bytes
//   wrong_type.bag     /imu/data declared as std_msgs/String
//   undeclared.bag     400 Imu messages, uncompressed, indexed: message 200's record names
//                      connection 9, which nothing declares (a corrupt byte)
//   short_imu.mcap     unchunked Imu messages, the third one's frame_id length set to 255 (too
//                      few bytes are left for the Imu body)
// (the ROS 2 files with tests/support/ros2_bag_writer.hpp). The byte offsets the CLI cases expect
// are checked here against the writers' layouts (kOffset* below), so a writer change that moves
// them fails here rather than as a puzzling regex mismatch.
// Data: 20000 samples at 200 Hz, white noise of 1e-3 rad/s (gyro) and 0.02 m/s^2 (accel, on
// gravity along z), a fixed seed.
//
// Second use, for `calibrate` on a bag (tests/cli/bags.cmake):
//   make_test_bags --from-csv IN.csv OUT.bag OUT_ns.csv
// converts a text log with header t,gx,gy,gz,ax,ay,az (t in s, as `sigmatau simulate` writes it)
// into a ROS 1 bag (lz4 chunks, /imu/data) and back into CSV with integer ns stamps relative to the
// first and 17-digit values, so the bag and OUT_ns.csv hold the same doubles and stamps.
// Usage: make_test_bags OUT_DIR
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <stdexcept>
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

/// Byte offsets the CLI cases name (tests/cli/bags.cmake); main() checks them against the layout.
/// ROS 1: 13-byte magic + 4096-byte bag header record, then the first chunk.
constexpr std::int64_t kOffsetRos1FirstChunk = 4109;
/// MCAP: 8-byte magic + Header record (1 + 8 + 4 + 4 "ros2" + 4 + 20 "sigmatau test writer"),
/// then the first chunk.
constexpr std::int64_t kOffsetMcapFirstChunk = 49;
/// bad_length.mcap: its second chunk (500 Imu messages of 360 bytes and their index records
/// later).
constexpr std::int64_t kOffsetMcapSecondChunk = 185875;
/// short_imu.mcap: the third top-level message record.
constexpr std::int64_t kOffsetShortImuMessage = 884;

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

void patch(const fs::path& path, std::int64_t at, const std::string& bytes) {
  std::string b = read_file(path);
  if (at < 0 || static_cast<std::size_t>(at) + bytes.size() > b.size()) {
    throw std::runtime_error("patch outside " + path.string());
  }
  b.replace(static_cast<std::size_t>(at), bytes.size(), bytes);
  write_bytes(path, b);
}

void expect_offset(const char* what, std::int64_t got, std::int64_t expected) {
  if (got != expected) {
    throw std::runtime_error(std::string(what) + " at byte offset " + std::to_string(got) +
                             ", but tests/cli/bags.cmake expects " + std::to_string(expected));
  }
}

/// The corrupt and reordered bags of the CLI cases (see the file comment).
void write_bad_bags(const fs::path& dir, const std::vector<Ros1Imu>& m) {
  {  // shuffled.bag: message 100 four messages late, 250 and 251 swapped.
    std::vector<Ros1Imu> arrival(m.begin(), m.begin() + 400);
    const Ros1Imu late = arrival[100];
    arrival.erase(arrival.begin() + 100);
    arrival.insert(arrival.begin() + 104, late);
    std::swap(arrival[250], arrival[251]);
    Ros1BagWriter::Options o;
    o.chunk_bytes = 8 * 1024;
    Ros1BagWriter w((dir / "shuffled.bag").string(), o);
    const auto imu = w.add_connection("/imu/data", "sensor_msgs/Imu");
    for (const Ros1Imu& x : arrival) w.write_imu(imu, x);
    w.finish();
  }
  {  // undeclared.bag: the "conn=" field of message 200's record header set to 9.
    Ros1BagWriter w((dir / "undeclared.bag").string(), {});
    const auto imu = w.add_connection("/imu/data", "sensor_msgs/Imu");
    std::int64_t at = -1;
    for (std::size_t i = 0; i < 400; ++i) {
      const std::int64_t here = w.write_imu(imu, m[i]);
      if (i == 200) at = here;
    }
    w.finish();
    const auto field = read_file(dir / "undeclared.bag").find("conn=", static_cast<std::size_t>(at));
    patch(dir / "undeclared.bag", static_cast<std::int64_t>(field) + 5, std::string("\x09\0\0\0", 4));
  }
  const auto topics = ros2_topics(std::vector<Ros1Imu>(m.begin(), m.begin() + 2000),
                                  t2::CdrKind::xcdr1_le);
  {  // bad_crc.mcap: a byte inside a message of chunk 0 (after the chunk's 9-byte record head,
     // 32 bytes of fixed fields with an empty compression name and the 8-byte records length).
    t2::McapOptions o;
    o.chunk_messages = 500;
    const auto layout = t2::write_mcap(dir / "bad_crc.mcap", topics, o);
    expect_offset("bad_crc.mcap chunk 0", layout.chunk_offsets.at(0), kOffsetMcapFirstChunk);
    patch(dir / "bad_crc.mcap", layout.chunk_offsets[0] + 9 + 32 + 8 + 300, "\x5a");
  }
  {
    t2::McapOptions o;
    o.chunk_messages = 500;
    o.compression = "brotli";  // the writer stores such chunks uncompressed under that name
    const auto layout = t2::write_mcap(dir / "brotli.mcap", topics, o);
    expect_offset("brotli.mcap chunk 0", layout.chunk_offsets.at(0), kOffsetMcapFirstChunk);
  }
  {  // bad_length.mcap: chunk 1's record length (after its opcode byte) set to 2^40.
    t2::McapOptions o;
    o.chunk_messages = 500;
    const auto layout = t2::write_mcap(dir / "bad_length.mcap", topics, o);
    std::string len(8, '\0');
    const std::uint64_t huge = std::uint64_t{1} << 40;
    for (int i = 0; i < 8; ++i) len[i] = static_cast<char>((huge >> (8 * i)) & 0xff);
    expect_offset("bad_length.mcap chunk 1", layout.chunk_offsets.at(1), kOffsetMcapSecondChunk);
    patch(dir / "bad_length.mcap", layout.chunk_offsets[1] + 1, len);
  }
  {
    Ros1BagWriter::Options o;
    o.compression_name = "zz9";
    Ros1BagWriter w((dir / "zz9.bag").string(), o);
    const auto imu = w.add_connection("/imu/data", "sensor_msgs/Imu");
    for (std::size_t i = 0; i < 50; ++i) w.write_imu(imu, m[i]);
    w.finish();
    expect_offset("zz9.bag chunk 0", w.chunk_positions().at(0), kOffsetRos1FirstChunk);
  }
  {
    Ros1BagWriter w((dir / "wrong_type.bag").string(), {});
    const auto s = w.add_connection("/imu/data", "std_msgs/String");
    w.write_message(s, m[0].receive_ns, std::string("\x05\0\0\0hello", 9));
    w.finish();
  }
  {  // short_imu.mcap: unchunked; in the third message record (9-byte head, 22 bytes of channel
     // id, sequence and times, 4-byte CDR encapsulation, 8-byte stamp) the frame_id length.
    t2::Ros2Topic imu = topics[0];
    imu.values.resize(5);
    t2::McapOptions o;
    o.chunked = false;
    const auto layout = t2::write_mcap(dir / "short_imu.mcap", {imu}, o);
    expect_offset("short_imu.mcap message 2", layout.message_offsets.at(2), kOffsetShortImuMessage);
    patch(dir / "short_imu.mcap", layout.message_offsets[2] + 9 + 22 + 4 + 8,
          std::string("\xff\x00\x00\x00", 4));
  }
}

/// make_test_bags --from-csv IN.csv OUT.bag OUT_ns.csv (see the file comment).
void convert_csv(const fs::path& in_path, const fs::path& bag_path, const fs::path& csv_path) {
  std::ifstream in(in_path);
  if (!in) throw std::runtime_error("cannot read " + in_path.string());
  std::string line;
  if (!std::getline(in, line) || line != "t,gx,gy,gz,ax,ay,az") {
    throw std::runtime_error(in_path.string() + ": expected the header t,gx,gy,gz,ax,ay,az");
  }
  std::vector<Ros1Imu> m;
  for (std::size_t row = 2; std::getline(in, line); ++row) {
    if (line.empty()) continue;
    const char* p = line.c_str();
    double v[7];
    for (int k = 0; k < 7; ++k) {
      char* end = nullptr;
      v[k] = std::strtod(p, &end);
      if (end == p || (k < 6 && *end != ',') || (k == 6 && *end != '\0')) {
        throw std::runtime_error(in_path.string() + ":" + std::to_string(row) + ": bad row");
      }
      p = end + 1;
    }
    Ros1Imu x;
    x.header_ns = kStartNs + std::llround(v[0] * 1e9);
    x.receive_ns = x.header_ns + 400000;
    for (int k = 0; k < 3; ++k) {
      x.gyro[k] = v[1 + k];
      x.accel[k] = v[4 + k];
    }
    m.push_back(x);
  }
  if (m.empty()) throw std::runtime_error(in_path.string() + ": no rows");
  write_ros1(bag_path.string(), m, Ros1BagWriter::Compression::lz4, true);
  write_csv(csv_path.string(), m);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 5 && std::string(argv[1]) == "--from-csv") {
    try {
      convert_csv(argv[2], argv[3], argv[4]);
    } catch (const std::exception& e) {
      std::cerr << "make_test_bags: " << e.what() << "\n";
      return 1;
    }
    return 0;
  }
  if (argc != 2) {
    std::cerr << "usage: make_test_bags OUT_DIR | make_test_bags --from-csv IN.csv OUT.bag "
                 "OUT_ns.csv\n";
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
      // A recorder that stalled: 1000 messages missing in the middle (a stamp gap).
      auto gapped = m;
      gapped.erase(gapped.begin() + 5000, gapped.begin() + 6000);
      write_ros1((dir / "imu_gap.bag").string(), gapped, Ros1BagWriter::Compression::none, true);
    }
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
    write_bad_bags(dir, m);
  } catch (const std::exception& e) {
    std::cerr << "make_test_bags: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
