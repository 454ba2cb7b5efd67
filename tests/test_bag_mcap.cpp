// Tests of the MCAP backend (lib/src/mcap.cpp): files written by tests/support/ros2_bag_writer.hpp
// with seeded Imu values are read back through the internal BagBackend interface.
//
// Values are compared bit for bit (==, no tolerance): the reader copies the float64 of the
// message unchanged, so any difference is a decoding bug. Corrupt files must give a ParseError
// whose message names the byte offset of the record at fault.

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "bag_backend_checks.hpp"
#include "ros2_bag_writer.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/log_reader.hpp"
#include "temp_dir.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace sigmatau;
using sigmatau::detail::ImuSample;
using sigmatau::test::CdrKind;
using sigmatau::test::check_same;
using sigmatau::test::read_all;
using sigmatau::test::ImuValue;
using sigmatau::test::McapOptions;
using sigmatau::test::Ros2Topic;

namespace {

/// A fresh directory for one test, removed when it ends.
struct TempDir : test::TempDir {
  TempDir() : test::TempDir("sigmatau_test_bag_mcap") {}
};

/// Writer options: chunk compression, summary section, footer (false: a crashed recorder).
McapOptions options(const std::string& compression = "", bool summary = true, bool footer = true) {
  McapOptions o;
  o.compression = compression;
  o.summary = summary;
  o.footer = footer;
  return o;
}

/// The Imu topic plus a second topic of another type, interleaved.
std::vector<Ros2Topic> two_topics(std::size_t n, std::uint64_t seed,
                                  CdrKind cdr = CdrKind::xcdr1_le) {
  Ros2Topic imu;
  imu.values = test::make_imu_values(n, seed);
  imu.cdr = cdr;
  Ros2Topic other;
  other.name = "/diagnostics";
  other.type = "diagnostic_msgs/msg/DiagnosticArray";
  other.values = test::make_imu_values(n / 3, seed + 1);
  return {imu, other};
}

/// The message of the ParseError thrown by `f` (fails the test when none is thrown).
template <class F>
std::string parse_error_of(F&& f) {
  try {
    f();
  } catch (const ParseError& e) {
    return e.what();
  }
  FAIL("no ParseError thrown");
  return {};
}

void patch(const fs::path& path, std::int64_t at, const std::string& bytes) {
  std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
  f.seekp(at);
  f.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::string le64(std::uint64_t v) {
  std::string s;
  test::writer_detail::put<std::uint64_t>(s, v);
  return s;
}

}  // namespace

TEST_CASE(
    "MCAP Imu values read back bit for bit in every chunk compression, with and without summary") {
  TempDir dir;
  const auto topics = two_topics(300, 11);
  for (const std::string compression : {"", "zstd", "lz4"}) {
    for (const bool summary : {true, false}) {
      for (const bool footer : {true, false}) {
        if (!footer && summary) continue;
        CAPTURE(compression);
        CAPTURE(summary);
        CAPTURE(footer);
        McapOptions o;
        o.compression = compression;
        o.summary = summary;
        o.footer = footer;
        const fs::path p = dir.file("imu.mcap");
        const auto layout = test::write_mcap(p, topics, o);
        CHECK(layout.chunk_offsets.size() > 3);  // several chunks, so chunk boundaries are crossed
        auto bag = detail::open_mcap(p.string());
        check_same(read_all(*bag, "/imu/data"), topics[0].values);
        CHECK(bag->total_bytes() == layout.size);
      }
    }
  }
}

TEST_CASE("MCAP without chunks: messages as top-level records") {
  TempDir dir;
  const auto topics = two_topics(120, 12);
  for (const bool summary : {true, false}) {
    CAPTURE(summary);
    McapOptions o;
    o.chunked = false;
    o.summary = summary;
    const fs::path p = dir.file("flat.mcap");
    const auto layout = test::write_mcap(p, topics, o);
    auto bag = detail::open_mcap(p.string());
    const auto got = read_all(*bag, "/imu/data");
    check_same(got, topics[0].values);
    // The first Imu message is the first top-level message record: its offset is reported.
    REQUIRE(!got.empty());
    CHECK(got[0].offset == layout.message_offsets[0]);
  }
}

TEST_CASE(
    "MCAP CDR encapsulations XCDR1 and XCDR2, little and big endian, decode the same values") {
  TempDir dir;
  for (const CdrKind kind :
       {CdrKind::xcdr1_le, CdrKind::xcdr1_be, CdrKind::xcdr2_le, CdrKind::xcdr2_be}) {
    CAPTURE(static_cast<int>(kind));
    const auto topics = two_topics(90, 13, kind);
    const fs::path p = dir.file("cdr.mcap");
    test::write_mcap(p, topics, options("zstd"));
    auto bag = detail::open_mcap(p.string());
    check_same(read_all(*bag, "/imu/data"), topics[0].values);
  }
}

TEST_CASE("MCAP channels with the ros1 message encoding decode as ROS 1 Imu") {
  TempDir dir;
  Ros2Topic t;
  t.type = "sensor_msgs/Imu";
  t.encoding = "ros1";
  t.values = test::make_imu_values(70, 14);
  const fs::path p = dir.file("ros1.mcap");
  test::write_mcap(p, {t}, options("lz4"));
  auto bag = detail::open_mcap(p.string());
  check_same(read_all(*bag, "/imu/data"), t.values);
}

TEST_CASE("MCAP topic listing gives types and counts, from Statistics or from a scan") {
  TempDir dir;
  const auto topics = two_topics(150, 15);
  for (const bool summary : {true, false}) {
    CAPTURE(summary);
    const fs::path p = dir.file("list.mcap");
    test::write_mcap(p, topics, options("", summary));
    auto bag = detail::open_mcap(p.string());
    const auto list = bag->topics(true);
    REQUIRE(list.size() == 2);
    CHECK(list[0].name == "/diagnostics");
    CHECK(list[0].type == "diagnostic_msgs/msg/DiagnosticArray");
    CHECK(list[0].messages == static_cast<std::int64_t>(topics[1].values.size()));
    CHECK(list[1].name == "/imu/data");
    CHECK(list[1].type == "sensor_msgs/msg/Imu");
    CHECK(list[1].messages == static_cast<std::int64_t>(topics[0].values.size()));
    // Listing first and reading afterwards still delivers every message.
    check_same(read_all(*bag, "/imu/data"), topics[0].values);
  }
}

TEST_CASE("MCAP select: a missing topic is false with a summary, an error at the end without") {
  TempDir dir;
  const auto topics = two_topics(50, 16);
  const fs::path p = dir.file("missing.mcap");
  test::write_mcap(p, topics);
  CHECK_FALSE(detail::open_mcap(p.string())->select("/imu/raw"));
  test::write_mcap(p, topics, options("", false, false));
  auto bag = detail::open_mcap(p.string());
  CHECK(bag->select("/imu/raw"));  // unknown until read through
  ImuSample s;
  const std::string msg = parse_error_of([&] { bag->next(s); });
  CHECK(msg.find("no topic /imu/raw") != std::string::npos);
  CHECK(msg.find("/imu/data (sensor_msgs/msg/Imu)") != std::string::npos);
}

TEST_CASE("MCAP chunks without the selected topic are skipped by the chunk index") {
  TempDir dir;
  // Topic A fills the first chunks alone, topic B the later ones: reading B must not need A's.
  Ros2Topic a;
  a.name = "/a";
  a.values = test::make_imu_values(200, 17);
  Ros2Topic b;
  b.name = "/b";
  b.values = test::make_imu_values(40, 18);
  const fs::path p = dir.file("skip.mcap");
  McapOptions o;
  o.chunk_messages = 10;
  const auto layout = test::write_mcap(p, {a, b}, o);
  // Corrupt the records of the last chunk, which holds only /a (b's 40 messages end earlier):
  // reading /b must not touch it, reading /a must fail on it.
  const std::int64_t last = layout.chunk_offsets.back();
  patch(p, last + 9 + 32 + 8 + 30, "\xff\xff\xff\xff");
  auto bag_b = detail::open_mcap(p.string());
  check_same(read_all(*bag_b, "/b"), b.values);
  auto bag_a = detail::open_mcap(p.string());
  REQUIRE(bag_a->select("/a"));
  ImuSample s;
  const std::string msg = parse_error_of([&] {
    while (bag_a->next(s)) {
    }
  });
  CHECK(msg.find("chunk at byte offset " + std::to_string(last)) != std::string::npos);
}

TEST_CASE("MCAP from a crashed recorder: ends cleanly at a record boundary, else names the cut") {
  TempDir dir;
  const auto topics = two_topics(200, 19);
  const fs::path p = dir.file("crash.mcap");
  const auto layout = test::write_mcap(p, topics, options("zstd", false, false));
  SUBCASE("the file ends after a complete chunk") {
    auto bag = detail::open_mcap(p.string());
    check_same(read_all(*bag, "/imu/data"), topics[0].values);
  }
  SUBCASE("the file ends inside the last chunk") {
    const std::int64_t last = layout.chunk_offsets.back();
    fs::resize_file(p, static_cast<std::uintmax_t>(last + 100));
    auto bag = detail::open_mcap(p.string());
    REQUIRE(bag->select("/imu/data"));
    std::vector<ImuSample> got;
    ImuSample s;
    const std::string msg = parse_error_of([&] {
      while (bag->next(s)) got.push_back(s);
    });
    CHECK(msg.find("truncated record at byte offset " + std::to_string(last)) != std::string::npos);
    CHECK(msg.find("cut short") != std::string::npos);
    // Every message of the complete chunks came out first.
    CHECK(got.size() > 0);
    CHECK(got.size() < topics[0].values.size());
    std::vector<ImuValue> prefix(
        topics[0].values.begin(),
        topics[0].values.begin() + static_cast<std::ptrdiff_t>(got.size()));
    check_same(got, prefix);
  }
}

TEST_CASE("MCAP corrupt files give a ParseError naming the byte offset") {
  TempDir dir;
  const auto topics = two_topics(120, 20);
  const fs::path p = dir.file("bad.mcap");
  std::string expect;
  SUBCASE("bad CRC of an uncompressed chunk") {
    const auto layout = test::write_mcap(p, topics);
    const std::int64_t chunk = layout.chunk_offsets[1];
    patch(p, chunk + 9 + 32 + 8 + 200, "\x5a");  // a byte inside a message's data
    expect = "chunk at byte offset " + std::to_string(chunk) + ": CRC32";
  }
  SUBCASE("bad CRC of a zstd chunk is found after decompression") {
    // Flip a stored CRC: the data decompresses fine, the check must still fire.
    const auto layout = test::write_mcap(p, topics, options("zstd"));
    const std::int64_t chunk = layout.chunk_offsets[2];
    patch(p, chunk + 9 + 24, "\x01\x02\x03\x04");
    expect = "chunk at byte offset " + std::to_string(chunk) + ": CRC32";
  }
  SUBCASE("truncated chunk (file cut inside a chunk, footer gone)") {
    const auto layout = test::write_mcap(p, topics, options("lz4"));
    const std::int64_t chunk = layout.chunk_offsets[1];
    fs::resize_file(p, static_cast<std::uintmax_t>(chunk + 60));
    expect = "truncated record at byte offset " + std::to_string(chunk);
  }
  SUBCASE("bad record length of a chunk") {
    const auto layout = test::write_mcap(p, topics);
    const std::int64_t chunk = layout.chunk_offsets[1];
    patch(p, chunk + 1, le64(std::uint64_t{1} << 40));
    expect = "corrupt record at byte offset " + std::to_string(chunk);
  }
  SUBCASE("bad record length inside an uncompressed chunk") {
    McapOptions o;
    o.crc = false;
    const auto layout = test::write_mcap(p, topics, o);
    const std::int64_t chunk = layout.chunk_offsets[0];
    const std::int64_t records = chunk + 9 + 32 + 8;      // compression "" has no name bytes
    patch(p, records + 1, le64(std::uint64_t{1} << 30));  // the first record's length
    expect = "record at byte offset " + std::to_string(records);
  }
  SUBCASE("unknown compression") {
    const auto layout = test::write_mcap(p, topics, options("brotli"));
    expect = "chunk at byte offset " + std::to_string(layout.chunk_offsets[0]) +
             ": unknown compression \"brotli\"";
  }
  SUBCASE("corrupt zstd data") {
    McapOptions o = options("zstd");
    o.crc = false;
    const auto layout = test::write_mcap(p, topics, o);
    const std::int64_t chunk = layout.chunk_offsets[0];
    patch(p, chunk + 9 + 32 + 4 + 8 + 6, std::string(8, '\xee'));
    expect = "chunk at byte offset " + std::to_string(chunk);
  }
  SUBCASE("a message too short for an Imu") {
    Ros2Topic t;
    t.values = test::make_imu_values(10, 21);
    McapOptions o;
    o.chunked = false;
    const auto layout = test::write_mcap(p, {t}, o);
    const std::int64_t msg = layout.message_offsets[3];
    // A frame_id length of 255 leaves too few bytes for the Imu body after it.
    patch(p, msg + 9 + 22 + 4 + 8, "\xff\x00\x00\x00");
    expect = "record at byte offset " + std::to_string(msg);
  }
  auto bag = detail::open_mcap(p.string());
  const std::string msg = parse_error_of([&] {
    REQUIRE(bag->select("/imu/data"));
    ImuSample s;
    while (bag->next(s)) {
    }
  });
  INFO(msg);
  CHECK(msg.find(expect) != std::string::npos);
}

TEST_CASE("MCAP wrong message type on the topic names the channel record") {
  TempDir dir;
  const auto topics = two_topics(60, 22);
  for (const bool summary : {true, false}) {
    CAPTURE(summary);
    const fs::path p = dir.file("type.mcap");
    test::write_mcap(p, topics, options("", summary, summary));
    auto bag = detail::open_mcap(p.string());
    const std::string msg = parse_error_of([&] {
      bag->select("/diagnostics");
      ImuSample s;
      while (bag->next(s)) {
      }
    });
    CHECK(msg.find("channel record at byte offset") != std::string::npos);
    CHECK(msg.find("diagnostic_msgs/msg/DiagnosticArray") != std::string::npos);
  }
}

TEST_CASE("MCAP a file that is no MCAP is refused at byte offset 0") {
  TempDir dir;
  const fs::path p = dir.file("not.mcap");
  std::ofstream(p) << "#ROSBAG V2.0\nnot an mcap file at all";
  const std::string msg = parse_error_of([&] { detail::open_mcap(p.string()); });
  CHECK(msg.find("not an MCAP file: byte offset 0") != std::string::npos);
}

TEST_CASE(
    "MCAP compressed as a whole (.mcap.zstd, rosbag2 file compression) is refused with advice") {
  TempDir dir;
  const fs::path plain = dir.file("plain.mcap");
  test::write_mcap(plain, two_topics(30, 23));
  std::ifstream in(plain, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), {});
  const fs::path p = dir.file("imu.mcap.zstd");
  test::writer_detail::write_file(p, test::writer_detail::compress(bytes, "zstd"));
  std::string msg;
  try {
    detail::open_mcap(p.string());
  } catch (const Error& e) {
    msg = e.what();
  }
  CHECK(msg.find("imu.mcap.zstd") != std::string::npos);
  CHECK(msg.find("decompress it first") != std::string::npos);
}

TEST_CASE("MCAP an empty chunk (no records) is skipped") {
  // Found by fuzz_bag (tests/data/fuzz/bag/empty_chunk.bin): a chunk whose records are 0 bytes
  // made the reader copy 0 bytes into a null buffer (UBSan). An empty chunk is legal MCAP: it is
  // inserted here before the first chunk of a file without summary (no offsets to fix) and every
  // message must still come back.
  TempDir dir;
  const auto topics = two_topics(120, 24);
  const fs::path p = dir.file("empty_chunk.mcap");
  McapOptions o = options("", false, false);
  o.crc = false;
  const auto layout = test::write_mcap(p, topics, o);
  std::string content;  // start, end, uncompressed size, CRC, compression "", records length
  content += le64(0) + le64(0) + le64(0) + std::string(4, '\0') + std::string(4, '\0') + le64(0);
  std::string record = std::string(1, '\x06') + le64(content.size()) + content;
  std::ifstream in(p, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), {});
  in.close();
  bytes.insert(static_cast<std::size_t>(layout.chunk_offsets.at(0)), record);
  std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes;
  auto bag = detail::open_mcap(p.string());
  check_same(read_all(*bag, "/imu/data"), topics[0].values);
}

// --- A recording cut short (its recorder died) under LogOptions::truncated -------------------

namespace {

/// The six channels of `got` equal the first `n` messages of `want`, bit for bit.
void check_prefix(const Log& got, const std::vector<ImuValue>& want, std::size_t n) {
  REQUIRE(got.channels.size() == 6);
  REQUIRE(got.channels[0].size() == n);
  for (std::size_t i = 0; i < n; ++i) {
    INFO("message " << i);
    for (int k = 0; k < 3; ++k) {
      CHECK(got.channels[static_cast<std::size_t>(k)][i] == want[i].gyro[k]);
      CHECK(got.channels[static_cast<std::size_t>(k) + 3][i] == want[i].accel[k]);
    }
  }
}

LogOptions cut_options(const fs::path& p, TruncatedPolicy policy, const std::string& topic) {
  LogOptions o;
  o.path = p.string();
  o.topic = topic;
  o.truncated = policy;
  return o;
}

}  // namespace

TEST_CASE("MCAP cut short inside a message: an error naming the cut and the count, or used") {
  TempDir dir;
  Ros2Topic imu;
  imu.values = test::make_imu_values(500, 31);
  McapOptions o = options("", false, false);
  o.chunked = false;
  const fs::path p = dir.file("cut.mcap");
  const auto layout = test::write_mcap(p, {imu}, o);
  const std::size_t k = 321;  // the file ends 30 bytes into message k's record
  const std::int64_t cut = layout.message_offsets.at(k);
  fs::resize_file(p, static_cast<std::uintmax_t>(cut + 30));
  // Without --topic the topic scan meets the cut first; with it, the read does.
  for (const std::string topic : {"", "/imu/data"}) {
    CAPTURE(topic);
    const std::string msg = parse_error_of(
        [&] { read_log(cut_options(p, TruncatedPolicy::error, topic)); });
    CHECK(msg.find("cut short at byte " + std::to_string(cut) + " after " + std::to_string(k) +
                   " complete messages of /imu/data") != std::string::npos);
    CHECK(msg.find("truncated record at byte offset " + std::to_string(cut)) != std::string::npos);
    CHECK(msg.find("--truncated use") != std::string::npos);

    const Log log = read_log(cut_options(p, TruncatedPolicy::use, topic));
    check_prefix(log, imu.values, k);
    CHECK(log.timing.samples == static_cast<std::int64_t>(k));
    CHECK(log.timing.truncated_at_byte == cut);
    CHECK(log.timing.truncated_file == p.string());
  }
}

TEST_CASE("MCAP cut short inside its last chunk: the messages of the complete chunks are used") {
  TempDir dir;
  Ros2Topic imu;
  imu.values = test::make_imu_values(400, 32);
  const fs::path p = dir.file("cut.mcap");
  const auto layout = test::write_mcap(p, {imu}, options("zstd", false, false));
  REQUIRE(layout.chunk_offsets.size() == 10);  // 40 messages per chunk
  const std::int64_t last = layout.chunk_offsets.back();
  fs::resize_file(p, static_cast<std::uintmax_t>(last + 100));
  SUBCASE("the backend after allow_cut") {
    auto bag = detail::open_mcap(p.string());
    bag->allow_cut();
    const auto got = read_all(*bag, "/imu/data");
    check_same(got, std::vector<ImuValue>(imu.values.begin(), imu.values.begin() + 360));
    CHECK(bag->cut().at_byte == last);
    CHECK(bag->cut().detail.find("truncated record at byte offset " + std::to_string(last)) !=
          std::string::npos);
  }
  SUBCASE("LogReader under TruncatedPolicy::use") {
    const Log log = read_log(cut_options(p, TruncatedPolicy::use, ""));
    check_prefix(log, imu.values, 360);
    CHECK(log.timing.truncated_at_byte == last);
  }
  SUBCASE("the same file ending at a chunk boundary is complete, not cut") {
    fs::resize_file(p, static_cast<std::uintmax_t>(last));
    const Log log = read_log(cut_options(p, TruncatedPolicy::error, ""));
    check_prefix(log, imu.values, 360);
    CHECK(log.timing.truncated_at_byte == -1);
  }
}

TEST_CASE("MCAP with a footer whose record runs past the data is corrupt even under use") {
  TempDir dir;
  Ros2Topic imu;
  imu.values = test::make_imu_values(200, 33);
  const fs::path p = dir.file("bad.mcap");
  const auto layout = test::write_mcap(p, {imu}, options("lz4", false, true));
  const std::int64_t chunk = layout.chunk_offsets.at(2);
  // A plausible length (1 MiB, under the chunk limit) that runs past the end of the data section:
  // with a footer the file is complete, so this is a corrupt length, not a cut.
  patch(p, chunk + 1, le64(std::uint64_t{1} << 20));
  const std::string msg = parse_error_of(
      [&] { read_log(cut_options(p, TruncatedPolicy::use, "/imu/data")); });
  CHECK(msg.find("corrupt record at byte offset " + std::to_string(chunk)) != std::string::npos);
  CHECK(msg.find("cut short") == std::string::npos);
}

TEST_CASE("rosbag2 folder of MCAP files: the last file cut short is used, an earlier one is not") {
  TempDir dir;
  Ros2Topic imu;
  imu.values = test::make_imu_values(400, 34);
  const fs::path folder = dir.file("rec");
  test::write_rosbag2_folder(folder, "mcap", {imu}, 2);
  const fs::path first = folder / "rec_0.mcap";
  const fs::path last = folder / "rec_1.mcap";
  REQUIRE(fs::is_regular_file(first));
  REQUIRE(fs::is_regular_file(last));
  // Each file holds 200 messages in 5 uncompressed chunks of 40, so both have the layout of a
  // rewrite of the last one: its last chunk's offset is where the cuts go.
  Ros2Topic part;
  part.values.assign(imu.values.begin() + 200, imu.values.end());
  const fs::path copy = dir.file("copy.mcap");
  const auto layout = test::write_mcap(copy, {part});
  REQUIRE(layout.chunk_offsets.size() == 5);
  REQUIRE(fs::file_size(copy) == fs::file_size(last));
  const std::int64_t cut = layout.chunk_offsets.back();
  SUBCASE("the last file cut inside its last chunk") {
    fs::resize_file(last, static_cast<std::uintmax_t>(cut + 50));
    const std::string msg = parse_error_of(
        [&] { read_log(cut_options(folder, TruncatedPolicy::error, "")); });
    CHECK(msg.find("rec_1.mcap") != std::string::npos);
    CHECK(msg.find("cut short at byte " + std::to_string(cut) + " after 360 complete messages") !=
          std::string::npos);
    const Log log = read_log(cut_options(folder, TruncatedPolicy::use, ""));
    check_prefix(log, imu.values, 360);
    CHECK(log.timing.truncated_at_byte == cut);
    CHECK(log.timing.truncated_file == last.string());
  }
  SUBCASE("the first file cut: corrupt, since a later file follows") {
    fs::resize_file(first, static_cast<std::uintmax_t>(cut + 50));
    const std::string msg = parse_error_of(
        [&] { read_log(cut_options(folder, TruncatedPolicy::use, "")); });
    CHECK(msg.find("rec_0.mcap") != std::string::npos);
    CHECK(msg.find("a file before the last of the recording") != std::string::npos);
  }
}
