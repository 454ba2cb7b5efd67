// Bag messages on a connection (ROS 1) or channel (MCAP) that no record declares (issue 28):
// they were skipped without a word while the topic note still counted them. Now each reader
// counts them into a warning naming the id and the first one's location, and a topic whose
// stated count (index, summary statistics) differs from the messages found says so, its listed
// count being the messages found.
//
// The bags are written by the test writers and one message's connection / channel id is then
// overwritten with an id nothing declares, as a corrupt byte would.
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

#include "ros1_bag_writer.hpp"
#include "ros2_bag_writer.hpp"
#include "sigmatau/log_reader.hpp"
#include "temp_dir.hpp"
#include "test_support.hpp"

using namespace sigmatau;
using sigmatau::test::Ros1BagWriter;
using sigmatau::test::Ros1Imu;

namespace {

constexpr std::size_t kMessages = 3000;
constexpr std::int64_t kStartNs = 1700000000123456789;
constexpr std::int64_t kPeriodNs = 5000000;  // 200 Hz
/// The message whose id is overwritten, and the id written: nothing declares connection 9.
constexpr std::size_t kPatched = 1000;
constexpr std::uint32_t kUndeclared = 9;

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}
void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// A ROS 1 bag with uncompressed chunks: /tf, then kMessages Imu messages on /imu/data, the
/// kPatched-th on connection kUndeclared. Returns the offset of that message's record.
std::int64_t write_ros1(const std::string& path, bool indexed) {
  Ros1BagWriter::Options options;
  options.indexed = indexed;
  options.chunk_bytes = 64 * 1024;
  Ros1BagWriter w(path, options);
  const auto tf = w.add_connection("/tf", "tf2_msgs/TFMessage");
  const auto imu = w.add_connection("/imu/data", "sensor_msgs/Imu");
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 1e-3);
  std::int64_t patched_at = -1;
  for (std::size_t i = 0; i < kMessages; ++i) {
    Ros1Imu m;
    m.header_ns = kStartNs + static_cast<std::int64_t>(i) * kPeriodNs;
    m.receive_ns = m.header_ns + 400000;
    for (double& g : m.gyro) g = noise(rng);
    const std::int64_t at = w.write_imu(imu, m);
    if (i == kPatched) patched_at = at;
    if (i % 10 == 0) w.write_message(tf, m.receive_ns, std::string(48, 'x'));
  }
  w.finish();
  // The record header's "conn=" field, 4 little-endian bytes after the name.
  std::string bytes = read_bytes(path);
  const std::size_t field = bytes.find("conn=", static_cast<std::size_t>(patched_at));
  REQUIRE(field != std::string::npos);
  REQUIRE(field < static_cast<std::size_t>(patched_at) + 64);
  const std::uint32_t id = kUndeclared;
  std::memcpy(&bytes[field + 5], &id, 4);  // little-endian hosts (x86, arm64)
  write_bytes(path, bytes);
  return patched_at;
}

std::vector<std::string> warnings_of(const Log& log) { return log.timing.warnings; }

bool has(const std::vector<std::string>& lines, const std::string& part) {
  for (const auto& l : lines) {
    if (l.find(part) != std::string::npos) return true;
  }
  return false;
}

}  // namespace

TEST_CASE("ROS 1: a message on an undeclared connection is skipped, counted and located") {
  test::TempDir dir("sigmatau_test_bag_undeclared");
  for (const bool indexed : {true, false}) {
    INFO("indexed: " << indexed);
    const std::string path = dir.file(indexed ? "indexed.bag" : "unindexed.bag").string();
    const std::int64_t at = write_ros1(path, indexed);
    LogOptions options;
    options.path = path;
    options.gaps = GapPolicy::report;  // the skipped message leaves a one-sample gap
    const Log log = read_log(options);
    CHECK(log.channels[0].size() == kMessages - 1);
    const auto w = warnings_of(log);
    INFO("warnings: " << (w.empty() ? std::string("none") : w.front()));
    CHECK(has(w, "skipped 1 message on connection 9, which no connection record declares (the "
                 "first: record at byte offset " + std::to_string(at)));
    CHECK(log.timing.gap_count == 1);  // and the time stamps show where it was
  }
}

TEST_CASE("ROS 1: the index's count of the topic is checked against the messages found") {
  test::TempDir dir("sigmatau_test_bag_undeclared");
  const std::string path = dir.file("indexed.bag").string();
  write_ros1(path, true);
  LogOptions options;
  options.path = path;
  options.gaps = GapPolicy::report;
  const Log log = read_log(options);
  const auto w = warnings_of(log);
  CHECK(has(w, "the bag states 3000 messages on /imu/data, but 2999 were found in it and read"));
  // The topic note (bag_topics, read without a topic) lists what was found, not the index.
  bool listed = false;
  for (const BagTopic& t : log.timing.bag_topics) {
    if (t.name != "/imu/data") continue;
    listed = true;
    CHECK(t.messages == 2999);
  }
  CHECK(listed);
}

TEST_CASE("ROS 1: an intact bag has no warning") {
  test::TempDir dir("sigmatau_test_bag_undeclared");
  const std::string path = dir.file("intact.bag").string();
  Ros1BagWriter w(path, Ros1BagWriter::Options{});
  const auto imu = w.add_connection("/imu/data", "sensor_msgs/Imu");
  for (std::size_t i = 0; i < 100; ++i) {
    Ros1Imu m;
    m.header_ns = m.receive_ns = kStartNs + static_cast<std::int64_t>(i) * kPeriodNs;
    w.write_imu(imu, m);
  }
  w.finish();
  LogOptions options;
  options.path = path;
  const Log log = read_log(options);
  CHECK(log.timing.warnings.empty());
  REQUIRE(log.timing.bag_topics.size() == 1);
  CHECK(log.timing.bag_topics[0].messages == 100);
}

TEST_CASE("MCAP: a message on an undeclared channel is skipped, counted and located") {
  test::TempDir dir("sigmatau_test_bag_undeclared");
  const std::string path = dir.file("undeclared.mcap").string();
  test::Ros2Topic imu;
  imu.values = test::make_imu_values(kMessages, 3);
  test::McapOptions options;
  options.chunked = false;  // top-level messages: the writer gives their offsets
  const test::McapLayout layout = test::write_mcap(path, {imu}, options);
  std::string bytes = read_bytes(path);
  const auto at = static_cast<std::size_t>(layout.message_offsets[kPatched]);
  const std::uint16_t id = kUndeclared;
  std::memcpy(&bytes[at + 9], &id, 2);  // after the opcode and the 8-byte length
  write_bytes(path, bytes);

  LogOptions log_options;
  log_options.path = path;
  log_options.gaps = GapPolicy::report;
  const Log log = read_log(log_options);
  CHECK(log.channels[0].size() == kMessages - 1);
  const auto w = warnings_of(log);
  CHECK(has(w, "skipped 1 message on channel 9, which no channel record declares (the first: "
               "record at byte offset " + std::to_string(at)));
  CHECK(has(w, "the bag states 3000 messages on /imu/data, but 2999 were found in it and read"));
}
