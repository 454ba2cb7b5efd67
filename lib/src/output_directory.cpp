// A report directory (analyze, demo) written atomically: built aside under a locked
// "<dir>.partial-XXXXXX", marked as sigmatau's with a file listing what it wrote, then renamed
// into place without replacing anything, or, with --force, exchanged with an earlier report of
// sigmatau's, never with another directory.
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include "output_internal.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/output_file.hpp"

namespace sigmatau {

using detail::describe;
using detail::directory_of;
using detail::resolve_target;
using detail::Target;
using detail::TargetKind;

namespace {

/// The marker's first line; the lines after it (but comments) name the files written.
constexpr std::string_view kMarkerTitle = "sigmatau report directory";

/// What analyze and demo wrote before the marker existed (sigmatau 0.x up to this change): an
/// old report whose results.json says "tool": "sigmatau" and that holds only files of these
/// names is taken as one of sigmatau's. Nothing else without the marker is.
const std::regex& legacy_report_names() {
  static const std::regex names(
      "results\\.json|truth\\.json|report\\.html|summary\\.md|"
      "(adev|psd)_(gyro|accel)\\.(svg|png|pdf)|dynamic_[^/]+\\.(svg|png|pdf)|"
      "compliance\\.(svg|png|pdf)|filter_[0-9.e+-]+Hz\\.json|gtsam_[0-9.e+-]+Hz\\.txt|"
      "(kalibr_imu|openvins_imu|vins_fusion)_[0-9.e+-]+Hz\\.yaml|px4_ekf2_[0-9.e+-]+Hz\\.params");
  return names;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

bool is_plain_file(const std::filesystem::path& path) {
  struct stat status {};
  return ::lstat(path.c_str(), &status) == 0 && S_ISREG(status.st_mode);
}

/// The names a marker lists, or nothing when `text` is not a marker.
std::optional<std::set<std::string>> listed_names(const std::string& text) {
  std::istringstream lines(text);
  std::string line;
  if (!std::getline(lines, line) || line != kMarkerTitle) return std::nullopt;
  std::set<std::string> names;
  while (std::getline(lines, line)) {
    if (!line.empty() && line[0] != '#') names.insert(line);
  }
  return names;
}

/// Whether the results.json of an old report says it is sigmatau's.
bool legacy_results(const std::filesystem::path& file) {
  if (!is_plain_file(file)) return false;
  const nlohmann::json results = nlohmann::json::parse(read_text(file), nullptr, false);
  return results.is_object() && results.value("tool", std::string()) == "sigmatau";
}

/// Why the existing directory `dir` is not an earlier report of sigmatau's that --force may
/// replace ("it is not a report directory ...", "it holds X, which sigmatau did not write"), or
/// "" when it is one.
std::string why_not_a_report(const std::filesystem::path& dir) {
  const std::filesystem::path marker = dir / kReportMarker;
  std::optional<std::set<std::string>> listed;
  if (is_plain_file(marker)) listed = listed_names(read_text(marker));
  if (!listed && !legacy_results(dir / "results.json")) {
    return "it is not a report directory sigmatau wrote (no " + std::string(kReportMarker) +
           " file in it)";
  }
  std::error_code ec;
  std::filesystem::recursive_directory_iterator it(dir, ec), end;
  for (; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().lexically_relative(dir).generic_string();
    if (name == kReportMarker) continue;
    const std::filesystem::file_status status = it->symlink_status(ec);
    bool written = false;
    if (std::filesystem::is_regular_file(status)) {
      written = listed ? listed->count(name) > 0 : std::regex_match(name, legacy_report_names());
    } else if (std::filesystem::is_directory(status) && listed) {
      const auto after = listed->lower_bound(name + "/");
      written = after != listed->end() && after->starts_with(name + "/");
    }
    if (!written) return "it holds " + name + ", which sigmatau did not write";
  }
  if (ec) return "it cannot be read (" + ec.message() + ")";
  return "";
}

/// The marker's text: its title, what it means, and the names of `files`.
std::string marker_text(const std::map<std::string, std::string>& files) {
  std::string text = std::string(kMarkerTitle) +
                     "\n# Written by sigmatau " SIGMATAU_VERSION
                     ". --force replaces this directory only while this file is in it\n"
                     "# and the directory holds no file but these:\n";
  for (const auto& entry : files) text += entry.first + "\n";
  return text;
}

/// "<dir>.partial-XXXXXX" beside `dir`, locked while this object lives (so that another run
/// takes it for abandoned only once this process is gone) and on the interrupt clean-up table.
/// Removed with everything in it when the object goes, unless it was placed.
class StagingDirectory {
 public:
  explicit StagingDirectory(const std::filesystem::path& dir) {
    constexpr int kTries = 4;  // as AtomicOutputFile: a new name when tidying took the first
    for (int attempt = 0; attempt < kTries && fd_ < 0; ++attempt) {
      std::string name = dir.string() + ".partial-XXXXXX";
      if (!::mkdtemp(name.data())) {
        throw Error("cannot create a directory next to " + dir.string() + ": " +
                    std::strerror(errno));
      }
      path_ = name;
      fd_ = ::open(path_.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
      if (fd_ >= 0 && detail::lock_as_live(fd_, path_)) break;
      if (fd_ >= 0) ::close(fd_);
      fd_ = -1;
    }
    if (fd_ < 0) throw Error("cannot create a directory next to " + dir.string());
    cleanup_ = std::make_unique<InterruptCleanup>(path_);
  }
  ~StagingDirectory() {
    if (!placed_) {
      std::error_code ec;
      std::filesystem::remove_all(path_, ec);
    }
    cleanup_.reset();
    ::close(fd_);
  }
  StagingDirectory(const StagingDirectory&) = delete;
  StagingDirectory& operator=(const StagingDirectory&) = delete;

  const std::filesystem::path& path() const { return path_; }
  /// Called once the directory was renamed to its final name: its name is no longer ours.
  void placed() { placed_ = true; }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  bool placed_ = false;
  std::unique_ptr<InterruptCleanup> cleanup_;
};

bool same_file(const struct stat& a, const struct stat& b) {
  return a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

/// Throws the Error check_output_directory gives for an existing directory `target` that may not
/// be replaced (an input, holding one, or not an earlier report), or, without `overwrite`, for
/// one that may.
void check_replaceable(const std::filesystem::path& requested, const Target& target,
                       bool overwrite) {
  detail::refuse_input_target(requested, target);
  const std::string why = why_not_a_report(target.path);
  if (!why.empty()) {
    throw Error((overwrite ? "cannot replace " + describe(requested, target)
                           : describe(requested, target) + " exists and cannot be replaced") +
                ": " + why + "; choose another name");
  }
  if (!overwrite) throw Error(describe(requested, target) + " exists; use --force to replace it");
}

/// Moves `staging` to `dir` (`requested` with its links followed): a rename that fails when the
/// name exists, or with `overwrite` an exchange with the earlier report found there (checked
/// again just before), which is then removed. Either the old report or the new one is at `dir`
/// at every moment.
void place(StagingDirectory& staging, const std::filesystem::path& requested,
           const std::filesystem::path& dir, bool overwrite) {
  constexpr int kTries = 4;  // the name may appear and vanish between the steps (other runs)
  for (int attempt = 0; attempt < kTries; ++attempt) {
    const int failure = detail::rename_without_replacing(staging.path(), dir);
    if (failure == 0) {
      staging.placed();
      return;
    }
    if (failure != EEXIST) {
      throw Error("cannot write " + requested.string() + ": " + std::strerror(failure));
    }
    const Target target{dir, TargetKind::directory};
    struct stat checked {};
    if (::lstat(dir.c_str(), &checked) != 0) continue;  // gone again: try the rename again
    if (!S_ISDIR(checked.st_mode)) {
      throw Error(requested.string() + " exists and is not a directory; choose another name");
    }
    check_replaceable(requested, target, overwrite);
    if (::renameat2(AT_FDCWD, staging.path().c_str(), AT_FDCWD, dir.c_str(), RENAME_EXCHANGE) !=
        0) {
      if (errno == ENOENT) continue;
      if (errno != EINVAL && errno != ENOSYS && errno != EOPNOTSUPP) {
        throw Error("cannot replace " + requested.string() + ": " + std::strerror(errno));
      }
      // No RENAME_EXCHANGE on this file system: the old report aside, then the new one in.
      const std::filesystem::path aside = staging.path().string() + ".old";
      std::filesystem::rename(dir, aside);
      std::filesystem::rename(staging.path(), dir);
      staging.placed();
      std::error_code ec;
      std::filesystem::remove_all(aside, ec);
      return;
    }
    // The staging name now holds what was at `dir`: the report checked above, unless it was
    // swapped in between, which is put back.
    struct stat swapped {};
    if (::lstat(staging.path().c_str(), &swapped) != 0 || !same_file(checked, swapped)) {
      ::renameat2(AT_FDCWD, staging.path().c_str(), AT_FDCWD, dir.c_str(), RENAME_EXCHANGE);
      throw Error("cannot replace " + requested.string() +
                  ": it changed while it was being replaced; nothing replaced");
    }
    std::error_code ec;
    std::filesystem::remove_all(staging.path(), ec);
    staging.placed();
    return;
  }
  throw Error("cannot write " + requested.string() + ": it kept appearing and vanishing");
}

}  // namespace

std::filesystem::path check_output_directory(const std::filesystem::path& dir, bool overwrite) {
  const Target target = resolve_target(dir);
  switch (target.kind) {
    case TargetKind::absent:
      break;
    case TargetKind::directory:
      check_replaceable(dir, target, overwrite);
      break;
    case TargetKind::regular:
      detail::refuse_input_target(dir, target);
      throw Error(describe(dir, target) +
                  " exists and is a file; expected a directory name (a report directory never "
                  "replaces a file)");
    default:
      throw Error("cannot write " + describe(dir, target) +
                  ": it is a device, pipe or socket; expected a directory name");
  }
  detail::check_can_create_in(target.path, describe(dir, target));
  return target.path;
}

void write_directory_atomically(const std::filesystem::path& requested,
                                const std::map<std::string, std::string>& files, bool overwrite) {
  // A trailing '/' dropped, a link followed (never replaced), a device or pipe refused even with
  // --force, an input or a directory that is not an earlier report refused.
  const std::filesystem::path dir = check_output_directory(requested, overwrite);
  const std::filesystem::path parent = directory_of(dir);
  std::error_code ec;
  std::filesystem::create_directories(parent, ec);
  if (ec) throw Error("cannot create directory " + parent.string() + ": " + ec.message());
  detail::remove_abandoned_leftovers(parent, dir.filename().native());
  StagingDirectory staging(dir);
  try {
    for (const auto& [file, content] : files) {
      write_file_atomically(staging.path() / file, content, false);
    }
    write_file_atomically(staging.path() / kReportMarker, marker_text(files), false);
    std::filesystem::permissions(staging.path(), std::filesystem::perms::owner_all |
                                                     std::filesystem::perms::group_read |
                                                     std::filesystem::perms::group_exec |
                                                     std::filesystem::perms::others_read |
                                                     std::filesystem::perms::others_exec);
    detail::hold_commit_for_tests(dir);
    place(staging, requested, dir, overwrite);
  } catch (const std::filesystem::filesystem_error& e) {
    throw Error("cannot write " + dir.string() + ": " + e.what());
  }
}

}  // namespace sigmatau
