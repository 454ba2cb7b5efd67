#pragma once
// Internal: how the dynamic Allan deviation cuts a channel into windows, shared by the
// in-memory (analysis.cpp) and bounded-memory (analysis_bounded.cpp) analyses, and what is said
// when the windows asked cannot be formed.
#include <cstdint>
#include <string>

namespace sigmatau::detail {

/// The windows of one channel: `windows` half-overlapping windows of `length` samples, the w-th
/// starting at w x length / 2 (analysis_results.hpp: dynamic_window_length); `windows` is 0 and
/// `warning` says why when each would be shorter than kMinDynamicWindow samples.
struct DynamicWindows {
  std::int64_t length = 0;  ///< samples per window
  int windows = 0;          ///< windows formed (the number asked, or 0)
  std::string warning;      ///< "" when the windows asked are formed
};

/// The plan for `asked` windows (>= 1) over `samples` samples. Throws Error when asked < 1.
DynamicWindows plan_dynamic_windows(std::int64_t samples, int asked);

}  // namespace sigmatau::detail
