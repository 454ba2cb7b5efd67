// Internal: placeholder until the rosbag2 SQLite (.db3) reader lands (issue 10); replaced by the reader itself.
#include "bag_backend.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau::detail {

std::unique_ptr<BagBackend> open_rosbag2_sqlite(const std::string& path) {
  throw Error(path + ": rosbag2 SQLite (.db3) files cannot be read yet");
}

}  // namespace sigmatau::detail
