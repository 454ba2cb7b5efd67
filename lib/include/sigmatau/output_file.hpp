#pragma once
/// \file output_file.hpp
/// Nothing lost: every output file is written to a temporary name in its directory and renamed
/// into place, and an existing file is only replaced when the user said --force.

#include <filesystem>
#include <string_view>

namespace sigmatau {

/// Writes `content` to `path` atomically: creates missing parent directories, writes
/// "<path>.tmp-<random>" in the same directory, flushes it to disk and renames it over `path`.
/// Throws Error (and leaves no temporary file behind) when `path` exists and `overwrite` is
/// false ("... exists; use --force to overwrite"), or when the directory cannot be created or
/// written, or the disk is full.
void write_file_atomically(const std::filesystem::path& path, std::string_view content,
                           bool overwrite);

/// Throws the same "exists" Error as write_file_atomically, early, before long work starts.
void check_can_write(const std::filesystem::path& path, bool overwrite);

}  // namespace sigmatau
