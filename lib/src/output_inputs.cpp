// Inputs are never outputs: the files and directories a run reads, by device and inode, which no
// output of the run may replace (nor, for a directory output, hold).
#include <sys/stat.h>

#include <mutex>
#include <string>
#include <vector>

#include "output_internal.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/output_file.hpp"

namespace sigmatau {
namespace {

struct Input {
  dev_t device = 0;
  ino_t inode = 0;
  std::filesystem::path path;  // as the user named it, for messages
};

// Entries of an input directory noted with it (a rosbag2 folder holds a few files): more are
// not looked at (the folder itself is still an input).
constexpr std::size_t kFolderEntries = 4096;

std::mutex inputs_mutex;
std::vector<Input> inputs;  // guarded by inputs_mutex

bool is_file_or_directory(const struct stat& status) {
  return S_ISREG(status.st_mode) || S_ISDIR(status.st_mode);
}

void add(const struct stat& status, const std::filesystem::path& path) {
  for (const auto& input : inputs) {
    if (input.device == status.st_dev && input.inode == status.st_ino) return;
  }
  inputs.push_back({status.st_dev, status.st_ino, path});
}

/// The input `status` names, or nullptr.
const Input* find(const struct stat& status) {
  for (const auto& input : inputs) {
    if (input.device == status.st_dev && input.inode == status.st_ino) return &input;
  }
  return nullptr;
}

}  // namespace

void note_input(const std::filesystem::path& path) {
  struct stat status {};
  if (path.empty() || ::stat(path.c_str(), &status) != 0 || !is_file_or_directory(status)) return;
  const std::lock_guard lock(inputs_mutex);
  add(status, path);
  if (!S_ISDIR(status.st_mode)) return;
  std::error_code ec;
  std::size_t seen = 0;
  for (std::filesystem::directory_iterator it(path, ec), end; !ec && it != end; it.increment(ec)) {
    if (++seen > kFolderEntries) break;
    struct stat entry {};
    if (::stat(it->path().c_str(), &entry) == 0 && S_ISREG(entry.st_mode)) add(entry, it->path());
  }
}

void forget_inputs() noexcept {
  const std::lock_guard lock(inputs_mutex);
  inputs.clear();
}

namespace detail {

void refuse_input_target(const std::filesystem::path& requested, const Target& target) {
  struct stat status {};
  if (::stat(target.path.c_str(), &status) != 0 || !is_file_or_directory(status)) return;
  const std::lock_guard lock(inputs_mutex);
  if (const Input* input = find(status)) {
    throw Error("cannot write " + describe(requested, target) + ": it is an input of this run (" +
                input->path.string() + "); choose another output name");
  }
  if (!S_ISDIR(status.st_mode)) return;
  // A directory holds an input when it is one of the input's ancestors, compared by device and
  // inode along the input's real path (links resolved, so "a/../b" and bind mounts agree).
  for (const auto& input : inputs) {
    std::error_code ec;
    std::filesystem::path ancestor = std::filesystem::canonical(input.path, ec);
    if (ec) continue;
    while (ancestor.has_relative_path()) {
      ancestor = ancestor.parent_path();
      struct stat above {};
      if (::stat(ancestor.c_str(), &above) == 0 && above.st_dev == status.st_dev &&
          above.st_ino == status.st_ino) {
        throw Error("cannot replace " + describe(requested, target) + ": it holds " +
                    input.path.string() + ", an input of this run; choose another output name");
      }
    }
  }
}

}  // namespace detail
}  // namespace sigmatau
