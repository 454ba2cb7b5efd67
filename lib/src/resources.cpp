// Locating shipped resources: environment override, install prefix, source tree.
#include "sigmatau/resources.hpp"

#include <cctype>
#include <cstdlib>
#include <string>

#include "sigmatau/error.hpp"

namespace sigmatau {

std::filesystem::path resource_dir(std::string_view name) {
  std::string variable = "SIGMATAU_";
  for (char c : name) variable += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  variable += "_DIR";
  std::string searched;
  if (const char* env = std::getenv(variable.c_str()); env && *env) {
    if (std::filesystem::is_directory(env)) return env;
    throw Error(variable + "=" + env + " is not a directory");
  }
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const auto installed = exe.parent_path().parent_path() / "share" / "sigmatau" / name;
    if (std::filesystem::is_directory(installed, ec)) return installed;
    searched += installed.string() + ", ";
  }
  const auto source = std::filesystem::path(SIGMATAU_SOURCE_DIR) / name;
  if (std::filesystem::is_directory(source, ec)) return source;
  searched += source.string();
  throw Error("cannot find the " + std::string(name) + " directory (looked in " + searched +
              "; set " + variable + ")");
}

}  // namespace sigmatau
