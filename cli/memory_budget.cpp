#include "memory_budget.hpp"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <system_error>

#include "sigmatau/error.hpp"
#include "sigmatau/inflated_size.hpp"
#include "sigmatau/log_reader.hpp"

namespace sigmatau::cli {
namespace {

/// Bag bytes per Imu value assumed: an uncompressed sensor_msgs/Imu message takes 300-400 bytes
/// with its record header (covariances included) for six values, about 60 per value; 16 leaves
/// room for chunks compressed up to ~4x (lz4 and zstd do 2-3x on Imu messages), so a bag goes
/// out of core early rather than overrunning --memory (out of core costs a second read pass).
constexpr std::int64_t kBagBytesPerValue = 16;
/// Values of one sensor_msgs/Imu message the reader can take (three rates, three accelerations).
constexpr std::int64_t kImuValues = 6;
/// Largest --memory accepted [bytes]: 2^60 (1024 PiB), beyond any machine and far enough below
/// int64's 2^63 that the sums and products made from it cannot overflow.
constexpr double kMaxMemoryBytes = 1152921504606846976.0;

}  // namespace

std::int64_t parse_bytes(const std::string& text) {
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  std::string suffix = text.substr(used);
  if (!suffix.empty() && (suffix.back() == 'B' || suffix.back() == 'b')) suffix.pop_back();
  double factor = 0;
  if (suffix.empty()) factor = 1;
  if (suffix == "K" || suffix == "k") factor = 1e3;
  if (suffix == "M") factor = 1e6;
  if (suffix == "G") factor = 1e9;
  if (suffix == "T") factor = 1e12;
  if (suffix == "Ki") factor = 1024.0;
  if (suffix == "Mi") factor = 1024.0 * 1024;
  if (suffix == "Gi") factor = 1024.0 * 1024 * 1024;
  if (suffix == "Ti") factor = 1024.0 * 1024 * 1024 * 1024;
  if (suffix == "P") factor = 1e15;
  if (suffix == "Pi") factor = 1024.0 * 1024 * 1024 * 1024 * 1024;
  if (used == 0 || !(factor > 0) || !(value > 0) || !std::isfinite(value)) {
    throw Error("--memory must be a size such as 1GiB, 512MiB or 800M, got \"" + text + "\"");
  }
  // In doubles first: 1e300 x 1 overflowed the int64 byte count (undefined behaviour).
  const double bytes = value * factor;
  if (!(bytes >= 1 && bytes <= kMaxMemoryBytes)) {
    throw Error("--memory must be from 1 byte to 2^60 bytes (1024PiB), got \"" + text + "\"");
  }
  return static_cast<std::int64_t>(bytes);
}

std::int64_t estimated_values(const LogArguments& log, std::int64_t enough_values) {
  if (log.input == "-") return -1;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(log.input, ec)) return -1;
  auto bytes = static_cast<std::int64_t>(std::filesystem::file_size(log.input, ec));
  if (ec) return -1;
  if (is_bag_path(log.input)) {
    // The index's (or summary's) count when the bag states one (six values per Imu message),
    // else an estimate from the size. A bag that cannot be opened is left to the reader's
    // error.
    try {
      const std::int64_t messages = indexed_bag_messages(log.input, log.topic);
      if (messages >= 0) return messages * kImuValues;
    } catch (const Error&) {
    }
    return bytes / kBagBytesPerValue;
  }
  const std::int64_t per_value = log.binary.empty() ? 4 : value_bytes(parse_binary_format(log.binary));
  // A gzip file holds what it inflates to (5-700x its size for text): counted, up to the
  // bytes that already make more than enough_values.
  if (is_gzip_file(log.input)) {
    const std::int64_t enough_bytes =
        enough_values < 0 || enough_values > INT64_MAX / per_value ? INT64_MAX - 1
                                                                   : enough_values * per_value;
    bytes = inflated_bytes(log.input, enough_bytes);
  }
  return bytes / per_value;
}

bool exact_needs_out_of_core(const LogArguments& log, std::int64_t memory_bytes) {
  const bool has_time =
      !log.time_column.empty() || !log.time_column_found.empty() || is_bag_path(log.input);
  if (has_time && (log.gaps == "split" || log.gaps == "fill")) return false;
  const std::int64_t fit = memory_bytes / kExactBytesPerSample;
  const std::int64_t values = estimated_values(log, fit);
  return values >= 0 && values > fit;
}

}  // namespace sigmatau::cli
