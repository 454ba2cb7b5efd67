#pragma once
/// \file sampling_limits.hpp
/// The sample rates and times sigmatau computes with, checked in one place by every verb and
/// every library entry point that takes one (a log's --rate or time column, a filter rate, a
/// simulation rate, a sample interval, a time turned into a sample count). Outside these
/// ranges the arithmetic leaves the double range somewhere (the noise fit's design holds
/// tau^-2 .. tau^2 and squares them: a rate of 1e80 Hz gave terms of 0 with NaN intervals,
/// p = nan), or a sample count leaves int64 (a trim of 1e300 s became -2^63 samples).
///
/// The limits are far outside any sensor or clock record: 1e-9 Hz is one sample in 31.7 years
/// (clock records are daily to monthly: 1e-5 to 4e-7 Hz), 1e12 Hz one sample a picosecond
/// (time-interval counters and fast digitisers stop near 1e10 Hz). Inside them, results scale
/// exactly with the rate (test_sampling_limits checks the fit, PSD and conversions at both ends).
/// Library functions name their field (rate_hz, tau0_s); the CLI passes the flag's name.

#include <cstdint>
#include <string_view>

namespace sigmatau {

/// Lowest sample or filter rate accepted [Hz]: one sample in 31.7 years.
inline constexpr double kMinRateHz = 1e-9;
/// Highest sample or filter rate accepted [Hz]: one sample a picosecond.
inline constexpr double kMaxRateHz = 1e12;
/// Shortest time accepted for a sample interval or a tau [s] (1 / kMaxRateHz).
inline constexpr double kMinTimeS = 1e-12;
/// Longest sample interval accepted [s] (1 / kMinRateHz).
inline constexpr double kMaxIntervalS = 1e9;
/// Longest time accepted for a tau, a reference time or a duration [s]: 3e10 years, beyond the
/// age of the universe (4.4e17 s) yet far from where tau^2 and tau^-2 overflow (1e154).
inline constexpr double kMaxTimeS = 1e18;
/// Largest sample count a time may stand for: 2^53, beyond which a double no longer counts
/// samples exactly (and far beyond any log: 9e15 samples are 2.9 years at 100 MHz).
inline constexpr double kMaxSampleCount = 9007199254740992.0;

/// `rate_hz` when it is finite and within [kMinRateHz, kMaxRateHz]. Throws Error "<field> must
/// be a rate from 1e-09 Hz to 1e+12 Hz (...), got <rate_hz> Hz" otherwise (NaN included).
double checked_rate_hz(double rate_hz, std::string_view field);

/// `tau0_s` when it is a sample interval of an accepted rate: finite, within
/// [kMinTimeS, kMaxIntervalS] = [1e-12 s, 1e9 s]. Throws Error naming `field` otherwise.
/// The rate and interval checks admit a few ulp beyond their ends, so that 1 / rate of an
/// accepted rate is an accepted interval and the reverse.
double checked_interval_s(double tau0_s, std::string_view field);

/// `seconds` when it is finite and within [kMinTimeS, kMaxTimeS]. Throws Error naming `field`
/// otherwise.
double checked_time_s(double seconds, std::string_view field);

/// The samples `seconds` [s, >= 0] span at `rate_hz` [Hz], rounded to the nearest: Throws Error
/// naming `field` when seconds is negative or not finite, or when the count exceeds
/// kMaxSampleCount (a time too long for any log; before this check such a count wrapped to a
/// negative int64).
std::int64_t checked_samples(double seconds, double rate_hz, std::string_view field);

}  // namespace sigmatau
