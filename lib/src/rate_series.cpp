// Rate series from rate, increment or phase values (see rate_series.hpp).
#include "sigmatau/rate_series.hpp"

#include <algorithm>

namespace sigmatau {

std::int64_t rate_count(std::int64_t values, DataKind kind) {
  return kind == DataKind::phase ? std::max<std::int64_t>(values - 1, 0) : values;
}

std::vector<double> to_rate_series(std::vector<double> values, DataKind kind, double rate_hz) {
  if (kind == DataKind::increment) {
    for (double& v : values) v *= rate_hz;
  } else if (kind == DataKind::phase) {
    for (std::size_t i = 0; i + 1 < values.size(); ++i) values[i] = (values[i + 1] - values[i]) * rate_hz;
    if (!values.empty()) values.pop_back();
  }
  return values;
}

std::span<const double> RateStream::convert(std::span<const double> values) {
  if (kind_ == DataKind::rate) return values;
  out_.clear();
  if (kind_ == DataKind::increment) {
    for (const double v : values) out_.push_back(v * rate_hz_);
  } else {
    for (const double v : values) {
      if (have_previous_) out_.push_back((v - previous_) * rate_hz_);
      previous_ = v;
      have_previous_ = true;
    }
  }
  return out_;
}

}  // namespace sigmatau
