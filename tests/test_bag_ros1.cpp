// Tests of ROS 1 bags through LogReader (lib/src/bag_log.cpp, rosbag1.cpp, bag_io.cpp): bags are
// written by tests/support/ros1_bag_writer.hpp with known values and read back.
//
// Values are compared bit for bit: the reader copies the float64 of the message unchanged. Times
// are compared exactly too: t_s is (stamp_ns - first_ns) / 1e9 computed from exact integers.

#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "ros1_bag_writer.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/log_reader.hpp"
#include "temp_dir.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace sigmatau;
using sigmatau::test::Ros1BagWriter;
using sigmatau::test::Ros1Imu;
using Compression = Ros1BagWriter::Compression;

namespace {

/// A fresh directory for one test, removed when it ends.
struct TempDir : test::TempDir {
  TempDir() : test::TempDir("sigmatau_test_bag_ros1") {}
};

/// 200 Hz from an epoch stamp with a nanosecond part, so rounding would show.
constexpr std::int64_t kStart = 1700000000123456789;
constexpr std::int64_t kPeriod = 5000000;

std::vector<Ros1Imu> make_messages(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gyro(0.0, 1e-3), accel(0.0, 0.05);
  std::vector<Ros1Imu> m(n);
  for (std::size_t i = 0; i < n; ++i) {
    m[i].header_ns = kStart + static_cast<std::int64_t>(i) * kPeriod;
    m[i].receive_ns = m[i].header_ns + 700000 + static_cast<std::int64_t>(i % 7) * 1000;
    for (int k = 0; k < 3; ++k) {
      m[i].gyro[k] = gyro(rng);
      m[i].accel[k] = accel(rng) + (k == 2 ? 9.80665 : 0.0);
    }
  }
  return m;
}

Ros1BagWriter::Options opts(Compression c, bool indexed, std::size_t chunk_bytes,
                           std::string compression_name = "") {
  Ros1BagWriter::Options o;
  o.compression = c;
  o.indexed = indexed;
  o.chunk_bytes = chunk_bytes;
  o.compression_name = std::move(compression_name);
  return o;
}

struct Written {
  std::vector<std::int64_t> chunks;   // chunk offsets
  std::vector<std::int64_t> offsets;  // per Imu message: the location the reader names
};

/// Writes `imu` on /imu/data, with a /tf (non-Imu) message after every 10th.
Written write_bag(const std::string& path, const std::vector<Ros1Imu>& imu,
                  Ros1BagWriter::Options options) {
  Ros1BagWriter w(path, options);
  const auto tf = w.add_connection("/tf", "tf2_msgs/TFMessage");
  const auto data = w.add_connection("/imu/data", "sensor_msgs/Imu");
  Written out;
  for (std::size_t i = 0; i < imu.size(); ++i) {
    out.offsets.push_back(w.write_imu(data, imu[i]));
    if (i % 10 == 0) w.write_message(tf, imu[i].receive_ns, std::string(48, 'x'));
  }
  w.finish();
  out.chunks = w.chunk_positions();
  return out;
}

bool same_bits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

double rel_s(std::int64_t ns, std::int64_t first) {
  return static_cast<double>(ns - first) / 1e9;
}

void check_values(const Log& log, const std::vector<Ros1Imu>& m) {
  REQUIRE(log.channels.size() == 6);
  REQUIRE(log.channels[0].size() == m.size());
  REQUIRE(log.t_s.size() == m.size());
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < m.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      mismatches += !same_bits(log.channels[k][i], m[i].gyro[k]);
      mismatches += !same_bits(log.channels[3 + k][i], m[i].accel[k]);
    }
    mismatches += log.t_s[i] != rel_s(m[i].header_ns, m[0].header_ns);
  }
  CHECK(mismatches == 0);
}

std::string error_of(const LogOptions& o) {
  try {
    read_log(o);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}
void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(),
                                                                static_cast<std::streamsize>(bytes.size()));
}

}  // namespace

TEST_CASE("a ROS 1 bag gives back every Imu value bit for bit in every compression") {
  const auto m = make_messages(3000, 1);
  for (const Compression c : {Compression::none, Compression::bz2, Compression::lz4}) {
    for (const bool indexed : {true, false}) {
      CAPTURE(static_cast<int>(c));
      CAPTURE(indexed);
      TempDir dir;
      const std::string path = dir.file("imu.bag");
      // 32 KiB chunks: about 80 messages each, so the bag holds many chunks.
      const auto w = write_bag(path, m, opts(c, indexed, 32 * 1024));
      REQUIRE(w.chunks.size() > 10);
      LogOptions o;
      o.path = path;
      o.topic = "/imu/data";
      const Log log = read_log(o);
      CHECK(log.channel_names == std::vector<std::string>{"gx", "gy", "gz", "ax", "ay", "az"});
      check_values(log, m);
      CHECK(log.timing.bag_topic == "/imu/data");
      CHECK(log.timing.samples == 3000);
      CHECK(log.timing.reordered_samples == 0);
      // 200 Hz from exact 5 ms integer intervals: the median interval is exactly 5e6 ns / 1e9.
      CHECK(log.timing.rate_hz == 1.0 / 0.005);
      CHECK(log.timing.jitter_s == 0.0);
      CHECK(log.timing.gap_count == 0);
    }
  }
}

TEST_CASE("the reader reports progress in bytes of the bag file") {
  TempDir dir;
  const std::string path = dir.file("imu.bag");
  write_bag(path, make_messages(500, 2), opts(Compression::lz4, true, 16 * 1024));
  LogOptions o;
  o.path = path;
  LogReader reader(o);
  SampleBlock block;
  while (reader.read_block(block, 100)) {
  }
  CHECK(reader.total_bytes() == static_cast<std::int64_t>(fs::file_size(path)));
  CHECK(reader.bytes_read() > 0);
  CHECK(reader.bytes_read() <= 2 * reader.total_bytes());  // the window may re-read a little
}

TEST_CASE("without a topic the only sensor_msgs/Imu topic is read") {
  const auto m = make_messages(200, 3);
  for (const bool indexed : {true, false}) {
    TempDir dir;
    const std::string path = dir.file("one_imu.bag");
    write_bag(path, m, opts(Compression::none, indexed, 8 * 1024));
    LogOptions o;
    o.path = path;
    const Log log = read_log(o);
    CHECK(log.timing.bag_topic == "/imu/data");
    check_values(log, m);
    // The topics as listed when the Imu topic was picked: both, with their types; the /tf
    // count is 20 (one after every 10th of 200 Imu messages) where the bag states counts.
    REQUIRE(log.timing.bag_topics.size() == 2);
    const auto& listed = log.timing.bag_topics;
    const bool tf_first = listed[0].name == "/tf";
    const BagTopic& tf = listed[tf_first ? 0 : 1];
    const BagTopic& imu = listed[tf_first ? 1 : 0];
    CHECK(tf.name == "/tf");
    CHECK(tf.type == "tf2_msgs/TFMessage");
    CHECK(imu.name == "/imu/data");
    CHECK(imu.type == "sensor_msgs/Imu");
    if (imu.messages >= 0) CHECK(imu.messages == 200);
    if (tf.messages >= 0) CHECK(tf.messages == 20);
    // Asked for by name, no listing.
    o.topic = "/imu/data";
    CHECK(read_log(o).timing.bag_topics.empty());
    // The index's counts without reading a message (the memory estimate of the CLI); a bag
    // without an index states none.
    CHECK(indexed_bag_messages(path) == (indexed ? 200 : -1));
    CHECK(indexed_bag_messages(path, "/tf") == (indexed ? 20 : -1));
    CHECK(indexed_bag_messages(path, "/imu/raw") == -1);
    // The reader's row hint (its arrays are sized once from it): the stated count, before any
    // block; an unindexed bag states none until it has been counted.
    o.topic = "/imu/data";
    LogReader reader(o);
    if (indexed) CHECK(reader.rows_left_hint() == 200);
    // With the topic given, the bag is read once: an unindexed one is not first read through to
    // count its messages (its bytes delivered were twice its size).
    SampleBlock block;
    while (reader.append_block(block)) {
    }
    CHECK(block.values.at(0).size() == 200);
    CHECK(static_cast<double>(reader.bytes_read()) <
          1.2 * static_cast<double>(std::filesystem::file_size(path)));
  }
}

TEST_CASE("two Imu topics without a topic is an error listing every topic with type and count") {
  TempDir dir;
  const std::string path = dir.file("two.bag");
  Ros1BagWriter w(path, {});
  const auto a = w.add_connection("/imu/a", "sensor_msgs/Imu");
  const auto b = w.add_connection("/imu/b", "sensor_msgs/Imu");
  const auto tf = w.add_connection("/tf", "tf2_msgs/TFMessage");
  const auto m = make_messages(10, 4);
  for (const auto& x : m) {
    w.write_imu(a, x);
    w.write_imu(b, x);
  }
  w.write_message(tf, kStart, "tf");
  w.finish();
  LogOptions o;
  o.path = path;
  const std::string e = error_of(o);
  CHECK(e.find("2 sensor_msgs/Imu topics; choose one with --topic") != std::string::npos);
  CHECK(e.find("/imu/a (sensor_msgs/Imu, 10 messages)") != std::string::npos);
  CHECK(e.find("/imu/b (sensor_msgs/Imu, 10 messages)") != std::string::npos);
  CHECK(e.find("/tf (tf2_msgs/TFMessage, 1 message)") != std::string::npos);

  o.topic = "/imu/b";
  CHECK(read_log(o).timing.bag_topic == "/imu/b");
  o.topic = "/imu/c";
  const std::string absent = error_of(o);
  CHECK(absent.find("no topic /imu/c in the bag") != std::string::npos);
  CHECK(absent.find("/imu/a (sensor_msgs/Imu, 10 messages)") != std::string::npos);

  // Two Imu topics: no count without a topic (the reader would ask which one).
  CHECK(indexed_bag_messages(path) == -1);
  CHECK(indexed_bag_messages(path, "/imu/b") == 10);

  const auto topics = list_bag_topics(path);
  REQUIRE(topics.size() == 3);
  CHECK(topics[0].name == "/imu/a");
  CHECK(topics[0].type == "sensor_msgs/Imu");
  CHECK(topics[0].messages == 10);
  CHECK(topics[2].name == "/tf");
  CHECK(topics[2].messages == 1);
}

TEST_CASE("a bag without an Imu topic is an error listing its topics") {
  TempDir dir;
  const std::string path = dir.file("tf.bag");
  Ros1BagWriter w(path, {});
  const auto tf = w.add_connection("/tf", "tf2_msgs/TFMessage");
  w.write_message(tf, kStart, "tf");
  w.finish();
  LogOptions o;
  o.path = path;
  const std::string e = error_of(o);
  CHECK(e.find("no sensor_msgs/Imu topic in the bag; its topics: /tf (tf2_msgs/TFMessage, 1 "
               "message)") != std::string::npos);
}

TEST_CASE("stamp receive takes the recorder's receive time as the time column") {
  TempDir dir;
  const std::string path = dir.file("imu.bag");
  const auto m = make_messages(300, 5);
  write_bag(path, m, opts(Compression::none, true, 8 * 1024));
  LogOptions o;
  o.path = path;
  o.stamp = BagStamp::receive;
  const Log log = read_log(o);
  REQUIRE(log.t_s.size() == m.size());
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < m.size(); ++i) {
    wrong += log.t_s[i] != rel_s(m[i].receive_ns, m[0].receive_ns);
  }
  CHECK(wrong == 0);
  CHECK(log.timing.jitter_s > 0);  // the receive times carry the writer's 0..6 us offsets
  CHECK(parse_bag_stamp("receive") == BagStamp::receive);
  CHECK(parse_bag_stamp("header") == BagStamp::header);
  CHECK_THROWS_AS(parse_bag_stamp("sensor"), Error);
}

TEST_CASE("stamps out of order within the reorder window are put back in order and reported") {
  TempDir dir;
  const std::string path = dir.file("shuffled.bag");
  auto m = make_messages(400, 6);
  // Message 100 arrives 4 messages late; 250 and 251 swap (1 late by one period).
  std::vector<Ros1Imu> arrival = m;
  const Ros1Imu late = arrival[100];
  arrival.erase(arrival.begin() + 100);
  arrival.insert(arrival.begin() + 104, late);
  std::swap(arrival[250], arrival[251]);
  write_bag(path, arrival, opts(Compression::lz4, true, 8 * 1024));
  LogOptions o;
  o.path = path;
  o.reorder_window = 4;
  const Log log = read_log(o);
  check_values(log, m);  // in stamp order, values travelling with their stamps
  CHECK(log.timing.reordered_samples == 2);
  // Message 100 arrived after 104: 4 periods late.
  CHECK(log.timing.max_reorder_s == static_cast<double>(4 * kPeriod) / 1e9);
  CHECK(log.timing.non_increasing == 0);

  SUBCASE("beyond the window it is refused with the message's location") {
    o.reorder_window = 3;
    const std::string e = error_of(o);
    CHECK(e.find("reorder window (3 messages)") != std::string::npos);
    CHECK(e.find("--reorder-window") != std::string::npos);
    // In an lz4 bag the location is the chunk holding the message.
    CHECK(e.find("byte offset ") != std::string::npos);
  }
  SUBCASE("a window of 0 refuses any backwards stamp, naming the record in an uncompressed bag") {
    const std::string flat = dir.file("shuffled_flat.bag");
    const auto w = write_bag(flat, arrival, opts(Compression::none, true, 8 * 1024));
    o.path = flat;
    o.reorder_window = 0;
    const std::string e = error_of(o);
    // Arrival 101..104 are stamps 101..104; arrival 104 holds stamp 100: the first refused.
    const std::int64_t at = w.offsets[104];
    CHECK(e.find("message at byte offset " + std::to_string(at)) != std::string::npos);
  }
}

TEST_CASE("duplicated stamps are kept in arrival order and counted as non-increasing") {
  TempDir dir;
  const std::string path = dir.file("dup.bag");
  auto m = make_messages(50, 7);
  m[21].header_ns = m[20].header_ns;
  write_bag(path, m, opts(Compression::none, true, 4 * 1024));
  LogOptions o;
  o.path = path;
  const Log log = read_log(o);
  check_values(log, m);
  CHECK(log.timing.non_increasing == 1);
  CHECK(log.timing.reordered_samples == 0);
}

TEST_CASE("gap policies work on a bag as on a text log") {
  TempDir dir;
  const std::string path = dir.file("gap.bag");
  auto m = make_messages(100, 8);
  for (std::size_t i = 60; i < m.size(); ++i) m[i].header_ns += 10 * kPeriod;  // 10 missing
  write_bag(path, m, opts(Compression::none, true, 4 * 1024));
  LogOptions o;
  o.path = path;
  Log log = read_log(o);
  CHECK(log.timing.gap_count == 1);
  CHECK(log.timing.largest_gap_s == static_cast<double>(11 * kPeriod) / 1e9);
  o.gaps = GapPolicy::error;
  CHECK(error_of(o).find("time stamp gap of 55 ms") != std::string::npos);
  o.gaps = GapPolicy::fill;
  log = read_log(o);
  CHECK(fill_gaps(log) == 10);
  CHECK(log.channels[0].size() == 110);
  o.gaps = GapPolicy::split;
  log = read_log(o);
  CHECK(log.timing.segment_starts == std::vector<std::int64_t>{0, 60});
}

TEST_CASE("non-finite values are refused with their location, or their rows skipped") {
  TempDir dir;
  const std::string path = dir.file("nan.bag");
  auto m = make_messages(100, 15);
  m[30].gyro[1] = std::numeric_limits<double>::quiet_NaN();
  m[40].accel[0] = std::numeric_limits<double>::infinity();
  const auto w = write_bag(path, m, opts(Compression::none, true, 4 * 1024));
  LogOptions o;
  o.path = path;
  CHECK(error_of(o).find("non-finite value (NaN or Inf) in channel gy of the message at byte "
                         "offset " + std::to_string(w.offsets[30])) != std::string::npos);
  o.nonfinite = NonFinitePolicy::skip_row;
  const Log log = read_log(o);
  CHECK(log.timing.rows_skipped_nonfinite == 2);
  CHECK(log.timing.samples == 98);
  CHECK(log.timing.gap_count == 2);  // each skipped row leaves a one-sample gap
  // Only the selected channels count: without ax the Inf of message 40 is not looked at.
  o.columns = {"gx", "gy", "gz"};
  CHECK(read_log(o).timing.rows_skipped_nonfinite == 1);
}

TEST_CASE("columns pick among the six Imu channels") {
  TempDir dir;
  const std::string path = dir.file("imu.bag");
  const auto m = make_messages(20, 9);
  write_bag(path, m, {});
  LogOptions o;
  o.path = path;
  o.columns = {"az", "gx"};
  const Log log = read_log(o);
  CHECK(log.channel_names == std::vector<std::string>{"az", "gx"});
  REQUIRE(log.channels.size() == 2);
  CHECK(same_bits(log.channels[0][7], m[7].accel[2]));
  CHECK(same_bits(log.channels[1][7], m[7].gyro[0]));
  o.columns = {"gq"};
  CHECK(error_of(o).find("unknown channel \"gq\" for a sensor_msgs/Imu topic (available: gx, gy, "
                         "gz, ax, ay, az)") != std::string::npos);
  o.columns = {"gx", "gx"};
  CHECK(error_of(o).find("selected twice") != std::string::npos);
  o.columns = {};
  o.time_column = "t";
  CHECK(error_of(o).find("a ROS bag has its own time stamps") != std::string::npos);
  o.time_column = "";
  o.reorder_window = -1;
  CHECK(error_of(o).find("reorder window must be in 0..") != std::string::npos);
}

TEST_CASE("bags are recognised by magic bytes, extension or a metadata.yaml folder") {
  TempDir dir;
  const std::string renamed = dir.file("recording.dat");
  write_bag(renamed, make_messages(5, 10), {});
  CHECK(is_bag_path(renamed));
  LogOptions o;
  o.path = renamed;
  CHECK(read_log(o).channels[0].size() == 5);
  CHECK(is_bag_path(dir.file("missing.bag")));
  CHECK(is_bag_path(dir.file("missing.mcap")));
  CHECK(is_bag_path(dir.file("missing.db3")));
  CHECK_FALSE(is_bag_path(dir.file("missing.csv")));
  CHECK_FALSE(is_bag_path("-"));
  const std::string csv = dir.file("log.csv");
  write_bytes(csv, "t,gx\n0,1\n");
  CHECK_FALSE(is_bag_path(csv));
  const std::string folder = dir.file("rosbag2_run");
  fs::create_directories(folder);
  CHECK_FALSE(is_bag_path(folder));
  write_bytes(folder + "/metadata.yaml", "rosbag2_bagfile_information:\n");
  CHECK(is_bag_path(folder));
  // A missing .bag is an Error naming the file (from the bag reader, not the text reader).
  o.path = dir.file("missing.bag");
  CHECK(error_of(o).find("missing.bag: cannot open") != std::string::npos);
}

TEST_CASE("the index is used: chunks without the topic are never read") {
  // 100 Imu messages, five 10 kB /tf messages (8 KiB chunks: each closes a chunk, so the 2nd to
  // 5th /tf chunks hold /tf alone), 100 more Imu messages. One /tf-only chunk then gets a broken
  // lz4 frame: an indexed bag skips it by its chunk info, a sequential scan must open it.
  const auto m = make_messages(200, 15);
  for (const bool indexed : {true, false}) {
    CAPTURE(indexed);
    TempDir dir;
    const std::string path = dir.file("skip.bag");
    Ros1BagWriter w(path, opts(Compression::lz4, indexed, 8 * 1024));
    const auto tf = w.add_connection("/tf", "tf2_msgs/TFMessage");
    const auto imu = w.add_connection("/imu/data", "sensor_msgs/Imu");
    for (std::size_t i = 0; i < 100; ++i) w.write_imu(imu, m[i]);
    const std::size_t before = w.chunk_positions().size();
    for (int k = 0; k < 5; ++k) w.write_message(tf, m[99].receive_ns, std::string(10000, 'x'));
    REQUIRE(w.chunk_positions().size() == before + 5);
    for (std::size_t i = 100; i < 200; ++i) w.write_imu(imu, m[i]);
    w.finish();
    const std::int64_t tf_only = w.chunk_positions()[before + 2];
    std::string bytes = read_bytes(path);
    std::uint32_t header_len = 0;
    std::memcpy(&header_len, bytes.data() + tf_only, 4);
    // The chunk's data (an lz4 frame) starts after its header and the 4-byte data length.
    bytes.replace(static_cast<std::size_t>(tf_only) + 4 + header_len + 4, 4, "\xee\xee\xee\xee");
    write_bytes(path, bytes);
    LogOptions o;
    o.path = path;
    o.topic = "/imu/data";
    if (indexed) {
      check_values(read_log(o), m);
    } else {
      const std::string e = error_of(o);
      CHECK(e.find("chunk at byte offset " + std::to_string(tf_only) + ": corrupt lz4 data") !=
            std::string::npos);
    }
  }
}

TEST_CASE("a truncated chunk is a ParseError naming its byte offset") {
  TempDir dir;
  const std::string path = dir.file("cut.bag");
  const auto w = write_bag(path, make_messages(600, 11), opts(Compression::bz2, true, 16 * 1024));
  REQUIRE(w.chunks.size() > 3);
  const std::int64_t chunk = w.chunks[2];
  const std::string bytes = read_bytes(path);
  write_bytes(path, bytes.substr(0, static_cast<std::size_t>(chunk) + 100));
  LogOptions o;
  o.path = path;
  o.topic = "/imu/data";
  const std::string e = error_of(o);
  CHECK(e.find("truncated record at byte offset " + std::to_string(chunk)) != std::string::npos);
}

TEST_CASE("a record whose length runs past its chunk is a ParseError naming its byte offset") {
  TempDir dir;
  const std::string path = dir.file("badlen.bag");
  const auto w = write_bag(path, make_messages(300, 12), opts(Compression::none, true, 8 * 1024));
  const std::int64_t at = w.offsets[123];
  std::string bytes = read_bytes(path);
  std::uint32_t header_len = 0;
  std::memcpy(&header_len, bytes.data() + at, 4);
  const std::uint32_t huge = 0x7fffffff;
  std::memcpy(bytes.data() + at + 4 + header_len, &huge, 4);
  write_bytes(path, bytes);
  LogOptions o;
  o.path = path;
  o.topic = "/imu/data";
  const std::string e = error_of(o);
  CHECK(e.find("corrupt record at byte offset " + std::to_string(at)) != std::string::npos);
  CHECK(e.find("runs past the end of the chunk") != std::string::npos);
}

TEST_CASE("an unknown chunk compression is a ParseError naming the chunk") {
  TempDir dir;
  const std::string path = dir.file("zz.bag");
  const auto w =
      write_bag(path, make_messages(50, 13), opts(Compression::none, true, 768 * 1024, "zz9"));
  LogOptions o;
  o.path = path;
  o.topic = "/imu/data";
  const std::string e = error_of(o);
  CHECK(e.find("chunk at byte offset " + std::to_string(w.chunks[0]) +
               ": unknown compression \"zz9\"") != std::string::npos);
}

TEST_CASE("a topic of another type, or a message that is no Imu, is a ParseError with the offset") {
  TempDir dir;
  SUBCASE("the connection declares another type") {
    const std::string path = dir.file("string.bag");
    Ros1BagWriter w(path, {});
    const auto s = w.add_connection("/imu/data", "std_msgs/String");
    w.write_message(s, kStart, std::string("\x05\0\0\0hello", 9));
    w.finish();
    LogOptions o;
    o.path = path;
    o.topic = "/imu/data";
    const std::string e = error_of(o);
    CHECK(e.find("connection record at byte offset ") != std::string::npos);
    CHECK(e.find("topic /imu/data has type std_msgs/String, expected sensor_msgs/Imu") !=
          std::string::npos);
  }
  SUBCASE("an Imu connection carries a short message") {
    const std::string path = dir.file("short.bag");
    Ros1BagWriter w(path, {});
    const auto imu = w.add_connection("/imu/data", "sensor_msgs/Imu");
    const auto m = make_messages(3, 14);
    w.write_imu(imu, m[0]);
    const std::int64_t at = w.write_message(imu, m[1].receive_ns, std::string(40, '\0'));
    w.finish();
    LogOptions o;
    o.path = path;
    const std::string e = error_of(o);
    CHECK(e.find("byte offset " + std::to_string(at)) != std::string::npos);
    CHECK(e.find("40-byte message on /imu/data is not a sensor_msgs/Imu") != std::string::npos);
  }
}

// --- A recording cut short (its recorder died) under LogOptions::truncated -------------------

namespace {

LogOptions cut_options(const std::string& path, TruncatedPolicy policy, const std::string& topic) {
  LogOptions o;
  o.path = path;
  o.topic = topic;
  o.truncated = policy;
  return o;
}

std::vector<Ros1Imu> first(const std::vector<Ros1Imu>& m, std::size_t n) {
  return {m.begin(), m.begin() + static_cast<std::ptrdiff_t>(n)};
}

}  // namespace

TEST_CASE("an unindexed bag cut inside an uncompressed chunk: its complete messages are used") {
  TempDir dir;
  const std::string path = dir.file("crash.bag");
  const auto m = make_messages(1500, 21);
  // 32 KiB chunks (about 80 messages): the cut falls inside a chunk, as rosbag's default
  // uncompressed 768 KiB chunks would be cut by a crash.
  const auto w = write_bag(path, m, opts(Compression::none, false, 32 * 1024));
  REQUIRE(w.chunks.size() > 10);
  const std::size_t k = 1234;
  const std::int64_t record = w.offsets.at(k);  // the record of Imu message k in the file
  const std::string bytes = read_bytes(path);
  // Cut 20 bytes into message k's record, or exactly at its start (the chunk's data then ends
  // with a complete record, yet the chunk is still cut short).
  for (const std::int64_t into : {std::int64_t{20}, std::int64_t{0}}) {
    CAPTURE(into);
    write_bytes(path, bytes.substr(0, static_cast<std::size_t>(record + into)));
    for (const std::string topic : {"", "/imu/data"}) {
      CAPTURE(topic);
      const std::string e = error_of(cut_options(path, TruncatedPolicy::error, topic));
      CHECK(e.find("cut short at byte " + std::to_string(record) + " after " + std::to_string(k) +
                   " complete messages of /imu/data") != std::string::npos);
      CHECK(e.find("--truncated use") != std::string::npos);
      const Log log = read_log(cut_options(path, TruncatedPolicy::use, topic));
      check_values(log, first(m, k));
      CHECK(log.timing.truncated_at_byte == record);
      CHECK(log.timing.truncated_file == path);
    }
  }
}

TEST_CASE("a bag cut inside a compressed chunk: the messages of the chunks before are used") {
  TempDir dir;
  const std::string path = dir.file("cut.bag");
  const auto m = make_messages(600, 22);
  // Indexed when written: the cut takes the index away, as a crash leaves index_pos unset.
  const auto w = write_bag(path, m, opts(Compression::bz2, true, 16 * 1024));
  REQUIRE(w.chunks.size() > 3);
  const std::int64_t chunk = w.chunks[2];
  write_bytes(path, read_bytes(path).substr(0, static_cast<std::size_t>(chunk) + 100));
  const Log log = read_log(cut_options(path, TruncatedPolicy::use, ""));
  const auto n = static_cast<std::size_t>(log.timing.samples);
  CHECK(n > 0);
  CHECK(n < m.size());
  check_values(log, first(m, n));
  CHECK(log.timing.truncated_at_byte == chunk);
  // The default names the same cut and the same count.
  const std::string e = error_of(cut_options(path, TruncatedPolicy::error, ""));
  CHECK(e.find("cut short at byte " + std::to_string(chunk) + " after " + std::to_string(n) +
               " complete messages of /imu/data") != std::string::npos);
}

TEST_CASE("an indexed bag whose chunk runs past the end of the file is corrupt even under use") {
  TempDir dir;
  const std::string path = dir.file("bad.bag");
  const auto w = write_bag(path, make_messages(600, 23), opts(Compression::none, true, 16 * 1024));
  const std::int64_t chunk = w.chunks.at(1);
  std::string bytes = read_bytes(path);
  std::uint32_t header_len = 0;
  std::memcpy(&header_len, bytes.data() + chunk, 4);
  const std::uint32_t past_end = static_cast<std::uint32_t>(bytes.size());  // a plausible size
  std::memcpy(bytes.data() + chunk + 4 + header_len, &past_end, 4);
  write_bytes(path, bytes);
  const std::string e = error_of(cut_options(path, TruncatedPolicy::use, "/imu/data"));
  CHECK(e.find("truncated record at byte offset " + std::to_string(chunk)) != std::string::npos);
  CHECK(e.find("--truncated use") == std::string::npos);
}
