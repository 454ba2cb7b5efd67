// Tests of the rosbag2 SQLite backend (lib/src/rosbag2_sqlite.cpp) and the rosbag2 folder backend
// (lib/src/rosbag2_folder.cpp): .db3 files and recording folders written by
// tests/support/ros2_bag_writer.hpp with seeded Imu values, read back through BagBackend.
//
// Values are compared bit for bit (==, no tolerance): the reader copies the float64 of the
// message unchanged. Errors in a .db3 must name the row id of the message at fault.
#include <sqlite3.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "bag_backend_checks.hpp"
#include "ros2_bag_writer.hpp"
#include "sigmatau/error.hpp"
#include "temp_dir.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace sigmatau;
using sigmatau::detail::ImuSample;
using sigmatau::test::CdrKind;
using sigmatau::test::check_same;
using sigmatau::test::read_all;
using sigmatau::test::ImuValue;
using sigmatau::test::Ros2Topic;

namespace {

/// A fresh directory for one test, removed when it ends.
struct TempDir : test::TempDir {
  TempDir() : test::TempDir("sigmatau_test_bag_rosbag2") {}
};

std::vector<Ros2Topic> two_topics(std::size_t n, std::uint64_t seed,
                                  CdrKind cdr = CdrKind::xcdr1_le) {
  Ros2Topic imu;
  imu.values = test::make_imu_values(n, seed);
  imu.cdr = cdr;
  Ros2Topic other;
  other.name = "/tf";
  other.type = "tf2_msgs/msg/TFMessage";
  other.values = test::make_imu_values(n / 4, seed + 1);
  return {imu, other};
}

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  FAIL("no Error thrown");
  return {};
}

std::string drain(detail::BagBackend& bag, const std::string& topic) {
  return error_of([&] {
    bag.select(topic);
    ImuSample s;
    while (bag.next(s)) {
    }
  });
}

/// Runs one SQL statement on a test database.
void sql(const fs::path& db, const std::string& statement) {
  sqlite3* h = nullptr;
  REQUIRE(sqlite3_open(db.string().c_str(), &h) == SQLITE_OK);
  const int rc = sqlite3_exec(h, statement.c_str(), nullptr, nullptr, nullptr);
  sqlite3_close(h);
  REQUIRE(rc == SQLITE_OK);
}

}  // namespace

TEST_CASE("db3 Imu values read back bit for bit, plain and per-message zstd, every CDR kind") {
  TempDir dir;
  for (const bool zstd : {false, true}) {
    for (const CdrKind kind :
         {CdrKind::xcdr1_le, CdrKind::xcdr1_be, CdrKind::xcdr2_le, CdrKind::xcdr2_be}) {
      CAPTURE(zstd);
      CAPTURE(static_cast<int>(kind));
      const auto topics = two_topics(250, 31, kind);
      const fs::path p = dir.file("imu.db3");
      test::write_db3(p, topics, zstd);
      auto bag = detail::open_rosbag2_sqlite(p.string());
      const auto got = read_all(*bag, "/imu/data");
      check_same(got, topics[0].values);
      // Row ids come in insertion order and are reported for every message.
      for (std::size_t i = 1; i < got.size(); ++i) CHECK(got[i].id > got[i - 1].id);
      CHECK(bag->bytes_read() == bag->total_bytes());
    }
  }
}

TEST_CASE("db3 topic listing gives types and counts") {
  TempDir dir;
  const auto topics = two_topics(120, 32);
  const fs::path p = dir.file("list.db3");
  test::write_db3(p, topics);
  auto bag = detail::open_rosbag2_sqlite(p.string());
  const auto quick = bag->topics(false);
  REQUIRE(quick.size() == 2);
  CHECK(quick[0].messages == -1);  // not counted unless asked
  const auto list = bag->topics(true);
  REQUIRE(list.size() == 2);
  CHECK(list[0].name == "/imu/data");
  CHECK(list[0].type == "sensor_msgs/msg/Imu");
  CHECK(list[0].messages == 120);
  CHECK(list[1].name == "/tf");
  CHECK(list[1].type == "tf2_msgs/msg/TFMessage");
  CHECK(list[1].messages == 30);
  CHECK_FALSE(bag->select("/imu/raw"));
}

TEST_CASE("db3 wrong message type on the topic names the topics row") {
  TempDir dir;
  const fs::path p = dir.file("type.db3");
  test::write_db3(p, two_topics(40, 33));
  auto bag = detail::open_rosbag2_sqlite(p.string());
  const std::string msg = drain(*bag, "/tf");
  CHECK(msg.find("topics table row id 2: topic /tf has type tf2_msgs/msg/TFMessage") !=
        std::string::npos);
}

TEST_CASE("db3 corrupt messages give a ParseError naming the row id") {
  TempDir dir;
  const fs::path p = dir.file("bad.db3");
  std::string expect;
  SUBCASE("a truncated message") {
    test::write_db3(p, two_topics(40, 34));
    sql(p, "UPDATE messages SET data = substr(data, 1, 100) WHERE id = 7");
    expect = "messages row id 7: 100-byte message on /imu/data is not a sensor_msgs/Imu";
  }
  SUBCASE("a corrupt per-message zstd frame") {
    test::write_db3(p, two_topics(40, 35), true);
    sql(p,
        "UPDATE messages SET data = CAST(substr(data, 1, 12) || zeroblob(20) AS BLOB) WHERE id = "
        "9");
    expect = "messages row id 9 at byte offset 0: corrupt zstd data";
  }
  SUBCASE("an unsupported CDR encapsulation") {
    test::write_db3(p, two_topics(40, 36));
    sql(p, "UPDATE messages SET data = CAST(X'0003' || substr(data, 3) AS BLOB) WHERE id = 5");
    expect =
        "messages row id 5: 324-byte message on /imu/data is not a sensor_msgs/Imu: unsupported "
        "CDR encapsulation";
  }
  auto bag = detail::open_rosbag2_sqlite(p.string());
  const std::string msg = drain(*bag, "/imu/data");
  INFO(msg);
  CHECK(msg.find(expect) != std::string::npos);
}

TEST_CASE("db3 files cut short say so") {
  TempDir dir;
  const fs::path whole = dir.file("whole.db3");
  test::write_db3(whole, two_topics(2000, 38));
  std::ifstream in(whole, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), {});
  const fs::path p = dir.file("cut.db3");
  std::string expect;
  SUBCASE("cut after two thirds") {
    test::writer_detail::write_file(p, bytes.substr(0, bytes.size() * 2 / 3));
    expect = "bytes: it was cut short, by a recording stopped before rosbag2 closed it or by an "
             "incomplete copy, and SQLite cannot read it)";
  }
  SUBCASE("cut inside the SQLite header") {
    test::writer_detail::write_file(p, bytes.substr(0, 50));
    expect = "the file is 50 bytes, shorter than the 100-byte SQLite header: it was cut short";
  }
  std::string msg;
  try {
    auto bag = detail::open_rosbag2_sqlite(p.string());
    msg = drain(*bag, "/imu/data");
  } catch (const Error& e) {
    msg = e.what();
  }
  INFO(msg);
  CHECK(msg.find(expect) != std::string::npos);
  // The whole file reads without the note (every other case here reads whole files too).
  auto bag = detail::open_rosbag2_sqlite(whole.string());
  CHECK(read_all(*bag, "/imu/data").size() == 2000);
}

TEST_CASE("db3 files that are not rosbag2 SQLite are refused clearly") {
  TempDir dir;
  SUBCASE("not SQLite") {
    const fs::path p = dir.file("text.db3");
    std::ofstream(p) << "t,gx,gy,gz\n0,1,2,3\n";
    CHECK(error_of([&] {
            detail::open_rosbag2_sqlite(p.string());
          }).find("not an SQLite database: byte offset 0") != std::string::npos);
  }
  SUBCASE("SQLite without the rosbag2 tables") {
    const fs::path p = dir.file("other.db3");
    sql(p, "CREATE TABLE t(x)");
    CHECK(error_of([&] {
            detail::open_rosbag2_sqlite(p.string());
          }).find("not a rosbag2 recording") != std::string::npos);
  }
  SUBCASE("a whole-file zstd (compression_mode FILE) .db3.zstd") {
    const fs::path plain = dir.file("plain.db3");
    test::write_db3(plain, two_topics(20, 37));
    std::ifstream in(plain, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    const fs::path p = dir.file("imu.db3.zstd");
    test::writer_detail::write_file(p, test::writer_detail::compress(bytes, "zstd"));
    const std::string msg = error_of([&] { detail::open_rosbag2_sqlite(p.string()); });
    CHECK(msg.find("imu.db3.zstd") != std::string::npos);
    CHECK(msg.find("decompress it first") != std::string::npos);
  }
}

TEST_CASE("db3 paths that look like SQLite URIs are read as plain file names") {
  TempDir dir;
  const auto topics = two_topics(30, 38);
  // '?', '#' and '%' would be URI syntax; "file:" a URI scheme.
  const fs::path p = dir.file("file:odd?mode=rwc#x%41.db3");
  test::write_db3(p, topics);
  auto bag = detail::open_rosbag2_sqlite(p.string());
  check_same(read_all(*bag, "/imu/data"), topics[0].values);
  CHECK_FALSE(fs::exists(dir.file("file:odd")));  // nothing created by a misread URI
}

TEST_CASE("rosbag2 folders of two files, sqlite3 and mcap, read in order") {
  TempDir dir;
  const auto topics = two_topics(301, 39, CdrKind::xcdr2_le);
  for (const std::string storage : {"sqlite3", "mcap"}) {
    for (const std::string mode : {"", "MESSAGE"}) {
      if (storage == "mcap" && !mode.empty()) continue;  // MCAP compresses chunks instead
      CAPTURE(storage);
      CAPTURE(mode);
      const fs::path folder = dir.file("rec_" + storage + mode);
      test::write_rosbag2_folder(folder, storage, topics, 2, mode);
      auto bag = detail::open_rosbag2_folder(folder.string());
      const auto list = bag->topics(false);
      REQUIRE(list.size() == 2);
      CHECK(list[0].name == "/imu/data");
      CHECK(list[0].messages == 301);  // from metadata.yaml
      CHECK(list[1].messages == 75);
      check_same(read_all(*bag, "/imu/data"), topics[0].values);
      CHECK(bag->bytes_read() <= bag->total_bytes());
      CHECK(bag->bytes_read() > 0);
    }
  }
}

TEST_CASE(
    "rosbag2 folders: old-style file paths resolve, refusals name metadata.yaml or the file") {
  TempDir dir;
  const auto topics = two_topics(40, 40);
  const fs::path folder = dir.file("rec");
  SUBCASE("file compression") {
    test::write_rosbag2_folder(folder, "sqlite3", topics, 2, "FILE");
    const std::string msg = error_of([&] { detail::open_rosbag2_folder(folder.string()); });
    CHECK(msg.find("metadata.yaml") != std::string::npos);
    CHECK(msg.find("compression_mode FILE") != std::string::npos);
  }
  SUBCASE("no metadata.yaml") {
    fs::create_directories(folder);
    const std::string msg = error_of([&] { detail::open_rosbag2_folder(folder.string()); });
    CHECK(msg.find("no metadata.yaml") != std::string::npos);
  }
  SUBCASE("a listed file is missing") {
    test::write_rosbag2_folder(folder, "mcap", topics, 2);
    fs::remove(folder / "rec_1.mcap");
    const std::string msg = error_of([&] { detail::open_rosbag2_folder(folder.string()); });
    CHECK(msg.find("metadata.yaml:") != std::string::npos);  // with line and column
    CHECK(msg.find("rec_1.mcap, which is not a file") != std::string::npos);
  }
  SUBCASE("unknown storage") {
    test::write_rosbag2_folder(folder, "sqlite3", topics, 1);
    std::ifstream in(folder / "metadata.yaml");
    std::string y((std::istreambuf_iterator<char>(in)), {});
    y.replace(y.find("sqlite3"), 7, "hdf5");
    test::writer_detail::write_file(folder / "metadata.yaml", y);
    CHECK(error_of([&] {
            detail::open_rosbag2_folder(folder.string());
          }).find("storage_identifier \"hdf5\"") != std::string::npos);
  }
  SUBCASE("file names with the folder's name in front (rosbag2 before metadata version 4)") {
    test::write_rosbag2_folder(folder, "sqlite3", topics, 2);
    std::ifstream in(folder / "metadata.yaml");
    std::string y((std::istreambuf_iterator<char>(in)), {});
    for (const std::string name : {"    - rec_0.db3", "    - rec_1.db3"}) {
      y.replace(y.find(name), name.size(), "    - rec/" + name.substr(6));
    }
    test::writer_detail::write_file(folder / "metadata.yaml", y);
    auto bag = detail::open_rosbag2_folder(folder.string());
    check_same(read_all(*bag, "/imu/data"), topics[0].values);
  }
  SUBCASE("wrong type on the topic") {
    test::write_rosbag2_folder(folder, "sqlite3", topics, 2);
    auto bag = detail::open_rosbag2_folder(folder.string());
    CHECK(drain(*bag, "/tf").find("type tf2_msgs/msg/TFMessage") != std::string::npos);
  }
}
