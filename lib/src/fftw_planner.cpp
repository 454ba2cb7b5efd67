#include "fftw_planner.hpp"

namespace sigmatau::detail {

std::mutex& fftw_planner_mutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace sigmatau::detail
