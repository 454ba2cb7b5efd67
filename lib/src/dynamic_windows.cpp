// The dynamic Allan windows of a channel, and the warning when they cannot be formed.
//
// Glossary: M = samples of the (trimmed) channel, K = windows asked; each window is
// L = 2 M / (K + 1) samples long, the w-th starting at w L / 2, so they overlap by half and the
// last ends at M.
#include "dynamic_windows.hpp"

#include "analysis_results.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau::detail {

DynamicWindows plan_dynamic_windows(std::int64_t samples, int asked) {
  if (asked < 1) throw Error("dynamic windows: the number asked must be >= 1, got " + std::to_string(asked));
  DynamicWindows plan;
  // In 64 bits: K + 1 overflowed an int at K = 2^31 - 1.
  plan.length = 2 * samples / (static_cast<std::int64_t>(asked) + 1);
  if (plan.length >= kMinDynamicWindow) {
    plan.windows = asked;
    return plan;
  }
  // The most windows of kMinDynamicWindow samples: 2 M / (K + 1) >= L_min <=> K <= 2 M / L_min - 1.
  const std::int64_t most = 2 * samples / kMinDynamicWindow - 1;
  plan.warning = "dynamic Allan deviation: none of the " + std::to_string(asked) +
                 " windows asked was formed: over " + std::to_string(samples) +
                 " samples each would hold " + std::to_string(plan.length) +
                 (plan.length == 1 ? " sample" : " samples") + ", fewer than the " +
                 std::to_string(kMinDynamicWindow) + " an OADEV curve needs; " +
                 (most > 1    ? "at most " + std::to_string(most) + " windows fit"
                  : most == 1 ? std::string("only 1 window fits")
                              : std::string("the log is too short for any window"));
  return plan;
}

}  // namespace sigmatau::detail
