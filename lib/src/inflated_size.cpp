// Counting a gzip file's inflated bytes (inflated_size.hpp) through the reader's own ByteSource,
// so multi-member files and corrupt data behave as when the log is read.
#include "sigmatau/inflated_size.hpp"

#include <vector>

#include "byte_source.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau {
namespace {

/// Bytes inflated per read: large enough that zlib's per-call cost vanishes, small next to any
/// memory budget.
constexpr std::size_t kCountBufferBytes = std::size_t{1} << 20;

}  // namespace

std::int64_t inflated_bytes(const std::string& path, std::int64_t stop_after) {
  if (stop_after < 0) throw Error("inflated_bytes: stop_after must be >= 0");
  detail::ByteSource source(path);
  std::vector<char> buffer(kCountBufferBytes);
  std::int64_t total = 0;
  while (total <= stop_after) {
    const std::size_t got = source.read(buffer.data(), buffer.size());
    if (got == 0) break;
    total += static_cast<std::int64_t>(got);
  }
  return total;
}

}  // namespace sigmatau
