#pragma once
// The order statistics the benchmarks report: the median of a sample and a distribution-free
// interval for it.
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace sigmatau::bench {

/// The median of v (the mean of the two middle values for an even count); NaN when v is empty.
inline double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/// Distribution-free 95 % interval of the median of v: the order statistics whose ranks are
/// n/2 -+ 1.96 sqrt(n)/2 (the number of values below the median is Binomial(n, 1/2), here by
/// its normal approximation, good to a rank for n >= 100). NaNs for fewer than 2 values.
inline std::pair<double, double> median_interval(std::vector<double> v) {
  if (v.size() < 2) return {std::nan(""), std::nan("")};
  std::sort(v.begin(), v.end());
  const double n = static_cast<double>(v.size());
  const double half_width = 1.96 * std::sqrt(n) / 2;
  const auto rank = [&](double r) {
    return v[static_cast<std::size_t>(std::clamp(r, 0.0, n - 1))];
  };
  return {rank(std::floor(n / 2 - half_width) - 1), rank(std::ceil(n / 2 + half_width) - 1)};
}

}  // namespace sigmatau::bench
