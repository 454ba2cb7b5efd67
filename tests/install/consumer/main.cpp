// Links the installed library and computes one OADEV: exits 0 only when the value is right.
#include <sigmatau/allan.hpp>
#include <sigmatau/phase_series.hpp>

#include <cmath>
#include <cstdio>
#include <vector>

int main() {
  // Alternating +1/-1 rate: every m=1 second difference is +-2, so OADEV(1) = sqrt(4/2) = sqrt(2).
  std::vector<double> y(100);
  for (std::size_t i = 0; i < y.size(); ++i) y[i] = (i % 2 == 0) ? 1.0 : -1.0;
  const auto series = sigmatau::PhaseSeries::from_rate(y, 1.0);
  const std::int64_t m[] = {1};
  const auto points = sigmatau::compute_deviation(series, sigmatau::Statistic::oadev, m);
  const bool ok = points.size() == 1 && std::abs(points[0].dev - std::sqrt(2.0)) < 1e-12;
  std::printf("oadev(1) = %.15g (%s)\n", points.empty() ? -1.0 : points[0].dev, ok ? "ok" : "WRONG");
  return ok ? 0 : 1;
}
