// Tests of the streaming log reader (lib/src/log_reader.cpp, text_log.cpp, binary_log.cpp,
// byte_source.cpp, log_common.cpp).
//
// Exact comparisons of doubles are deliberate here: the reader must return the double nearest
// to each decimal in the file (std::from_chars is correctly rounded, as is the compiler's
// conversion of the same literal), and binary samples must come back bit for bit.
#include <fcntl.h>
#include <unistd.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "sigmatau/error.hpp"
#include "sigmatau/log_reader.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace sigmatau;
using sigmatau::test::rel;

namespace {

std::string logs(const std::string& name) {
  return (test::test_data_dir() / "logs" / name).string();
}
std::string bad(const std::string& name) { return (test::test_data_dir() / "bad" / name).string(); }

/// A file in the temp directory, removed when the test ends.
class TempFile {
 public:
  TempFile(const std::string& content, const std::string& suffix) {
    static int counter = 0;
    path_ = (fs::temp_directory_path() / ("sigmatau_test_log_reader_" + std::to_string(::getpid()) +
                                          "_" + std::to_string(counter++) + suffix))
                .string();
    std::ofstream out(path_, std::ios::binary);
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
    REQUIRE(out.good());
  }
  TempFile(const std::vector<unsigned char>& bytes, const std::string& suffix)
      : TempFile(std::string(bytes.begin(), bytes.end()), suffix) {}
  ~TempFile() { std::remove(path_.c_str()); }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

LogOptions text_options(const std::string& path) {
  LogOptions o;
  o.path = path;
  return o;
}

LogOptions binary_options(const std::string& path, BinaryFormat format, int channels,
                          bool big_endian) {
  LogOptions o;
  o.path = path;
  o.binary = format;
  o.binary_channels = channels;
  o.big_endian = big_endian;
  return o;
}

/// Reads through LogReader with `max_rows` per block (read_log always uses the default).
Log read_in_blocks(const LogOptions& options, std::int64_t max_rows) {
  LogReader reader(options);
  Log log;
  log.channel_names = reader.channel_names();
  log.channels.resize(log.channel_names.size());
  SampleBlock block;
  while (reader.read_block(block, max_rows)) {
    CHECK(block.rows() <= max_rows);
    for (std::size_t c = 0; c < block.values.size(); ++c) {
      log.channels[c].insert(log.channels[c].end(), block.values[c].begin(), block.values[c].end());
    }
    log.t_s.insert(log.t_s.end(), block.t_s.begin(), block.t_s.end());
  }
  log.timing = reader.timing();
  return log;
}

void check_same(const Log& a, const Log& b) {
  CHECK(a.channel_names == b.channel_names);
  CHECK(a.channels == b.channels);
  CHECK(a.t_s == b.t_s);
  CHECK(a.timing.samples == b.timing.samples);
  CHECK(a.timing.rate_hz == b.timing.rate_hz);
  CHECK(a.timing.jitter_s == b.timing.jitter_s);
  CHECK(a.timing.gap_count == b.timing.gap_count);
}

// The gyro columns of header.csv (and of noheader.tsv and space.txt), as written there.
const std::vector<double> kGyroX = {1.5, 1.75, 2.0, 0.125};
const std::vector<double> kGyroY = {-2.25, -2.5, -2.75, -3};
const std::vector<double> kGyroZ = {3e-3, 4e-3, -5e-3, 6e-3};
const std::vector<double> kTime = {0.00, 0.01, 0.02, 0.03};

/// Points fd 0 at a file for the lifetime of the object.
class StdinFrom {
 public:
  explicit StdinFrom(const std::string& path) : saved_(::dup(STDIN_FILENO)) {
    const int fd = ::open(path.c_str(), O_RDONLY);
    REQUIRE(fd >= 0);
    REQUIRE(::dup2(fd, STDIN_FILENO) == STDIN_FILENO);
    ::close(fd);
  }
  ~StdinFrom() {
    ::dup2(saved_, STDIN_FILENO);
    ::close(saved_);
  }
  StdinFrom(const StdinFrom&) = delete;
  StdinFrom& operator=(const StdinFrom&) = delete;

 private:
  int saved_;
};

std::string shortest(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

}  // namespace

TEST_CASE("a CSV with header, comments, blank lines, spaces, quotes and '+' reads every value") {
  const Log log = read_log(text_options(logs("header.csv")));
  // t is numeric and no time column was named, so it is a channel; "status" is text: left out.
  CHECK(log.channel_names == std::vector<std::string>{"t", "gyro_x", "gyro_y", "gyro_z"});
  REQUIRE(log.channels.size() == 4);
  CHECK(log.channels[0] == kTime);
  CHECK(log.channels[1] == kGyroX);
  CHECK(log.channels[2] == kGyroY);
  CHECK(log.channels[3] == kGyroZ);
  CHECK(log.t_s.empty());
  CHECK_FALSE(log.timing.has_time);
  CHECK(log.timing.samples == 4);
}

TEST_CASE("TSV and whitespace files without a header read the same values, named c<index>") {
  for (const char* name : {"noheader.tsv", "space.txt"}) {
    CAPTURE(name);
    const Log log = read_log(text_options(logs(name)));
    CHECK(log.channel_names == std::vector<std::string>{"c0", "c1", "c2"});
    REQUIRE(log.channels.size() == 3);
    CHECK(log.channels[0] == kGyroX);
    CHECK(log.channels[1] == kGyroY);
    CHECK(log.channels[2] == kGyroZ);
  }
}

TEST_CASE("CRLF line ends and gzip compression give the same log as the plain file") {
  const Log plain = read_log(text_options(logs("header.csv")));
  check_same(read_log(text_options(logs("crlf.csv"))), plain);
  check_same(read_log(text_options(logs("header.csv.gz"))), plain);
}

TEST_CASE("columns are chosen by name, by index or by c<index>, in the order given") {
  SUBCASE("names and indices mixed") {
    LogOptions o = text_options(logs("header.csv"));
    o.columns = {"gyro_z", "1"};
    const Log log = read_log(o);
    CHECK(log.channel_names == std::vector<std::string>{"gyro_z", "gyro_x"});
    CHECK(log.channels[0] == kGyroZ);
    CHECK(log.channels[1] == kGyroX);
  }
  SUBCASE("c<index> without a header") {
    LogOptions o = text_options(logs("noheader.tsv"));
    o.columns = {"c2", "0"};
    const Log log = read_log(o);
    CHECK(log.channel_names == std::vector<std::string>{"c2", "c0"});
    CHECK(log.channels[0] == kGyroZ);
    CHECK(log.channels[1] == kGyroX);
  }
  SUBCASE("a text column asked for by name fails at its first field") {
    LogOptions o = text_options(logs("header.csv"));
    o.columns = {"status"};
    try {
      read_log(o);
      FAIL("no exception");
    } catch (const ParseError& e) {
      CHECK(e.line() == 4);
      CHECK(e.column() == 5);
      CHECK(e.message() == "expected a number, found \"ok\"");
    }
  }
  SUBCASE("ambiguous names, a column twice, the time column as a channel are errors") {
    TempFile dup("a,b,a\n1,2,3\n", ".csv");
    LogOptions o = text_options(dup.path());
    o.columns = {"a"};
    CHECK_THROWS_WITH_AS(read_log(o), doctest::Contains("is ambiguous: it names columns 0 and 2"),
                         ParseError);
    o.columns = {"b", "1"};
    CHECK_THROWS_WITH_AS(read_log(o), doctest::Contains("\"1\" is selected twice"), ParseError);
    o.columns = {"b"};
    o.time_column = "b";
    CHECK_THROWS_WITH_AS(read_log(o), doctest::Contains("is the time column"), ParseError);
  }
}

TEST_CASE("the time column is read by name or index and converted to seconds") {
  SUBCASE("by name, seconds") {
    LogOptions o = text_options(logs("header.csv"));
    o.time_column = "t";
    const Log log = read_log(o);
    CHECK(log.channel_names == std::vector<std::string>{"gyro_x", "gyro_y", "gyro_z"});
    CHECK(log.t_s == kTime);
    CHECK(log.timing.has_time);
    // Differences of decimal fractions carry one rounding each (~1e-18 s on 0.01 s).
    CHECK(log.timing.rate_hz == rel(100.0, 1e-12));
  }
  SUBCASE("by index, each unit") {
    TempFile f("t,x\n1000,1\n2000,2\n", ".csv");
    const std::map<TimeUnit, std::vector<double>> expected = {
        {TimeUnit::s, {1000, 2000}},
        {TimeUnit::ms, {1, 2}},
        {TimeUnit::us, {1e-3, 2e-3}},  // divided by 1e6: the nearest doubles to 0.001, 0.002
        {TimeUnit::ns, {1e-6, 2e-6}}};
    for (const auto& [unit, t_s] : expected) {
      LogOptions o = text_options(f.path());
      o.time_column = "0";
      o.time_unit = unit;
      const Log log = read_log(o);
      CHECK(log.t_s == t_s);
      CHECK(log.channels == std::vector<std::vector<double>>{{1, 2}});
    }
  }
}

TEST_CASE("timing report: rate from the median interval, jitter, duplicates and a known gap") {
  LogOptions o = text_options(logs("gap.csv"));
  o.time_column = "t_ms";
  o.time_unit = TimeUnit::ms;
  const Log log = read_log(o);
  const TimingReport& t = log.timing;
  // Intervals (ms, listed in the file): 10,10,11,9,10,40,10,0,10,9,11. Median 10 ms.
  CHECK(t.samples == 12);
  CHECK(t.rate_hz == rel(100.0, 1e-12));  // 1e-12: one rounding of 10/1e3
  CHECK(t.mean_interval_s == rel(0.130 / 11, 1e-12));
  // Regular intervals 10,10,11,9,10,10,10,9,11 ms: mean 10, squared deviations sum 4 ms^2,
  // sample variance 4/8 ms^2.
  CHECK(t.jitter_s == rel(std::sqrt(0.5) * 1e-3, 1e-9));  // 1e-9: rounding of ms -> s
  CHECK(t.non_increasing == 1);
  CHECK(t.gap_count == 1);
  REQUIRE(t.gaps.size() == 1);
  CHECK(t.gaps[0].row == 6);    // the stamp 90 ms is row 6 (0-based)
  CHECK(t.gaps[0].line == 10);  // 2 comment lines + header, row 0 on line 4
  CHECK(t.gaps[0].start_s == 0.05);
  CHECK(t.gaps[0].length_s == rel(0.04, 1e-12));
}

TEST_CASE("nanosecond and decimal-second epoch stamps give exact intervals") {
  SUBCASE("integer nanoseconds since 1970") {
    LogOptions o = text_options(logs("epoch_ns.csv"));
    o.time_column = "t_ns";
    o.time_unit = TimeUnit::ns;
    const Log log = read_log(o);
    // 1e7 ns / 1e9 is one correctly rounded division: exactly the double 0.01 every time.
    CHECK(log.timing.rate_hz == 100.0);
    CHECK(log.timing.mean_interval_s == 0.01);
    CHECK(log.timing.jitter_s == 0.0);
  }
  SUBCASE("decimal seconds since 1970") {
    std::string text = "t,x\n";
    for (int k = 0; k < 100; ++k) {
      char stamp[32];
      std::snprintf(stamp, sizeof stamp, "1700000000.%06d", k * 10000);
      text += std::string(stamp) + ",1\n";
    }
    TempFile f(text, ".csv");
    LogOptions o = text_options(f.path());
    o.time_column = "t";
    const Log log = read_log(o);
    // Parsed as one double, 1.7e9 s has a 2.4e-7 s step, and the jitter would be ~1e-7 s; the
    // split integer/fraction parse leaves only the rounding of the fractions (~1e-17 s).
    CHECK(log.timing.jitter_s < 1e-15);
    CHECK(log.timing.rate_hz == rel(100.0, 1e-12));
  }
}

TEST_CASE("timing over more than the 100000-interval median window: gaps counted, list capped") {
  // 1 kHz integer-ns stamps; every 100th sample from k = 1050 on is removed (1500 gaps), so
  // gaps fall both inside the median window and after it.
  constexpr int kOriginal = 160000;
  std::string text = "t_ns,x\n";
  text.reserve(4000000);
  for (int k = 0; k < kOriginal; ++k) {
    if (k >= 1050 && (k - 1050) % 100 == 0 && (k - 1050) / 100 < 1500) continue;
    text += std::to_string(std::int64_t{k} * 1000000) + "," + std::to_string(k % 7) + "\n";
  }
  TempFile f(text, ".csv");
  LogOptions o = text_options(f.path());
  o.time_column = "t_ns";
  o.time_unit = TimeUnit::ns;
  LogReader reader(o);
  SampleBlock block;
  REQUIRE(reader.read_block(block, 65536));
  // Provisional report after 65536 rows: gaps j = 0..651 end at rows 1050 + 99 j <= 65535.
  CHECK(reader.timing().gap_count == 652);
  CHECK(reader.timing().rate_hz == 1000.0);
  while (reader.read_block(block)) {
  }
  const TimingReport& t = reader.timing();
  CHECK(t.samples == kOriginal - 1500);
  CHECK(t.rate_hz == 1000.0);  // 1e6 ns / 1e9: exactly the double 1e-3
  CHECK(t.jitter_s == 0.0);    // every regular interval is that same double
  CHECK(t.non_increasing == 0);
  CHECK(t.gap_count == 1500);
  REQUIRE(t.gaps.size() == 1000);
  CHECK(t.gaps.front().row == 1050);  // original sample 1051, one removed before it
  CHECK(t.gaps.front().line == 1052);
  CHECK(t.gaps.front().start_s == 1.049);
  CHECK(t.gaps.front().length_s == 2e-3);
  CHECK(t.gaps.back().row == 99951);  // original 100951, 1000 removed before it
  CHECK(t.gaps.back().line == 99953);
  // (t_last - t_first) / (samples - 1), t_last = 159.999 s.
  CHECK(t.mean_interval_s == rel(159.999 / (kOriginal - 1500 - 1), 1e-12));
}

TEST_CASE("raw binary: every type, both byte orders, byte-exact values") {
  struct Case {
    BinaryFormat format;
    bool big_endian;
    int channels;
    std::vector<unsigned char> bytes;
    std::vector<std::vector<double>> expected;  // per channel
  };
  const std::vector<Case> cases = {
      {BinaryFormat::i16,
       false,
       2,
       {0x01, 0x00, 0xff, 0xff, 0x00, 0x80, 0xff, 0x7f},
       {{1, -32768}, {-1, 32767}}},
      {BinaryFormat::i16,
       true,
       2,
       {0x00, 0x01, 0xff, 0xfe, 0x80, 0x00, 0x7f, 0xff},
       {{1, -32768}, {-2, 32767}}},
      {BinaryFormat::i32,
       false,
       1,
       {0x78, 0x56, 0x34, 0x12, 0x00, 0x00, 0x00, 0x80},
       {{305419896, -2147483648.0}}},
      {BinaryFormat::i32,
       true,
       1,
       {0x12, 0x34, 0x56, 0x78, 0xff, 0xff, 0xff, 0xff},
       {{305419896, -1}}},
      // 0xc0490fdb is -pi rounded to float; 0x00000001 is the smallest subnormal float 2^-149.
      {BinaryFormat::f32,
       false,
       1,
       {0x00, 0x00, 0x80, 0x3f, 0xdb, 0x0f, 0x49, 0xc0},
       {{1.0, static_cast<double>(-3.14159274101257324f)}}},
      {BinaryFormat::f32,
       true,
       1,
       {0x3f, 0x80, 0x00, 0x00, 0x00, 0x00, 0x00, 0x01},
       {{1.0, std::ldexp(1.0, -149)}}},
      // 0xc00921fb54442d18 is -pi; 0x3fb999999999999a is 0.1.
      {BinaryFormat::f64,
       false,
       2,
       {0, 0, 0, 0, 0, 0, 0xf0, 0x3f, 0x18, 0x2d, 0x44, 0x54, 0xfb, 0x21, 0x09, 0xc0},
       {{1.0}, {-3.141592653589793}}},
      {BinaryFormat::f64,
       true,
       2,
       {0x40, 0x09, 0x21, 0xfb, 0x54, 0x44, 0x2d, 0x18, 0x3f, 0xb9, 0x99, 0x99, 0x99, 0x99, 0x99,
        0x9a},
       {{3.141592653589793}, {0.1}}},
  };
  for (const Case& c : cases) {
    CAPTURE(static_cast<int>(c.format));
    CAPTURE(c.big_endian);
    TempFile f(c.bytes, ".bin");
    const Log log = read_log(binary_options(f.path(), c.format, c.channels, c.big_endian));
    CHECK(log.channels == c.expected);
    CHECK(log.channel_names.size() == static_cast<std::size_t>(c.channels));
    CHECK(log.timing.samples == static_cast<std::int64_t>(c.expected[0].size()));
    CHECK_FALSE(log.timing.has_time);
  }
}

TEST_CASE("raw binary: skip_bytes header and channel selection") {
  // 3 junk header bytes, then i16 LE records (1, 2, 3) and (4, 5, 6).
  TempFile f(std::vector<unsigned char>{0xaa, 0xbb, 0xcc, 1, 0, 2, 0, 3, 0, 4, 0, 5, 0, 6, 0},
             ".bin");
  LogOptions o = binary_options(f.path(), BinaryFormat::i16, 3, false);
  o.skip_bytes = 3;
  o.columns = {"2", "c0"};
  const Log log = read_log(o);
  CHECK(log.channel_names == std::vector<std::string>{"c2", "c0"});
  CHECK(log.channels == std::vector<std::vector<double>>{{3, 6}, {1, 4}});
  SUBCASE("a header as long as the file leaves no data rows") {
    o.skip_bytes = 15;
    CHECK_THROWS_WITH_AS(read_log(o),
                         doctest::Contains("no data rows: no bytes after the 15-byte header"),
                         ParseError);
  }
}

TEST_CASE("rows split across read buffers give the same values as one read") {
  // Buffer sizes down to 1 byte put every boundary inside every kind of token: numbers, CRLF,
  // comments, gzip output, binary records.
  const std::vector<std::int64_t> sizes = {1, 2, 3, 5, 7, 11, 64, 257};
  for (const char* name : {"header.csv", "crlf.csv", "header.csv.gz", "space.txt", "gap.csv"}) {
    LogOptions o = text_options(logs(name));
    if (std::string(name) == "gap.csv") o.time_column = "t_ms";
    const Log whole = read_log(o);
    for (const auto size : sizes) {
      CAPTURE(name);
      CAPTURE(size);
      o.read_buffer_bytes = size;
      check_same(read_log(o), whole);
      check_same(read_in_blocks(o, 1), whole);  // one row per block as well
    }
  }
  std::vector<unsigned char> bytes;
  for (int i = 0; i < 150; ++i) {
    const double v = 0.5 * i - 7;
    unsigned char b[8];
    std::memcpy(b, &v, 8);
    bytes.insert(bytes.end(), b, b + 8);
  }
  TempFile f(bytes, ".f64");
  LogOptions o = binary_options(f.path(), BinaryFormat::f64, 3, false);
  const Log whole = read_log(o);
  CHECK(whole.channels[1][49] == 0.5 * 148 - 7);
  for (const std::int64_t size : {1, 5, 24, 25, 1000}) {
    CAPTURE(size);
    o.read_buffer_bytes = size;
    check_same(read_log(o), whole);
    check_same(read_in_blocks(o, 7), whole);
  }
}

TEST_CASE("a file larger than the default 4 MiB buffer reads back the values written") {
  std::mt19937_64 rng(20240611);
  std::uniform_real_distribution<double> uniform(-10.0, 10.0);
  constexpr int kRows = 90000;  // ~6 MB of text
  std::vector<std::vector<double>> truth(3, std::vector<double>(kRows));
  std::string text = "t,a,b,c\n";
  text.reserve(7000000);
  for (int r = 0; r < kRows; ++r) {
    text += std::to_string(r);
    for (int c = 0; c < 3; ++c) {
      truth[c][r] = uniform(rng) * std::pow(10.0, c * 3 - 4);
      text += "," + shortest(truth[c][r]);  // shortest round-trip form: reads back exactly
    }
    text += r % 3 == 0 ? "\r\n" : "\n";
  }
  REQUIRE(text.size() > (std::size_t{4} << 20));
  TempFile f(text, ".csv");
  LogOptions o = text_options(f.path());
  o.time_column = "t";
  LogReader reader(o);
  CHECK(reader.total_bytes() == static_cast<std::int64_t>(text.size()));
  Log log;
  log.channels.resize(3);
  SampleBlock block;
  while (reader.read_block(block)) {
    for (int c = 0; c < 3; ++c) {
      log.channels[c].insert(log.channels[c].end(), block.values[c].begin(), block.values[c].end());
    }
  }
  CHECK(reader.bytes_read() == static_cast<std::int64_t>(text.size()));
  CHECK(log.channels == truth);
  CHECK(reader.timing().rate_hz == 1.0);
}

TEST_CASE("\"-\" reads stdin, plain or gzip, and names it <stdin> in messages") {
  const Log plain = read_log(text_options(logs("header.csv")));
  {
    StdinFrom in(logs("header.csv.gz"));
    check_same(read_log(text_options("-")), plain);
  }
  {
    StdinFrom in(bad("nan.csv"));
    CHECK_THROWS_WITH_AS(read_log(text_options("-")),
                         doctest::Contains("<stdin>:3:3: non-finite value"), ParseError);
  }
}

TEST_CASE("small text cases: BOM, last line without newline, one named column, trailing blanks") {
  SUBCASE("UTF-8 byte-order mark") {
    TempFile f(
        "\xEF\xBB\xBF"
        "a,b\n1,2\n",
        ".csv");
    CHECK(read_log(text_options(f.path())).channel_names == std::vector<std::string>{"a", "b"});
  }
  SUBCASE("no newline at the end") {
    TempFile f("1,2\n3,4", ".csv");
    CHECK(read_log(text_options(f.path())).channels ==
          std::vector<std::vector<double>>{{1, 3}, {2, 4}});
  }
  SUBCASE("a one-column file whose header holds spaces") {
    TempFile f("gyro x [deg/s]\n0.5\n-0.25\n", ".txt");
    const Log log = read_log(text_options(f.path()));
    CHECK(log.channel_names == std::vector<std::string>{"gyro x [deg/s]"});
    CHECK(log.channels == std::vector<std::vector<double>>{{0.5, -0.25}});
  }
  SUBCASE("tiny and huge exponents") {
    TempFile f("x\n1e-310\n-1.7976931348623157e308\n", ".csv");
    const Log log = read_log(text_options(f.path()));
    CHECK(log.channels[0] == std::vector<double>{1e-310, -1.7976931348623157e308});
  }
}

TEST_CASE("NonFinitePolicy::skip_row drops the row and counts it") {
  LogOptions o = text_options(bad("nan.csv"));
  o.nonfinite = NonFinitePolicy::skip_row;
  const Log log = read_log(o);
  CHECK(log.channels == std::vector<std::vector<double>>{{0}, {1}, {2}});
  CHECK(log.timing.rows_skipped_nonfinite == 1);
  CHECK(log.timing.samples == 1);

  LogOptions b = binary_options(bad("nan.f64"), BinaryFormat::f64, 2, false);
  b.nonfinite = NonFinitePolicy::skip_row;
  const Log blog = read_log(b);
  CHECK(blog.channels == std::vector<std::vector<double>>{{1}, {2}});
  CHECK(blog.timing.rows_skipped_nonfinite == 1);

  TempFile all_nan("x\nnan\ninf\n", ".csv");
  LogOptions a = text_options(all_nan.path());
  a.nonfinite = NonFinitePolicy::skip_row;
  CHECK_THROWS_WITH_AS(read_log(a), doctest::Contains("no samples"), Error);
}

TEST_CASE("read_block returns false with an empty block at the end, and stays there") {
  LogReader reader(text_options(logs("header.csv")));
  SampleBlock block;
  CHECK(reader.read_block(block, 3));
  CHECK(block.rows() == 3);
  CHECK(reader.read_block(block, 3));
  CHECK(block.rows() == 1);
  CHECK_FALSE(reader.read_block(block, 3));
  CHECK(block.rows() == 0);
  CHECK_FALSE(reader.read_block(block, 3));
  CHECK(reader.bytes_read() == reader.total_bytes());
  CHECK(reader.total_bytes() == static_cast<std::int64_t>(fs::file_size(logs("header.csv"))));
  CHECK_THROWS_AS(reader.read_block(block, 0), Error);
}

TEST_CASE("resolve_rate_hz: the given rate, else the measured one, else a clear error") {
  TimingReport none;
  CHECK(resolve_rate_hz(200.0, none, "x.csv") == 200.0);
  CHECK_THROWS_WITH_AS(resolve_rate_hz(std::nullopt, none, "x.csv"),
                       doctest::Contains("no --rate and no time column"), Error);
  CHECK_THROWS_AS(resolve_rate_hz(0.0, none, "x.csv"), Error);
  CHECK_THROWS_AS(resolve_rate_hz(std::nan(""), none, "x.csv"), Error);
  TimingReport timed;
  timed.has_time = true;
  timed.rate_hz = 100;
  CHECK(resolve_rate_hz(std::nullopt, timed, "x.csv") == 100.0);
  timed.rate_hz = 0;  // e.g. a single time stamp
  CHECK_THROWS_WITH_AS(resolve_rate_hz(std::nullopt, timed, "x.csv"),
                       doctest::Contains("cannot measure the sample rate"), Error);
}

TEST_CASE("parse_time_unit and parse_binary_format accept their words only") {
  CHECK(parse_time_unit("us") == TimeUnit::us);
  CHECK(parse_binary_format("f32") == BinaryFormat::f32);
  CHECK_THROWS_WITH_AS(parse_time_unit("sec"), doctest::Contains("unknown time unit \"sec\""),
                       Error);
  CHECK_THROWS_WITH_AS(parse_binary_format("u8"), doctest::Contains("unknown binary format"),
                       Error);
}

TEST_CASE("value_bytes and is_gzip_file give the sizes and the magic the readers use") {
  CHECK(value_bytes(BinaryFormat::i16) == 2);
  CHECK(value_bytes(BinaryFormat::i32) == 4);
  CHECK(value_bytes(BinaryFormat::f32) == 4);
  CHECK(value_bytes(BinaryFormat::f64) == 8);
  CHECK_THROWS_AS(value_bytes(BinaryFormat::none), Error);
  CHECK(is_gzip_file(logs("header.csv.gz")));
  CHECK_FALSE(is_gzip_file(logs("header.csv")));
  CHECK_FALSE(is_gzip_file(logs("no_such_file.csv")));
  TempFile one_byte(std::string(1, '\x1f'), ".gz");
  CHECK_FALSE(is_gzip_file(one_byte.path()));
}

TEST_CASE("the rate is the median of the first kRateMedianIntervals intervals only") {
  // kRateMedianIntervals intervals of 1 ms, then more of 2 ms than of 1 ms: the median of the
  // whole log would be 2 ms, the report keeps the first window's 1 ms.
  std::string text = "t_ns,x\n";
  std::int64_t t_ns = 0;
  for (std::int64_t k = 0; k <= 3 * kRateMedianIntervals; ++k) {
    text += std::to_string(t_ns) + ",0\n";
    t_ns += k < kRateMedianIntervals ? 1000000 : 2000000;
  }
  TempFile f(text, ".csv");
  LogOptions o = text_options(f.path());
  o.time_column = "t_ns";
  o.time_unit = TimeUnit::ns;
  LogReader reader(o);
  SampleBlock block;
  while (reader.read_block(block)) {
  }
  CHECK(reader.timing().rate_hz == 1000.0);  // 1e6 ns / 1e9: exactly the double 1e-3
}

TEST_CASE("a ParseError prints FILE:LINE:COLUMN: message") {
  try {
    read_log(text_options(bad("non_numeric.csv")));
    FAIL("no exception");
  } catch (const ParseError& e) {
    CHECK(std::string(e.what()) ==
          bad("non_numeric.csv") + ":3:2: expected a number, found \"abc\"");
  }
}

TEST_CASE("every file of the bad-input catalogue fails with its line, column and message") {
  const fs::path dir = test::test_data_dir() / "bad";
  std::ifstream readme(dir / "README.md");
  REQUIRE(readme.good());
  std::set<std::string> listed;
  std::string row;
  bool in_table = false;
  while (std::getline(readme, row)) {
    if (row.rfind("|---", 0) == 0) {
      in_table = true;
      continue;
    }
    if (!in_table || row.rfind("| ", 0) != 0) continue;
    std::vector<std::string> cells;
    std::stringstream cells_in(row.substr(1));
    for (std::string cell; std::getline(cells_in, cell, '|');) {
      const auto b = cell.find_first_not_of(' ');
      const auto e = cell.find_last_not_of(' ');
      cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
    }
    REQUIRE(cells.size() == 5);
    const std::string& file = cells[0];
    const std::int64_t line = std::stoll(cells[1]);
    const std::int64_t column = std::stoll(cells[2]);
    const std::string& fragment = cells[3];
    CAPTURE(file);
    listed.insert(file);
    LogOptions o = text_options((dir / file).string());
    std::stringstream flags(cells[4]);
    for (std::string flag; flags >> flag;) {
      std::string value;
      if (flag == "--big-endian") {
        o.big_endian = true;
        continue;
      }
      REQUIRE(static_cast<bool>(flags >> value));
      if (flag == "--columns")
        o.columns = {value};
      else if (flag == "--time-column")
        o.time_column = value;
      else if (flag == "--binary")
        o.binary = parse_binary_format(value);
      else if (flag == "--channels")
        o.binary_channels = std::stoi(value);
      else if (flag == "--skip-bytes")
        o.skip_bytes = std::stoll(value);
      else if (flag == "--gaps")
        o.gaps = parse_gap_policy(value);
      else if (flag == "--nonfinite")
        o.nonfinite = parse_nonfinite_policy(value);
      else if (flag == "--time-unit")
        o.time_unit = parse_time_unit(value);
      else
        FAIL("unknown flag in the table: " << flag);
    }
    try {
      read_log(o);
      FAIL("no exception");
    } catch (const ParseError& e) {
      INFO("message: " << e.message());
      CHECK(e.line() == line);
      CHECK(e.column() == column);
      CHECK(e.message().find(fragment) != std::string::npos);
      CHECK(e.file() == (dir / file).string());
    } catch (const Error& e) {
      CHECK(line == 0);
      CHECK(column == 0);
      INFO("message: " << e.what());
      CHECK(std::string(e.what()).find(fragment) != std::string::npos);
    }
  }
  CHECK(listed.size() >= 30);
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    CAPTURE(name);
    if (name != "README.md") CHECK(listed.count(name) == 1);
  }
}

// ---- Clock files, time columns found by name, and columns never dropped silently (issue 28) --

namespace {

/// `rows` rows "t,<a>,<b>" at 100 Hz with values that are plain numbers, except `first_a` as
/// the first row's <a> field.
std::string two_channel_csv(const std::string& header, const std::string& first_a, int rows,
                            char delimiter = ',') {
  std::string text = header + "\n";
  for (int i = 0; i < rows; ++i) {
    char line[96];
    std::snprintf(line, sizeof line, "%.2f%c%s%c%.3f\n", i * 0.01, delimiter,
                  i == 0 ? first_a.c_str() : std::to_string(0.5 + 0.001 * i).c_str(), delimiter,
                  0.25 + 0.002 * i);
    text += line;
  }
  return text;
}

}  // namespace

TEST_CASE("a preamble of Key: value lines is skipped; a Stable32 file's Type and Tau are read") {
  SUBCASE("Stable32's ACF output: File:, Date:, Points: lines before the data") {
    // Used to be ":2:3: expected 2 fields, found 3" ("File: AUTO.DAT" taken as the header).
    TempFile f("File: AUTO.DAT\nDate: 01/01/21 15:34:21\nPoints: 3\n0 9.99e-01\n1 7.1e-01\n"
               "2 5.0e-01\n",
               ".dat");
    const Log log = read_log(text_options(f.path()));
    CHECK(log.channel_names == std::vector<std::string>{"c0", "c1"});
    REQUIRE(log.channels[1].size() == 3);
    CHECK(log.channels[1][2] == 5.0e-01);
    CHECK(log.timing.header.declared_type.empty());
  }
  SUBCASE("a Stable32 phase file: # Type, # Tau and # Header End") {
    TempFile f("#Type: Phase\n#Points: 3\n#Tau: 2.500000e+00\n#Tag Scale: 8.640000e+04\n"
               "# Header End\n0.0\n8.5e-02\n-2.2e-01\n",
               ".dat");
    const Log log = read_log(text_options(f.path()));
    CHECK(log.timing.header.declared_type == "phase");
    CHECK(log.timing.header.declared_tau_s == 2.5);
    CHECK(log.channel_names == std::vector<std::string>{"c0"});
    CHECK(log.timing.header.time_tag_column.empty());
  }
  SUBCASE("the same declarations without '#', and Type: Freq") {
    TempFile f("Type: Freq\nTau: 1.0e+01\n1e-12\n2e-12\n", ".dat");
    const Log log = read_log(text_options(f.path()));
    CHECK(log.timing.header.declared_type == "frequency");
    CHECK(log.timing.header.declared_tau_s == 10.0);
    CHECK(log.channels[0].size() == 2);
  }
  SUBCASE("a Stable32 file of time tags and values: the tags are left out, as Stable32 does") {
    TempFile f("# Type: Freq\n# Points: 3\n# Tau: 2.500000e+00\n# Header End\n"
               "3.661957841370000e+09 8.768489e-17\n3.661957842680000e+09 9.874540e-17\n"
               "3.661957849260000e+09 7.519143e-17\n",
               ".txt");
    const Log log = read_log(text_options(f.path()));
    CHECK(log.channel_names == std::vector<std::string>{"c1"});
    CHECK(log.timing.header.time_tag_column == "c0");
    REQUIRE(log.channels.size() == 1);
    CHECK(log.channels[0][1] == 9.874540e-17);
    // Columns named by the caller are taken as asked.
    LogOptions both = text_options(f.path());
    both.columns = {"0", "1"};
    CHECK(read_log(both).channels.size() == 2);
  }
  SUBCASE("the reference data's Stable32 files") {
    if (!test::has_reference_data("allantoolkit/Sr87/freq/freq_data.txt")) return;
    const auto dir = test::reference_data_dir() / "allantoolkit";
    const Log freq = read_log(text_options((dir / "Sr87/freq/freq_data.txt").string()));
    CHECK(freq.timing.header.declared_type == "frequency");
    CHECK(freq.timing.header.declared_tau_s == 2.5);
    CHECK(freq.channels.size() == 1);
    CHECK(freq.channels[0].size() == 1252);
    const Log acf = read_log(text_options((dir / "Sr87/AUTO.DAT").string()));
    CHECK(acf.channels[1].size() == 626);
    const Log phase = read_log(text_options((dir / "phasedat_stable32_1.61/PHASE.DAT").string()));
    CHECK(phase.timing.header.declared_type == "phase");
    CHECK(phase.channels[0].size() == 1001);
  }
}

TEST_CASE("a time column is found by its name, its suffix giving the unit") {
  const auto found = [](const std::string& content, const LogOptions& base = {}) {
    TempFile f(content, ".csv");
    LogOptions o = base;
    o.path = f.path();
    o.find_time_column = true;
    return read_log(o);
  };
  SUBCASE("t, Time, TIMESTAMP: seconds") {
    for (const char* name : {"t", "Time", "TIMESTAMP", "time (s)", "t_sec"}) {
      INFO(name);
      const Log log = found(std::string(name) + ",gx\n0,1\n0.01,2\n0.02,3\n");
      CHECK(log.timing.has_time);
      CHECK(log.timing.rate_hz == rel(100, 1e-9));
      CHECK(log.channel_names == std::vector<std::string>{"gx"});
      CHECK(log.timing.header.time_column_found == name);
    }
  }
  SUBCASE("unit suffixes: _ms, _us, _ns, [ms], _min, _h, _d, _mjd") {
    const std::pair<const char*, std::string> cases[] = {
        {"t_ms", "0,1\n10,2\n20,3\n"},
        {"time_us", "0,1\n10000,2\n20000,3\n"},
        {"Timestamp_ns", "1700000000000000000,1\n1700000000010000000,2\n1700000000020000000,3\n"},
        {"time [ms]", "0,1\n10,2\n20,3\n"},
    };
    for (const auto& [name, rows] : cases) {
      INFO(name);
      const Log log = found(std::string(name) + ",gx\n" + rows);
      CHECK(log.timing.rate_hz == rel(100, 1e-9));
      CHECK(log.timing.header.time_unit_from_name);
    }
    // Minutes, hours and days (an MJD column): 0.5 min, 0.25 h, 0.5 d between stamps.
    CHECK(found("t_min,gx\n0,1\n0.5,2\n1.0,3\n").timing.mean_interval_s == rel(30, 1e-12));
    CHECK(found("t_h,gx\n0,1\n0.25,2\n0.5,3\n").timing.mean_interval_s == rel(900, 1e-12));
    const Log mjd = found("t_mjd,y\n60000.0,1e-12\n60000.5,2e-12\n60001.0,3e-12\n");
    CHECK(mjd.timing.mean_interval_s == rel(43200, 1e-12));
    CHECK(mjd.timing.header.time_unit == TimeUnit::d);
  }
  SUBCASE("an explicit unit wins over the suffix") {
    LogOptions o;
    o.time_unit = TimeUnit::s;
    const Log log = found("t_ms,gx\n0,1\n10,2\n20,3\n", o);
    CHECK(log.timing.rate_hz == rel(0.1, 1e-9));
    CHECK_FALSE(log.timing.header.time_unit_from_name);
  }
  SUBCASE("the suffix also sets the unit of a column named explicitly") {
    TempFile f("t_ns,gx\n0,1\n10000000,2\n20000000,3\n", ".csv");
    LogOptions o = text_options(f.path());
    o.time_column = "t_ns";
    CHECK(read_log(o).timing.rate_hz == rel(100, 1e-9));
  }
  SUBCASE("not a time column: other names, a column asked for, no header, not enabled") {
    for (const char* name : {"t_sensor", "time_offset", "tx", "dt", "stamp"}) {
      INFO(name);
      const Log log = found(std::string(name) + ",gx\n0,1\n0.01,2\n0.02,3\n");
      CHECK_FALSE(log.timing.has_time);
      CHECK(log.channels.size() == 2);
    }
    LogOptions asked;
    asked.columns = {"t", "gx"};
    CHECK_FALSE(found("t,gx\n0,1\n0.01,2\n", asked).timing.has_time);
    CHECK_FALSE(found("0,1\n0.01,2\n").timing.has_time);
    TempFile f("t,gx\n0,1\n0.01,2\n", ".csv");
    CHECK_FALSE(read_log(text_options(f.path())).timing.has_time);  // the library default
  }
  SUBCASE("a column named T whose values go up and down is a channel (a temperature)") {
    const Log log = found("T,gx\n25.1,1\n25.0,2\n25.1,3\n25.1,4\n25.0,5\n25.2,6\n");
    CHECK_FALSE(log.timing.has_time);
    CHECK(log.channel_names == std::vector<std::string>{"T", "gx"});
    CHECK(log.timing.header.time_column_not_increasing == "T");
  }
  SUBCASE("t beside a temperature named T: t is the time column") {
    const Log log = found("t,T,gx\n0,25.1,1\n0.01,25.0,2\n0.02,25.1,3\n0.03,25.1,4\n");
    CHECK(log.timing.header.time_column_found == "t");
    CHECK(log.timing.header.time_column_not_increasing == "T");
    CHECK(log.channel_names == std::vector<std::string>{"T", "gx"});
    CHECK(log.timing.rate_hz == rel(100, 1e-9));
  }
  SUBCASE("two increasing time columns by name are an error naming both") {
    TempFile f("t,timestamp_ns,gx\n0,0,1\n0.01,10000000,2\n", ".csv");
    LogOptions o = text_options(f.path());
    o.find_time_column = true;
    CHECK_THROWS_WITH_AS(read_log(o),
                         doctest::Contains(":1: columns \"t\" and \"timestamp_ns\" are both named"),
                         ParseError);
  }
}

TEST_CASE("parse_time_unit reads minutes, hours and days") {
  CHECK(parse_time_unit("min") == TimeUnit::min);
  CHECK(parse_time_unit("h") == TimeUnit::h);
  CHECK(parse_time_unit("d") == TimeUnit::d);
  CHECK_THROWS_WITH_AS(parse_time_unit("day"), doctest::Contains("expected s, ms, us, ns, min, h or d"),
                       Error);
  // A column named explicitly, in days.
  TempFile f("mjd,y\n60000,1e-12\n60000.25,2e-12\n60000.5,3e-12\n", ".csv");
  LogOptions o = text_options(f.path());
  o.time_column = "mjd";
  o.time_unit = TimeUnit::d;
  CHECK(read_log(o).timing.mean_interval_s == rel(21600, 1e-12));
}

TEST_CASE("a data column is never dropped silently") {
  SUBCASE("a typo in the first data row of a numeric column: the row is an error") {
    // Used to leave gx out of the channels without a word (its 2999 good rows lost).
    TempFile f(two_channel_csv("t,gx,gy", "x1.288185", 3000), ".csv");
    LogOptions o = text_options(f.path());
    o.time_column = "t";
    {
      LogReader reader(o);
      CHECK(reader.channel_names() == std::vector<std::string>{"gx", "gy"});
    }
    CHECK_THROWS_WITH_AS(read_log(o), doctest::Contains(":2:2: expected a number, found \"x1.288185\""),
                         ParseError);
    // Under NonFinitePolicy::skip_row the row is dropped and counted, like a NaN.
    o.nonfinite = NonFinitePolicy::skip_row;
    const Log log = read_log(o);
    CHECK(log.channels[0].size() == 2999);
    CHECK(log.timing.rows_skipped_nonfinite == 1);
  }
  SUBCASE("the same with a read buffer of 64 bytes: one more read is looked at") {
    TempFile f(two_channel_csv("t,gx,gy", "x1.288185", 200), ".csv");
    LogOptions o = text_options(f.path());
    o.time_column = "t";
    o.read_buffer_bytes = 64;
    CHECK_THROWS_WITH_AS(read_log(o), doctest::Contains(":2:2: expected a number"), ParseError);
  }
  SUBCASE("a TSV column written with decimal commas") {
    std::string text = "t\tgx\tgy\n";
    for (int i = 0; i < 100; ++i) {
      text += std::to_string(i) + "\t" + std::to_string(i % 7) + ",5\t" + std::to_string(i % 5) +
              ".25\n";
    }
    TempFile f(text, ".tsv");
    CHECK_THROWS_WITH_AS(read_log(text_options(f.path())),
                         doctest::Contains(":2:2: expected a number, found \"0,5\" in column \"gx\": "
                                           "a decimal comma"),
                         ParseError);
  }
  SUBCASE("a decimal comma further down a numeric column") {
    TempFile f("t\tgx\n0\t1.5\n1\t1.25\n2\t1,75\n", ".tsv");
    CHECK_THROWS_WITH_AS(read_log(text_options(f.path())),
                         doctest::Contains(":4:2: expected a number, found \"1,75\" in column \"gx\""),
                         ParseError);
  }
  SUBCASE("a text column is left out and listed") {
    std::string text = "t,gx,status\n";
    for (int i = 0; i < 50; ++i) text += std::to_string(i) + ",1.5," + (i == 7 ? "3" : "OK") + "\n";
    TempFile f(text, ".csv");
    const Log log = read_log(text_options(f.path()));
    CHECK(log.channel_names == std::vector<std::string>{"t", "gx"});
    REQUIRE(log.timing.header.text_columns.size() == 1);
    const TextColumn& t = log.timing.header.text_columns.front();
    CHECK(t.column == 2);
    CHECK(t.name == "status");
    CHECK(t.first_field == "OK");
    CHECK(t.line == 2);
  }
}
