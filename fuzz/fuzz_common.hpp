#pragma once
// Shared helpers of the libFuzzer harnesses: the input goes to a per-process temporary file
// (the reader opens paths), and the options are taken from the first bytes.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "sigmatau/error.hpp"
#include "sigmatau/log_reader.hpp"

namespace sigmatau::fuzz {

/// The directory of the scratch files: /dev/shm when there is one (memory: rewriting a file on
/// disk for every input was the harnesses' largest cost after the read buffers), else /tmp.
inline const std::string& scratch_dir() {
  static const std::string dir = access("/dev/shm", W_OK) == 0 ? "/dev/shm" : "/tmp";
  return dir;
}

/// Unlinks the scratch files when the fuzzer exits normally (-max_total_time, -runs); a crash
/// leaves them, beside the crash artifact.
struct ScratchFiles {
  std::vector<std::string> paths;
  ~ScratchFiles() {
    for (const auto& p : paths) unlink(p.c_str());
  }
};

/// A scratch file named after the process with `suffix` (e.g. ".dat", ".bag"), rewritten for
/// every input and removed at exit.
inline std::string scratch_file(const char* suffix) {
  static ScratchFiles files;
  std::string path =
      scratch_dir() + "/sigmatau_fuzz_" + std::to_string(static_cast<long>(getpid())) + suffix;
  files.paths.push_back(path);
  return path;
}

/// The scratch file of the text and binary harnesses.
inline const std::string& scratch_path() {
  static const std::string path = scratch_file(".dat");
  return path;
}

inline void write_scratch(const std::uint8_t* data, std::size_t size) {
  std::FILE* f = std::fopen(scratch_path().c_str(), "wb");
  if (!f) __builtin_trap();
  if (size > 0 && std::fwrite(data, 1, size, f) != size) __builtin_trap();
  std::fclose(f);
}

/// Reads the whole input through LogReader in small blocks and checks the invariants every
/// block must keep. sigmatau::Error is the expected outcome of bad input; anything else escapes
/// and is reported by libFuzzer as a crash.
inline void read_all(const LogOptions& options) {
  try {
    LogReader reader(options);
    SampleBlock block;
    std::int64_t rows = 0;
    while (reader.read_block(block, 7)) {
      if (block.values.size() != reader.channel_names().size()) __builtin_trap();
      for (const auto& v : block.values) {
        if (static_cast<std::int64_t>(v.size()) != block.rows()) __builtin_trap();
      }
      rows += block.rows();
    }
    if (reader.timing().samples != rows) __builtin_trap();
    if (options.gaps == GapPolicy::split) {
      const auto& s = reader.timing().segment_starts;
      if (reader.has_time() && (s.empty() || s.front() != 0)) __builtin_trap();
      for (std::size_t i = 1; i < s.size(); ++i) {
        if (!(s[i] > s[i - 1] && s[i] < rows)) __builtin_trap();
      }
    }
    if (options.gaps == GapPolicy::fill && reader.has_time() && rows > 0) {
      Log log = read_log(options);
      const auto before = log.t_s.size();
      const auto added = fill_gaps(log);
      if (log.t_s.size() != before + static_cast<std::size_t>(added)) __builtin_trap();
      for (const auto& c : log.channels) {
        if (c.size() != log.t_s.size()) __builtin_trap();
      }
    }
  } catch (const Error&) {
  }
}

}  // namespace sigmatau::fuzz
