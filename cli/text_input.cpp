// Whole small text inputs (saved JSON results) read with an error that says why they could not be.
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "sigmatau/error.hpp"
#include "verbs.hpp"

namespace sigmatau::cli {

std::string read_text_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw Error(path + ": cannot read: Is a directory (expected a JSON file)");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open: " + std::strerror(errno));
  std::string text;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw Error(path + ": cannot read: " + std::strerror(errno));
  return text;
}

}  // namespace sigmatau::cli
