#pragma once
/// \file taus.hpp
/// Which averaging factors m (tau = m tau0) a deviation curve is computed at.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "sigmatau/allan.hpp"

namespace sigmatau {

struct TauSpec {
  enum class Kind { octave, decade, many, all, explicit_seconds };
  Kind kind = Kind::octave;
  int per_decade = 10;               ///< for `many`
  std::vector<double> seconds;       ///< for `explicit_seconds` [s]
};

/// Parses "octave" | "decade" | "many" | "many:P" | "all" | a list of times: bare numbers are
/// seconds ("0.01,0.1,1"), or each with a unit ("10ms,1s,2min"; parse_quantity).
/// Throws Error naming the text on anything else.
TauSpec parse_tau_spec(std::string_view text);

/// The largest m the statistic is reported at for N phase points, following Stable32's stop
/// ratios: largest m = (data points) / ratio, with ratio adev 5, oadev 4, mdev 4, tdev 4, hdev 5,
/// ohdev 4, totdev 2, and the data points counted as Stable32 counts them: N for phase input,
/// M = N - 1 for rate or increment input (so 8192 phase points give OADEV to m = 2048 and
/// TOTDEV to 4096, 8192 rate samples OADEV to 2048 and TOTDEV to 4096 as well). Never beyond
/// the point where the estimator has at least one term.
std::int64_t max_averaging_factor(Statistic statistic, std::int64_t n_phase_points,
                                  DataKind kind = DataKind::rate);

/// Averaging factors for a spec: octave 1,2,4,...; decade 1,2,4,10,20,40,100,...; many:P P
/// log-spaced per decade rounded to integers and de-duplicated; all 1..max; explicit seconds
/// rounded to the nearest m >= 1 (a tau that is not a multiple of tau0 within 1e-9 relative is
/// an Error, and so is an explicit tau beyond max_averaging_factor). The generated grids are
/// capped at max_averaging_factor for the statistic and the input's kind.
std::vector<std::int64_t> averaging_factors(const TauSpec& spec, Statistic statistic,
                                            std::int64_t n_phase_points, double tau0_s,
                                            DataKind kind = DataKind::rate);

}  // namespace sigmatau
