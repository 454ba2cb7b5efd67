// Inputs the fuzzers (fuzz/, scripts/fuzz.sh) found crashing, kept in tests/data/fuzz/: each must
// now parse or fail with sigmatau::Error, never with a foreign exception.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "sigmatau/error.hpp"
#include "sigmatau/log_reader.hpp"
#include "sigmatau/spec.hpp"
#include "test_support.hpp"

using namespace sigmatau;
namespace fs = std::filesystem;

namespace {

/// "error" when `f` throws sigmatau::Error, "ok" when it returns, else the foreign exception.
template <class F>
std::string outcome(F f) {
  try {
    f();
    return "ok";
  } catch (const Error&) {
    return "error";
  } catch (const std::exception& e) {
    return std::string("foreign exception: ") + e.what();
  }
}

/// A directory under the temp directory for one test case, removed at its end.
struct Scratch {
  fs::path dir = fs::temp_directory_path() /
                 ("sigmatau_fuzz_regressions_" + std::to_string(static_cast<long>(::getpid())));
  Scratch() { fs::create_directories(dir); }
  ~Scratch() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  std::string file(const std::string& name) const { return (dir / name).string(); }
};

}  // namespace

TEST_CASE("spec inputs found by fuzz_spec parse or throw sigmatau::Error") {
  int files = 0;
  for (const auto& entry : fs::directory_iterator(test::test_data_dir() / "fuzz" / "spec")) {
    CAPTURE(entry.path().string());
    const std::string text = test::file_text(entry.path());
    const std::string r = outcome([&] { parse_data_sheet(text, entry.path().string()); });
    INFO(r);
    CHECK((r == "ok" || r == "error"));
    ++files;
  }
  CHECK(files >= 1);
}

TEST_CASE("text logs found by fuzz_text_log read, fill or throw sigmatau::Error") {
  // The first byte chooses the options as in fuzz/fuzz_text_log.cpp; the rest is the file. The
  // harness runs fill_gaps after read_log under --gaps fill, so this does too. Under UBSan
  // (scripts/test.sh's sanitizer stage, halt_on_error) an overflow aborts the test.
  Scratch dir;
  int files = 0;
  for (const auto& entry : fs::directory_iterator(test::test_data_dir() / "fuzz" / "text_log")) {
    CAPTURE(entry.path().string());
    const std::string bytes = test::file_text(entry.path());
    REQUIRE(!bytes.empty());
    const auto flags = static_cast<unsigned char>(bytes[0]);
    const std::string path = dir.file("input.txt");
    std::ofstream(path, std::ios::binary) << bytes.substr(1);
    LogOptions o;
    o.path = path;
    if (flags & 1) o.time_column = "0";
    o.time_unit = static_cast<TimeUnit>((flags >> 1) & 3);
    o.gaps = static_cast<GapPolicy>((flags >> 3) & 3);
    o.nonfinite = (flags & 32) ? NonFinitePolicy::skip_row : NonFinitePolicy::error;
    o.read_buffer_bytes = (flags & 64) ? 5 : 4096;
    if (flags & 128) o.columns = {"1"};
    const std::string r = outcome([&] {
      Log log = read_log(o);
      if (o.gaps == GapPolicy::fill) fill_gaps(log);
    });
    INFO(r);
    CHECK((r == "ok" || r == "error"));
    ++files;
  }
  CHECK(files >= 1);
}

TEST_CASE("--gaps fill refuses a gap of more than 2^63 intervals without overflow") {
  // fill_huge_gap.bin in plain words: stamps in s near 1.7e18 with one of 1.7e28, 1 s apart
  // otherwise. The gap spans ~1e28 intervals: far more than doubling the log.
  Scratch dir;
  const std::string path = dir.file("huge_gap.csv");
  std::ofstream(path) << "t,x\n0,0\n1,1\n2,2\n1e28,3\n";
  LogOptions o;
  o.path = path;
  o.time_column = "t";
  o.gaps = GapPolicy::fill;
  Log log = read_log(o);
  CHECK_THROWS_WITH_AS(fill_gaps(log), doctest::Contains("would more than double the log"), Error);
}

TEST_CASE("bags found by fuzz_bag read or throw sigmatau::Error") {
  // The first byte chooses the file name extension and the options as in fuzz/fuzz_bag.cpp; the
  // rest is the file. list_bag_topics runs on it too. Under UBSan (the sanitizer stage) undefined
  // behaviour aborts the test.
  Scratch dir;
  int files = 0;
  for (const auto& entry : fs::directory_iterator(test::test_data_dir() / "fuzz" / "bag")) {
    CAPTURE(entry.path().string());
    const std::string bytes = test::file_text(entry.path());
    REQUIRE(!bytes.empty());
    const auto flags = static_cast<unsigned char>(bytes[0]);
    const char* const extensions[3] = {".bag", ".mcap", ".db3"};
    const int kind = (flags & 3) == 3 ? 0 : (flags & 3);
    const std::string path = dir.file(std::string("input") + extensions[kind]);
    std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes.substr(1);
    LogOptions o;
    o.path = path;
    o.stamp = (flags & 4) ? BagStamp::receive : BagStamp::header;
    o.nonfinite = (flags & 8) ? NonFinitePolicy::skip_row : NonFinitePolicy::error;
    constexpr std::int64_t kWindows[4] = {0, 1, 4, 10000};
    o.reorder_window = kWindows[(flags >> 4) & 3];
    if (flags & 64) o.topic = "/imu/data";
    o.gaps = (flags & 128) ? GapPolicy::split : GapPolicy::report;
    std::string r = outcome([&] { read_log(o); });
    INFO(r);
    CHECK((r == "ok" || r == "error"));
    r = outcome([&] { list_bag_topics(path); });
    CHECK((r == "ok" || r == "error"));
    ++files;
  }
  CHECK(files >= 1);
}
