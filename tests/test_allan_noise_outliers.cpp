// isolated_noise_types: a noise type that jumps at one tau between agreeing neighbours.
#include <doctest/doctest.h>

#include <vector>

#include "sigmatau/allan_curve.hpp"
#include "sigmatau/log_reader.hpp"
#include "sigmatau/phase_series.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

AllanCurve curve_of(const std::vector<int>& alphas) {
  AllanCurve curve;
  for (const int alpha : alphas) {
    CurvePoint p;
    p.confidence.noise.alpha = alpha;
    curve.points.push_back(p);
  }
  return curve;
}

}  // namespace

TEST_CASE("a jump of two or more between agreeing neighbours is flagged, a gradual change is not") {
  // The HiPNUC CH104 gyro's pattern: white FM, white PM at one tau (a 0.2 Hz line), white FM.
  CHECK(isolated_noise_types(curve_of({0, 0, 2, 0, 0})) == std::vector<std::size_t>{2});
  CHECK(isolated_noise_types(curve_of({-1, 1, -1})) == std::vector<std::size_t>{1});
  // Power-law noise changing type along the curve: quantization to white to flicker to RW FM.
  CHECK(isolated_noise_types(curve_of({2, 2, 1, 0, 0, -1, -1, -2})).empty());
  // A one-step wobble (flicker read once among white FM) is within the estimator's scatter.
  CHECK(isolated_noise_types(curve_of({0, -1, 0})).empty());
  // Neighbours that disagree: a transition, not an outlier.
  CHECK(isolated_noise_types(curve_of({2, 0, -2})).empty());
  // The ends have one neighbour only and are never flagged.
  CHECK(isolated_noise_types(curve_of({2, 0, 0, 0, -2})).empty());
  CHECK(isolated_noise_types(curve_of({})).empty());
  CHECK(isolated_noise_types(curve_of({0, 2})).empty());
}

TEST_CASE("the HiPNUC CH104 gyro's 0.2 Hz line is flagged at 2.56 s and nowhere else") {
  if (!test::has_reference_data("imu/hipnuc_ch104")) return;
  LogOptions options;
  options.path =
      (test::reference_data_dir() / "imu/hipnuc_ch104/hipnuc_ch104_static_100Hz.csv.gz").string();
  options.columns = {"gyro_x"};
  const Log log = read_log(options);
  REQUIRE(log.channels.size() == 1);
  const auto series = PhaseSeries::from_rate(log.channels[0], 0.01);
  const AllanCurve curve = compute_allan_curve(series, Statistic::oadev, TauSpec{}, 0.683);
  const auto flagged = isolated_noise_types(curve);
  REQUIRE(flagged.size() == 1);
  const CurvePoint& p = curve.points[flagged[0]];
  CHECK(p.value.m == 256);
  CHECK(p.confidence.noise.alpha == 2);
  // The jumped type's EDF dwarfs its neighbours' (1.65e5 against 3762 and 939 in review D).
  CHECK(p.confidence.edf > 10 * curve.points[flagged[0] - 1].confidence.edf);
}
