#pragma once
/// \file rate_series.hpp
/// The rate series behind a log of any DataKind, which the PSD and the warm-up detection work
/// on: rates as they are, increments x rate_hz, phase differenced x rate_hz (one fewer value).
/// Whole series and series arriving block by block give the same values, bit for bit.

#include <cstdint>
#include <span>
#include <vector>

#include "sigmatau/phase_series.hpp"

namespace sigmatau {

/// Rate samples behind `values` values of `kind`: as many, or one fewer for phase (0 for none).
std::int64_t rate_count(std::int64_t values, DataKind kind);

/// The rate series of a whole series of `kind` sampled at rate_hz [Hz].
std::vector<double> to_rate_series(std::vector<double> values, DataKind kind, double rate_hz);

/// The same for values arriving in blocks: convert() returns the rates the block completes
/// (for phase, the first value yields none), valid until the next call.
class RateStream {
 public:
  RateStream(DataKind kind, double rate_hz) : kind_(kind), rate_hz_(rate_hz) {}
  std::span<const double> convert(std::span<const double> values);

 private:
  DataKind kind_;
  double rate_hz_;
  std::vector<double> out_;
  double previous_ = 0;
  bool have_previous_ = false;
};

}  // namespace sigmatau
