#pragma once
/// \file saved_adev.hpp
/// A saved `sigmatau adev --format json` result read back, so that `fit` can work from it
/// instead of the log: its OADEV curves in SI and what the fit needs to know of the series
/// behind them (sample interval, length).

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sigmatau/allan_curve.hpp"
#include "sigmatau/fit.hpp"
#include "sigmatau/noise_model.hpp"

namespace sigmatau {

/// One channel of a saved adev result, converted to SI.
struct SavedCurve {
  std::string channel;
  AllanCurve curve;  ///< oadev, deviations in SI
  CurveSource source;
  std::optional<Sensor> sensor;  ///< from the unit's dimension, when the result has a unit
};

/// A saved adev result: the log's sample rate as written ("input": {"rate_hz"}) [Hz], and
/// every OADEV curve in it.
struct SavedAdev {
  double rate_hz = 0;
  std::vector<SavedCurve> curves;
};

/// Whether `text` (the start of a file is enough) looks like JSON rather than a log.
bool looks_like_json(std::string_view text);

/// Reads a saved adev JSON result: every "oadev" result (others are skipped). Deviations are
/// converted to SI with the result's unit (empty unit: taken as SI).
/// Throws Error naming `file` and the missing or malformed field, or when it holds no oadev
/// result ("rerun adev with --stat oadev").
SavedAdev read_adev_json(std::string_view text, const std::string& file);

}  // namespace sigmatau
