#pragma once
// --memory for the log-reading verbs (adev, fit, psd): parsing the size, and how many values a
// file holds, to decide before reading whether the exact in-memory path fits.
#include <cstdint>
#include <string>

#include "log_options.hpp"

namespace sigmatau::cli {

/// Bytes from "1GiB", "512MiB", "800M", "2G", "123456" (K/M/G/T/P decimal, Ki/Mi/Gi/Ti/Pi
/// binary, an optional trailing B), from 1 to 2^60. Throws Error naming --memory otherwise.
std::int64_t parse_bytes(const std::string& text);

/// Bytes the exact in-memory Allan path needs per sample and channel: the raw value (8) while
/// reading, then the double-double phase (16) and the sweep copy (8) that each series keeps.
constexpr std::int64_t kExactBytesPerSample = 32;

/// Values (samples x channels) a seekable input file holds, estimated from its size: exact for
/// raw binary, at most bytes / 4 for text (a value and its delimiter take >= 4 bytes in
/// practice), bytes / kBagBytesPerValue for a ROS bag, -1 for stdin, a rosbag2 folder or when the
/// size is unknown. A gzip file counts what it inflates to (inflated_size.hpp), counted up to
/// the bytes of `enough_values` values (-1: all): a return above enough_values means "more".
std::int64_t estimated_values(const LogArguments& log, std::int64_t enough_values = -1);

/// Whether exact Allan curves of `log` would need more than `memory_bytes` in memory, so that
/// they are computed out of core (allan_out_of_core.hpp) instead. Never for stdin (it cannot be
/// read twice) nor for --gaps split/fill with a time column or a ROS bag (they need the whole log
/// in memory).
bool exact_needs_out_of_core(const LogArguments& log, std::int64_t memory_bytes);

}  // namespace sigmatau::cli
