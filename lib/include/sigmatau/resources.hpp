#pragma once
/// \file resources.hpp
/// Where sigmatau finds the files it ships (plots/ gnuplot templates, specs/ data sheets):
/// $SIGMATAU_<NAME>_DIR if set, else <prefix>/share/sigmatau/<name> next to an installed
/// executable, else the source tree the library was built from.

#include <filesystem>
#include <string_view>

namespace sigmatau {

/// The directory holding the shipped resource `name` ("plots" or "specs"). Throws Error naming
/// the places searched when none exists.
std::filesystem::path resource_dir(std::string_view name);

}  // namespace sigmatau
