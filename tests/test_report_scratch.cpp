// The report's plot scratch directory (code review G#22): made in $TMPDIR like the plots' own
// (it was always "/tmp/..."), and removed on any exception, not only on sigmatau::Error.
#include <stdlib.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "sigmatau/error.hpp"
#include "sigmatau/plot.hpp"
#include "sigmatau/report.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

/// Sets $TMPDIR for the life of the object, restoring the old value after.
class TmpdirOverride {
 public:
  explicit TmpdirOverride(const std::filesystem::path& dir) {
    if (const char* old = std::getenv("TMPDIR")) old_ = old;
    ::setenv("TMPDIR", dir.c_str(), 1);
  }
  ~TmpdirOverride() {
    if (old_) {
      ::setenv("TMPDIR", old_->c_str(), 1);
    } else {
      ::unsetenv("TMPDIR");
    }
  }

 private:
  std::optional<std::string> old_;
};

/// A results.json with one gyro channel; `tau` is what its ADEV point holds.
nlohmann::json results_with_tau(const nlohmann::json& tau) {
  const nlohmann::json points = {{{"tau", tau}, {"dev", 1e-4}, {"ci_low", 0.9e-4}, {"ci_high", 1.1e-4}},
                                 {{"tau", 1.0}, {"dev", 1e-5}, {"ci_low", 0.9e-5}, {"ci_high", 1.1e-5}}};
  return {{"tool", "sigmatau"},
          {"version", "test"},
          {"input", {{"path", "log.csv"}}},
          {"channels",
           {{{"name", "gx"},
             {"sensor", "gyro"},
             {"allan", {{{"statistic", "oadev"}, {"points", points}}}}}}}};
}

}  // namespace

TEST_CASE("the report's plot scratch directory is made in $TMPDIR") {
  if (!gnuplot_available()) {
    MESSAGE("gnuplot not found: the report makes no scratch directory; check skipped");
    return;
  }
  // A $TMPDIR that is a file: the scratch directory cannot be made there, and the report says
  // so (with "/tmp/..." hard-wired it went to /tmp and succeeded).
  const auto file = std::filesystem::temp_directory_path() /
                    ("sigmatau_tmpdir_is_a_file_" + std::to_string(::getpid()));
  std::ofstream(file) << "not a directory\n";
  {
    const TmpdirOverride tmpdir(file);
    CHECK_THROWS_AS(build_report(results_with_tau(0.1).dump(), ReportOptions{}), Error);
  }
  std::filesystem::remove(file);
}

TEST_CASE("the report's plot scratch directory is removed when a non-Error exception unwinds it") {
  if (!gnuplot_available()) {
    MESSAGE("gnuplot not found: the report makes no scratch directory; check skipped");
    return;
  }
  const auto dir = std::filesystem::temp_directory_path() /
                   ("sigmatau_scratch_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    const TmpdirOverride tmpdir(dir);
    // A tau that is text: reading it throws a json exception inside the plots, after the scratch
    // directory was made (build_report turns it into an Error on the way out).
    CHECK_THROWS_AS(build_report(results_with_tau("0.1").dump(), ReportOptions{}), Error);
    // And a good file renders, leaving nothing behind either.
    const ReportFiles files = build_report(results_with_tau(0.1).dump(), ReportOptions{});
    CHECK(files.files.count("adev_gyro.svg") == 1);
  }
  CHECK(std::filesystem::is_empty(dir));
  std::filesystem::remove_all(dir);
}
