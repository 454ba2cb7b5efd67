// Averaging-factor grids for deviation curves (tau = m tau0).
//
// Glossary: N = number of phase points, m = averaging factor, tau0 = sample interval [s].
// Stable32's stop ratios (W. J. Riley, "The Evolution of Frequency Stability Analysis Software",
// Table III; allantoolkit's tau_generator): the largest m reported is (data points)/ratio, beyond
// which a statistic has too few terms to mean much. Stable32 counts the values it was given: N
// phase points, or M = N - 1 frequency values.
#include "sigmatau/taus.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

#include "sigmatau/error.hpp"
#include "sigmatau/sampling_limits.hpp"
#include "sigmatau/units.hpp"

namespace sigmatau {
namespace {

/// An explicit tau is taken as the nearest multiple m tau0 when it is this close (relative) to
/// one. Logs with time stamps measure tau0 from their own clock, which is a few ppm (a crystal)
/// to a few hundred ppm (a host clock) off the nominal rate: `--taus 1` must still mean the
/// m = 100 point of a 100 Hz log whose stamps say 100.0001 Hz. 1e-3 admits a clock 1000 ppm off
/// and still refuses a tau between two multiples (0.015 s at 0.01 s is 0.5 of m away, 1/3 of
/// its ratio). The tau reported is m tau0, the one computed.
constexpr double kTauMultipleTolerance = 1e-3;
/// Upper limit for "many:P": a denser grid than 1000 per decade has duplicates from m = 1 to
/// beyond 400, so it only costs time.
constexpr int kMaxPerDecade = 1000;

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

[[noreturn]] void bad_spec(std::string_view text, const std::string& why) {
  throw Error("bad tau specification \"" + std::string(text) + "\": " + why +
              " (expected octave, decade, many, many:P, all, or times such as 0.01,0.1,1 (seconds) or "
              "10ms,1s,2min)");
}

std::int64_t stop_ratio(Statistic statistic) {
  switch (statistic) {
    case Statistic::adev: return 5;
    case Statistic::oadev: return 4;
    case Statistic::mdev: return 4;
    case Statistic::tdev: return 4;
    case Statistic::hdev: return 5;
    case Statistic::ohdev: return 4;
    case Statistic::totdev: return 2;
  }
  return 5;
}

}  // namespace

TauSpec parse_tau_spec(std::string_view text) {
  const std::string_view t = trim(text);
  TauSpec spec;
  if (t == "octave") {
    spec.kind = TauSpec::Kind::octave;
  } else if (t == "decade") {
    spec.kind = TauSpec::Kind::decade;
  } else if (t == "all") {
    spec.kind = TauSpec::Kind::all;
  } else if (t == "many") {
    spec.kind = TauSpec::Kind::many;
  } else if (t.rfind("many:", 0) == 0) {
    spec.kind = TauSpec::Kind::many;
    const std::string_view p = t.substr(5);
    int value = 0;
    const auto [end, ec] = std::from_chars(p.data(), p.data() + p.size(), value);
    if (p.empty() || ec != std::errc() || end != p.data() + p.size() || value < 1 ||
        value > kMaxPerDecade) {
      bad_spec(text, "P in many:P must be an integer from 1 to " + std::to_string(kMaxPerDecade));
    }
    spec.per_decade = value;
  } else {
    spec.kind = TauSpec::Kind::explicit_seconds;
    std::string_view rest = t;
    while (true) {
      const std::size_t comma = rest.find(',');
      const std::string_view item = trim(rest.substr(0, comma));
      double value = 0.0;
      const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), value);
      if (item.empty() || ec != std::errc() || end != item.data() + item.size()) {
        // A time with its unit ("100 ms", "2min", "1h"), as --duration takes it.
        try {
          value = parse_quantity_as(item, dim::time, "tau");
        } catch (const UnitError&) {
          bad_spec(text, "\"" + std::string(item) + "\" is not a time (seconds, or a number with "
                         "a unit such as 100ms or 2min)");
        }
      }
      if (!(value > 0.0 && std::isfinite(value))) {
        bad_spec(text, "tau must be a finite number > 0 s, got \"" + std::string(item) + "\"");
      }
      spec.seconds.push_back(value);
      if (comma == std::string_view::npos) break;
      rest = rest.substr(comma + 1);
    }
  }
  return spec;
}

std::int64_t max_averaging_factor(Statistic statistic, std::int64_t n_phase_points,
                                  DataKind kind) {
  const std::int64_t N = n_phase_points;
  if (N < 2) return 0;
  const std::int64_t data_points = kind == DataKind::phase ? N : N - 1;
  // Largest m with at least one term (term_count in allan.cpp).
  std::int64_t limit = 0;
  switch (statistic) {
    case Statistic::adev:
    case Statistic::oadev: limit = (N - 1) / 2; break;
    case Statistic::totdev: limit = N / 2; break;
    case Statistic::mdev:
    case Statistic::tdev: limit = N / 3; break;
    case Statistic::hdev:
    case Statistic::ohdev: limit = (N - 1) / 3; break;
  }
  if (statistic == Statistic::totdev && N < 3) limit = 0;
  // A record too short for the stop ratio still gets m = 1 when that has terms.
  const std::int64_t by_ratio =
      std::max<std::int64_t>(data_points / stop_ratio(statistic), 1);
  return std::min(by_ratio, limit);
}

std::vector<std::int64_t> averaging_factors(const TauSpec& spec, Statistic statistic,
                                            std::int64_t n_phase_points, double tau0_s,
                                            DataKind kind) {
  checked_interval_s(tau0_s, "sample interval tau0_s");
  const std::int64_t max_m = max_averaging_factor(statistic, n_phase_points, kind);
  std::vector<std::int64_t> m;
  switch (spec.kind) {
    case TauSpec::Kind::octave:
      for (std::int64_t v = 1; v <= max_m; v *= 2) m.push_back(v);
      break;
    case TauSpec::Kind::decade:
      for (std::int64_t decade = 1; decade <= max_m; decade *= 10) {
        for (const std::int64_t step : {1, 2, 4}) {
          if (step * decade <= max_m) m.push_back(step * decade);
        }
      }
      break;
    case TauSpec::Kind::many: {
      if (!(spec.per_decade >= 1 && spec.per_decade <= kMaxPerDecade)) {
        throw Error("many:P needs P from 1 to " + std::to_string(kMaxPerDecade) + ", got " +
                    std::to_string(spec.per_decade));
      }
      for (int k = 0;; ++k) {
        const double v = std::pow(10.0, static_cast<double>(k) / spec.per_decade);
        const auto rounded = static_cast<std::int64_t>(std::llround(v));
        if (rounded > max_m) break;
        if (m.empty() || m.back() != rounded) m.push_back(rounded);
      }
      break;
    }
    case TauSpec::Kind::all:
      for (std::int64_t v = 1; v <= max_m; ++v) m.push_back(v);
      break;
    case TauSpec::Kind::explicit_seconds:
      for (const double seconds : spec.seconds) {
        const double ratio = seconds / tau0_s;
        if (!(ratio >= 0.5 && std::isfinite(ratio))) {
          char text[200];
          std::snprintf(text, sizeof text, "tau %.10g s is shorter than the sample interval %.10g s",
                        seconds, tau0_s);
          throw Error(text);
        }
        const double rounded = std::round(ratio);
        if (!(std::abs(ratio - rounded) <= kTauMultipleTolerance * ratio)) {
          char text[200];
          std::snprintf(text, sizeof text,
                        "tau %.10g s is not a multiple of the sample interval %.10g s (%.6g of it)",
                        seconds, tau0_s, ratio);
          throw Error(text);
        }
        if (rounded > static_cast<double>(max_m)) {
          // An explicitly asked tau that the record cannot give is an error, not a silent gap.
          char text[200];
          std::snprintf(text, sizeof text,
                        "tau %g s is too long for %s on this log: the longest is %g s (m = %lld "
                        "of %lld %s)",
                        seconds, std::string(to_string(statistic)).c_str(),
                        static_cast<double>(max_m) * tau0_s, static_cast<long long>(max_m),
                        static_cast<long long>(kind == DataKind::phase ? n_phase_points
                                                                       : n_phase_points - 1),
                        kind == DataKind::phase ? "phase points" : "samples");
          throw Error(text);
        }
        m.push_back(static_cast<std::int64_t>(rounded));
      }
      std::sort(m.begin(), m.end());
      m.erase(std::unique(m.begin(), m.end()), m.end());
      break;
  }
  return m;
}

}  // namespace sigmatau
