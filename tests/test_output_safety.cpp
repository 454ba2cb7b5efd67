// Nothing lost (issue 28, "Data loss"): an input is never an output; --force replaces an earlier
// report of sigmatau's and nothing else; of two writers of one new name the second is refused;
// temporary names abandoned by a killed run are removed, a live one's never; an interrupt removes
// a scratch tree with whatever is in it and kills the child writing there. The CLI side
// (every verb, real races, kill -9, signals) is in tests/cli/output_safety.cmake.
#include <doctest/doctest.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "sigmatau/error.hpp"
#include "sigmatau/output_file.hpp"
#include "temp_dir.hpp"
#include "test_support.hpp"

using namespace sigmatau;
namespace fs = std::filesystem;

namespace {

using test::error_of;

void write_text(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

/// Forgets the inputs noted by a test when it ends (they are process-wide).
struct InputsForgotten {
  InputsForgotten() { forget_inputs(); }
  ~InputsForgotten() { forget_inputs(); }
};

/// A file or directory held open and locked as a live writer holds its temporary name.
class Held {
 public:
  explicit Held(const fs::path& path) : fd_(::open(path.c_str(), O_RDONLY | O_CLOEXEC)) {
    REQUIRE(fd_ >= 0);
    REQUIRE(::flock(fd_, LOCK_EX) == 0);
  }
  ~Held() { ::close(fd_); }
  Held(const Held&) = delete;
  Held& operator=(const Held&) = delete;

 private:
  int fd_;
};

}  // namespace

TEST_CASE("an input is never replaced, also through a symbolic or a hard link, --force or not") {
  const InputsForgotten forgotten;
  test::TempDir dir("sigmatau_safety_input");
  const fs::path log = dir.file("log.csv");
  write_text(log, "t,gx\n0,1\n");
  fs::create_symlink("log.csv", dir.file("soft.csv"));
  fs::create_hard_link(log, dir.file("hard.csv"));
  note_input(log);
  for (const bool overwrite : {false, true}) {
    CAPTURE(overwrite);
    for (const char* name : {"log.csv", "soft.csv", "hard.csv"}) {
      CAPTURE(name);
      CHECK(contains(error_of([&] { check_can_write(dir.file(name), overwrite); }),
                     "is an input of this run"));
      CHECK(contains(error_of([&] { write_file_atomically(dir.file(name), "x\n", overwrite); }),
                     "is an input of this run"));
    }
  }
  CHECK(test::file_text(log) == "t,gx\n0,1\n");
  // A file no one reads is still replaced with --force.
  write_text(dir.file("old.json"), "old\n");
  write_file_atomically(dir.file("old.json"), "new\n", true);
  CHECK(test::file_text(dir.file("old.json")) == "new\n");
}

TEST_CASE("a directory holding an input, an input folder and its files are never outputs") {
  const InputsForgotten forgotten;
  test::TempDir dir("sigmatau_safety_holds");
  // The issue's `analyze data/log.csv -o data --force`, with `data` an earlier report (so that
  // only the input stops it), and the directory above it.
  write_directory_atomically(dir.file("report"), {{"results.json", "{}\n"}, {"log.csv", "x"}},
                             false);
  note_input(dir.file("report/log.csv"));
  CHECK(contains(error_of([&] { check_output_directory(dir.file("report"), true); }),
                 "holds " + dir.file("report/log.csv").string() + ", an input of this run"));
  CHECK(contains(error_of([&] { check_output_directory(dir.file("report").parent_path(), true); }),
                 "an input of this run"));
  CHECK(test::file_text(dir.file("report/log.csv")) == "x");
  // A rosbag2 folder given as the input: the folder and the files in it.
  write_text(dir.file("bag/metadata.yaml"), "rosbag2_bagfile_information: {}\n");
  note_input(dir.file("bag"));
  CHECK(contains(error_of([&] { write_file_atomically(dir.file("bag/metadata.yaml"), "", true); }),
                 "is an input of this run"));
  CHECK(contains(error_of([&] { check_output_directory(dir.file("bag"), true); }),
                 "is an input of this run"));
  write_file_atomically(dir.file("bag/notes.txt"), "a new file beside the bag\n", false);
  CHECK(test::file_text(dir.file("bag/metadata.yaml")) == "rosbag2_bagfile_information: {}\n");
}

TEST_CASE("--force replaces an earlier report of sigmatau's and nothing else") {
  test::TempDir dir("sigmatau_safety_force");
  const std::map<std::string, std::string> files = {{"results.json", "{\"tool\": \"sigmatau\"}\n"},
                                                    {"report.html", "<html></html>\n"},
                                                    {"dynamic_a/b.svg", "<svg/>\n"}};
  SUBCASE("a directory sigmatau did not write") {
    write_text(dir.file("mine/notes.txt"), "notes\n");
    CHECK(contains(error_of([&] { write_directory_atomically(dir.file("mine"), files, true); }),
                   "is not a report directory sigmatau wrote (no .sigmatau-report file in it)"));
    CHECK(contains(error_of([&] { check_output_directory(dir.file("mine"), false); }),
                   "exists and cannot be replaced"));
    CHECK(test::file_text(dir.file("mine/notes.txt")) == "notes\n");
  }
  SUBCASE("an earlier report, its files listed in the marker, a subdirectory among them") {
    write_directory_atomically(dir.file("report"), files, false);
    const std::string marker = test::file_text(dir.file("report") / kReportMarker);
    CHECK(marker.starts_with("sigmatau report directory\n"));
    CHECK(contains(marker, "\nresults.json\n"));
    CHECK(contains(marker, "\ndynamic_a/b.svg\n"));
    CHECK(contains(error_of([&] { check_output_directory(dir.file("report"), false); }),
                   "exists; use --force to replace it"));
    write_directory_atomically(dir.file("report"), {{"results.json", "second\n"}}, true);
    CHECK(test::file_text(dir.file("report/results.json")) == "second\n");
    CHECK(!fs::exists(dir.file("report/report.html")));
  }
  SUBCASE("an earlier report holding a file sigmatau did not write") {
    write_directory_atomically(dir.file("report"), files, false);
    write_text(dir.file("report/dynamic_a/mine.txt"), "mine\n");
    CHECK(contains(error_of([&] { write_directory_atomically(dir.file("report"), files, true); }),
                   "holds dynamic_a/mine.txt, which sigmatau did not write"));
    CHECK(test::file_text(dir.file("report/dynamic_a/mine.txt")) == "mine\n");
  }
  SUBCASE("a report written before the marker: its names and a results.json of sigmatau's") {
    write_text(dir.file("old/results.json"), "{\"tool\": \"sigmatau\", \"version\": \"0.0\"}\n");
    for (const char* name : {"report.html", "summary.md", "adev_gyro.svg", "psd_accel.png",
                             "dynamic_gx.svg", "compliance.pdf", "filter_200Hz.json",
                             "gtsam_200Hz.txt", "kalibr_imu_200Hz.yaml", "openvins_imu_200Hz.yaml",
                             "vins_fusion_200Hz.yaml", "px4_ekf2_200Hz.params", "truth.json"}) {
      write_text(dir.file("old") / name, "old\n");
    }
    fs::copy(dir.file("old"), dir.file("old_notes"));
    write_text(dir.file("old_notes/notes.md"), "notes\n");
    fs::copy(dir.file("old"), dir.file("not_ours"));
    write_text(dir.file("not_ours/results.json"), "{\"tool\": \"other\"}\n");
    CHECK(contains(error_of([&] { check_output_directory(dir.file("old_notes"), true); }),
                   "holds notes.md, which sigmatau did not write"));
    CHECK(contains(error_of([&] { check_output_directory(dir.file("not_ours"), true); }),
                   "is not a report directory sigmatau wrote"));
    write_directory_atomically(dir.file("old"), files, true);
    CHECK(fs::exists(dir.file("old") / kReportMarker));
    CHECK(!fs::exists(dir.file("old/summary.md")));
  }
  SUBCASE("a file is never replaced by a report directory") {
    write_text(dir.file("file.txt"), "plain\n");
    CHECK(contains(error_of([&] { write_directory_atomically(dir.file("file.txt"), files, true); }),
                   "exists and is a file; expected a directory name"));
    CHECK(test::file_text(dir.file("file.txt")) == "plain\n");
  }
}

TEST_CASE("of two writers of one new name, the second is refused and the first's file stays") {
  test::TempDir dir("sigmatau_safety_claim");
  const fs::path out = dir.file("out.json");
  {
    AtomicOutputFile first(out, false);
    AtomicOutputFile second(out, false);
    first.write("first\n");
    second.write("second\n");
    first.commit();
    CHECK(contains(error_of([&] { second.commit(); }), "exists; use --force to overwrite it"));
  }
  CHECK(test::file_text(out) == "first\n");
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(out.parent_path())) ++entries;
  CHECK(entries == 1);  // no temporary file left
}

TEST_CASE("temporary names a killed run left are removed, a live run's and look-alikes kept") {
  test::TempDir dir("sigmatau_safety_leftovers");
  // As kill -9 leaves them: no process holds their lock.
  write_text(dir.file("out.json.tmp-0a1b2c"), "dead\n");
  write_text(dir.file("report.partial-Ab12Cd/results.json"), "dead\n");
  fs::create_directories(dir.file("report.partial-Xy34Zw.old"));
  // Held, as a live run holds its own; and names that only look alike.
  write_text(dir.file("out.json.tmp-abcdef"), "live\n");
  fs::create_directories(dir.file("report.partial-LiVe00"));
  const Held live_file(dir.file("out.json.tmp-abcdef"));
  const Held live_directory(dir.file("report.partial-LiVe00"));
  for (const char* name : {"out.json.tmp-notes", "out.json.tmp-0a1b2c3", "other.json.tmp-0a1b2c",
                           "report.partial-", "report.partial-Ab12Cd.bak"}) {
    write_text(dir.file(name), "kept\n");
  }
  write_file_atomically(dir.file("out.json"), "{}\n", false);
  write_directory_atomically(dir.file("report"), {{"results.json", "{}\n"}}, false);
  CHECK(!fs::exists(dir.file("out.json.tmp-0a1b2c")));
  CHECK(!fs::exists(dir.file("report.partial-Ab12Cd")));
  CHECK(!fs::exists(dir.file("report.partial-Xy34Zw.old")));
  CHECK(fs::exists(dir.file("out.json.tmp-abcdef")));
  CHECK(fs::exists(dir.file("report.partial-LiVe00")));
  for (const char* name : {"out.json.tmp-notes", "out.json.tmp-0a1b2c3", "other.json.tmp-0a1b2c",
                           "report.partial-", "report.partial-Ab12Cd.bak"}) {
    CAPTURE(name);
    CHECK(test::file_text(dir.file(name)) == "kept\n");
  }
}

TEST_CASE("an interrupt removes a tracked scratch directory with everything in it") {
  test::TempDir dir("sigmatau_safety_interrupt");
  const fs::path scratch = dir.file("scratch");
  // A finished plot, a child's log, a subdirectory: none tracked by name.
  write_text(scratch / "adev_gyro.svg", "<svg/>\n");
  write_text(scratch / "gnuplot.log", "\n");
  write_text(scratch / "sub" / "deeper" / "data.dat", "1 2\n");
  write_text(dir.file("output.json"), "an output, not tracked\n");
  {
    const InterruptCleanup tracked(scratch);
    remove_pending_temporaries();
  }
  CHECK(!fs::exists(scratch));
  CHECK(fs::exists(dir.file("output.json")));
}

TEST_CASE("an interrupt kills and reaps a tracked child before removing its directory") {
  char program[] = "sleep";
  char seconds[] = "30";
  char* argv[] = {program, seconds, nullptr};
  pid_t pid = 0;
  REQUIRE(::posix_spawnp(&pid, "sleep", nullptr, nullptr, argv, environ) == 0);
  {
    const KillOnInterrupt child(pid);
    remove_pending_temporaries();
  }
  // Reaped already: nothing is left to wait for.
  errno = 0;
  CHECK(::waitpid(pid, nullptr, WNOHANG) == -1);
  CHECK(errno == ECHILD);
}
