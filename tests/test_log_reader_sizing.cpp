// LogReader::rows_left_hint and read_log's sizing: the arrays of a log in memory are sized once
// from the input's size instead of growing by reallocation (issue 25).
#include <doctest/doctest.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "sigmatau/log_reader.hpp"
#include "temp_dir.hpp"

using namespace sigmatau;

TEST_CASE("a raw binary file tells its rows before it is read, and read_log sizes its arrays once") {
  test::TempDir dir("sigmatau_sizing");
  const std::string path = dir.file("x.f64").string();
  constexpr std::int64_t kRows = 100000;  // more than one 65536-row block
  {
    std::ofstream out(path, std::ios::binary);
    const char header[12] = {};
    out.write(header, sizeof header);
    for (std::int64_t i = 0; i < kRows; ++i) {
      const double v[2] = {static_cast<double>(i), -static_cast<double>(i)};
      out.write(reinterpret_cast<const char*>(v), sizeof v);
    }
  }
  LogOptions options;
  options.path = path;
  options.binary = BinaryFormat::f64;
  options.binary_channels = 2;
  options.skip_bytes = 12;
  {
    LogReader reader(options);
    CHECK(reader.rows_left_hint() == kRows);
    SampleBlock block;
    REQUIRE(reader.read_block(block, 1000));
    CHECK(reader.rows_left_hint() == kRows - 1000);
  }
  const Log log = read_log(options);
  REQUIRE(log.channels.size() == 2);
  CHECK(log.channels[0].size() == static_cast<std::size_t>(kRows));
  // Sized once from the hint: the rows and one spare (room for a phase of M + 1 points), never
  // a grown capacity.
  CHECK(log.channels[0].capacity() == static_cast<std::size_t>(kRows) + 1);
  CHECK(log.channels[1][kRows - 1] == -static_cast<double>(kRows - 1));
}

TEST_CASE("a text file's rows are estimated after its first block, generously") {
  test::TempDir dir("sigmatau_sizing");
  const std::string path = dir.file("x.csv").string();
  constexpr std::int64_t kRows = 200000;
  {
    std::ofstream out(path);
    out << "a,b\n";
    for (std::int64_t i = 0; i < kRows; ++i) out << i << ',' << static_cast<double>(i % 7) * 0.5 << '\n';
  }
  LogOptions options;
  options.path = path;
  {
    LogReader reader(options);
    CHECK(reader.rows_left_hint() == -1);  // nothing read yet: nothing to tell
    SampleBlock block;
    REQUIRE(reader.read_block(block, 1000));
    // Rows lengthen from "0,0" to "199999,3": the estimate from the first rows is low, but
    // it is only a capacity; it must be positive and not absurd.
    CHECK(reader.rows_left_hint() > 0);
    CHECK(reader.rows_left_hint() < 4 * kRows);
  }
  const Log log = read_log(options);
  CHECK(log.channels[0].size() == static_cast<std::size_t>(kRows));
  CHECK(log.channels[1][kRows - 1] == 1.0);  // (kRows - 1) % 7 = 2
}
