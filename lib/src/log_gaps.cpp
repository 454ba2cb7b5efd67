// Gap policies (log_reader.hpp, GapPolicy): their names, and fill_gaps, which interpolates the
// samples a gap lost under GapPolicy::fill. Gaps are found as in the timing statistics
// (log_common.cpp): dt > kGapFactor x the nominal interval.
#include <cmath>
#include <string>
#include <vector>

#include "log_internal.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau {

GapPolicy parse_gap_policy(std::string_view text) {
  if (text == "report") return GapPolicy::report;
  if (text == "error") return GapPolicy::error;
  if (text == "split") return GapPolicy::split;
  if (text == "fill") return GapPolicy::fill;
  throw Error("unknown gap policy \"" + std::string(text) +
              "\" (expected error, split, fill or report)");
}

std::int64_t fill_gaps(Log& log) {
  using detail::format_seconds;
  using detail::kGapFactor;
  const std::string file = log.path == "-" ? "<stdin>" : log.path;
  if (log.t_s.empty()) throw Error(file + ": --gaps fill needs a time column");
  if (!(log.timing.rate_hz > 0)) {
    throw Error(file + ": --gaps fill needs a sample rate measured from the time column");
  }
  const double nominal_s = 1.0 / log.timing.rate_hz;
  const std::size_t n = log.t_s.size();
  // First pass: count (and check) what would be inserted, so that nothing changes on error.
  std::int64_t missing = 0;
  for (std::size_t i = 1; i < n; ++i) {
    const double dt = log.t_s[i] - log.t_s[i - 1];
    if (!(dt > 0)) {
      throw ParseError(file, 0, 0,
                       "time stamp at row " + std::to_string(i) +
                           " does not increase; --gaps fill cannot interpolate backwards "
                           "(use --gaps split)");
    }
    if (dt > kGapFactor * nominal_s) {
      const double spans = std::round(dt / nominal_s);  // intervals the gap spans
      // Compared in double before any integer conversion: absurd stamps can make a gap of more
      // than 2^63 intervals, where llround overflowed (found by fuzz_text_log).
      if (!(static_cast<double>(missing) + spans - 1 <= static_cast<double>(n))) {
        throw Error(file + ": --gaps fill would more than double the log (a gap of " +
                    format_seconds(dt) + " before row " + std::to_string(i) +
                    "); use --gaps split");
      }
      missing += static_cast<std::int64_t>(spans) - 1;
    }
  }
  if (missing == 0) return 0;
  const auto grow = [&](std::vector<double>& x) {
    std::vector<double> out;
    out.reserve(n + static_cast<std::size_t>(missing));
    out.push_back(x[0]);
    for (std::size_t i = 1; i < n; ++i) {
      const double dt = log.t_s[i] - log.t_s[i - 1];
      if (dt > kGapFactor * nominal_s) {
        const auto k = std::llround(dt / nominal_s);  // intervals the gap spans
        for (long long j = 1; j < k; ++j) {
          const double w = static_cast<double>(j) / static_cast<double>(k);
          out.push_back(x[i - 1] + w * (x[i] - x[i - 1]));
        }
      }
      out.push_back(x[i]);
    }
    x.swap(out);
  };
  for (auto& channel : log.channels) grow(channel);
  grow(log.t_s);  // last: the loops above read the original stamps
  log.timing.filled_samples += missing;
  return missing;
}

}  // namespace sigmatau
