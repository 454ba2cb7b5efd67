#pragma once
// Private to the library (plot.cpp, report_plots.cpp): a scratch directory for gnuplot's data
// and output files. Not installed.

#include <stdlib.h>

#include <filesystem>
#include <memory>
#include <string>
#include <system_error>

#include "sigmatau/error.hpp"
#include "sigmatau/output_file.hpp"

namespace sigmatau::detail {

/// A private directory "<prefix>XXXXXX" in the temporary directory ($TMPDIR, else /tmp),
/// removed with everything in it when this object goes, whatever the exception that unwinds it.
/// The directory is also on the interrupt clean-up table (InterruptCleanup), which removes it with
/// everything in it, so a run interrupted by a signal leaves nothing behind.
class ScratchDir {
 public:
  /// Throws Error when the directory cannot be created (a $TMPDIR that is not a directory, a
  /// full or read-only disk).
  explicit ScratchDir(const std::string& prefix = "sigmatau-plot-") {
    std::error_code ec;
    const std::filesystem::path base = std::filesystem::temp_directory_path(ec);
    if (ec) throw Error("cannot find a temporary directory for plots: " + ec.message());
    std::string pattern = (base / (prefix + "XXXXXX")).string();
    if (!::mkdtemp(pattern.data())) {
      throw Error("cannot create a temporary directory for plots in " + base.string());
    }
    path_ = pattern;
    tracked_ = std::make_unique<InterruptCleanup>(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  /// The directory.
  const std::filesystem::path& path() const { return path_; }

  /// The path of a file named `name` in the directory (removed with it, also on an interrupt).
  std::filesystem::path file(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
  std::unique_ptr<InterruptCleanup> tracked_;
};

}  // namespace sigmatau::detail
