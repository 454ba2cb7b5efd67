// Internal: placeholder until the MCAP reader lands (issue 10); replaced by the reader itself.
#include "bag_backend.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau::detail {

std::unique_ptr<BagBackend> open_mcap(const std::string& path) {
  throw Error(path + ": MCAP files cannot be read yet");
}

}  // namespace sigmatau::detail
