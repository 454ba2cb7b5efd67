#pragma once
// A fresh directory in the temp directory for one test, removed when it ends.
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>

namespace sigmatau::test {

class TempDir {
 public:
  /// <temp>/<prefix>_<pid>_<n>, emptied if it exists.
  explicit TempDir(const std::string& prefix) {
    static int counter = 0;
    path_ = std::filesystem::temp_directory_path() /
            (prefix + "_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  /// The path of `name` inside the directory.
  std::filesystem::path file(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

}  // namespace sigmatau::test
