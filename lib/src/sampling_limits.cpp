// The accepted ranges of rates, sample intervals and times (sampling_limits.hpp), and the one
// message every verb gives outside them.
#include "sigmatau/sampling_limits.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "sigmatau/error.hpp"

namespace sigmatau {
namespace {

/// Relative slack at the ends of the ranges: 1 / 1e-9 is 1e9 x (1 + 1.2e-16) in doubles, so a
/// rate at an end and its interval would otherwise not both be accepted. 1e-12 covers the
/// rounding of a few divisions and nothing else.
constexpr double kEdgeSlack = 1e-12;

bool within(double v, double low, double high) {
  return v >= low * (1 - kEdgeSlack) && v <= high * (1 + kEdgeSlack);
}

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

}  // namespace

double checked_rate_hz(double rate_hz, std::string_view field) {
  if (!within(rate_hz, kMinRateHz, kMaxRateHz)) {
    throw Error(std::string(field) + " must be a rate from " + number(kMinRateHz) + " Hz to " +
                number(kMaxRateHz) + " Hz (one sample in 31.7 years to one a picosecond), got " +
                number(rate_hz) + " Hz");
  }
  return rate_hz;
}

double checked_interval_s(double tau0_s, std::string_view field) {
  if (!within(tau0_s, kMinTimeS, kMaxIntervalS)) {
    throw Error(std::string(field) + " must be a sample interval from " + number(kMinTimeS) +
                " s to " + number(kMaxIntervalS) +
                " s (a rate from " + number(kMaxRateHz) + " Hz to " + number(kMinRateHz) +
                " Hz), got " + number(tau0_s) + " s");
  }
  return tau0_s;
}

double checked_time_s(double seconds, std::string_view field) {
  if (!within(seconds, kMinTimeS, kMaxTimeS)) {
    throw Error(std::string(field) + " must be a time from " + number(kMinTimeS) + " s to " +
                number(kMaxTimeS) + " s, got " + number(seconds) + " s");
  }
  return seconds;
}

std::int64_t checked_samples(double seconds, double rate_hz, std::string_view field) {
  if (!(seconds >= 0) || !std::isfinite(seconds)) {
    throw Error(std::string(field) + " must be a finite time >= 0 s, got " + number(seconds) +
                " s");
  }
  const double count = std::round(seconds * rate_hz);
  if (!(count <= kMaxSampleCount)) {
    throw Error(std::string(field) + ": " + number(seconds) + " s at " + number(rate_hz) +
                " Hz is " + number(count) + " samples, more than any log holds (2^53)");
  }
  return static_cast<std::int64_t>(count);
}

}  // namespace sigmatau
