// A calibrated triad's misalignment checked by what does not depend on the calibration frame
// (non-orthogonality), the gyro-to-accelerometer rotation reported beside the verdicts, and how a
// check states the limit it used or that it compared nothing.
#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "sigmatau/compliance.hpp"
#include "sigmatau/triad_frames.hpp"
#include "made_up_sheet.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A made-up sheet: a gyro misalignment printed axis-to-axis, an accelerometer cross-axis
// sensitivity (per axis against the package), and a noise density for the convention test.
const std::string kSheet = test::made_up_sheet("T-2", R"(gyro:
  noise_density:
    typ: 0.01 °/s/√Hz
    source: ds
    page: 1
  misalignment:
    typ: ±0.05 °
    condition: axis-to-axis
    source: ds
    page: 1
accel:
  cross_axis_sensitivity:
    typ: ±2 %
    source: ds
    page: 1
)");

// Like STIM300: a misalignment with no condition (read as each axis against the package).
constexpr const char* kPerAxisSheet = R"(schema: 1
manufacturer: Test
part: T-3
grade: tactical
sources:
  ds:
    document: test sheet
    revision: "1"
    kind: primary
gyro:
  misalignment:
    typ: 1 mrad
    source: ds
    page: 1
accel:
  misalignment:
    typ: 1 mrad
    source: ds
    page: 1
)";

/// A calibrate-like result: an orthogonal accelerometer (lower-triangular frame) and a gyro whose
/// matrix in that frame is `gyro` (row-major), each matrix entry with standard error `se`.
std::string calibration(const Eigen::Matrix3d& gyro, double se) {
  const auto num = [](double v) {
    std::ostringstream out;
    out.precision(17);
    out << v;
    return out.str();
  };
  const auto row = [&](const Eigen::Matrix3d& m, int i) {
    return "[" + num(m(i, 0)) + "," + num(m(i, 1)) + "," + num(m(i, 2)) + "]";
  };
  const auto matrix = [&](const Eigen::Matrix3d& m) {
    return "[" + row(m, 0) + "," + row(m, 1) + "," + row(m, 2) + "]";
  };
  const auto diagonal_covariance = [&](int n) {
    std::string out = "[";
    for (int i = 0; i < n; ++i) {
      out += i ? ",[" : "[";
      for (int j = 0; j < n; ++j) out += (j ? "," : "") + num(i == j ? se * se : 0.0);
      out += "]";
    }
    return out + "]";
  };
  return R"({"confidence":0.95,"accelerometer":{"confidence":0.95,"bias":[0,0,0],
    "matrix":)" + matrix(Eigen::Matrix3d::Identity()) + R"(,
    "parameters":["s_x","s_y","s_z","m_yx","m_zx","m_zy","b_x","b_y","b_z"],
    "covariance":)" + diagonal_covariance(9) + R"(},
    "gyroscope":{"confidence":0.95,"bias":[0,0,0],"matrix":)" + matrix(gyro) + R"(,
    "parameters":["G_xx","G_xy","G_xz","G_yx","G_yy","G_yz","G_zx","G_zy","G_zz","b_x","b_y","b_z"],
    "covariance":)" + diagonal_covariance(12) + "}}";
}

const ComplianceItem* find(const std::vector<ComplianceItem>& items, Sensor sensor,
                           MeasuredQuantity quantity, const std::string& axis) {
  for (const auto& item : items) {
    if (item.measured.sensor == sensor && item.measured.quantity == quantity &&
        item.measured.axis == axis) {
      return &item;
    }
  }
  return nullptr;
}

}  // namespace

TEST_CASE("an axis pair at a known angle has that non-orthogonality") {
  const double e = 0.003;  // the y axis leans e towards x
  TriadMatrix t;
  t.a << 1, 0, 0, std::sin(e), std::cos(e), 0, 0, 0, 1;
  // Exact geometry: only rounding separates the two (1e-12 of a 3e-3 angle).
  CHECK(non_orthogonality(t, 0, 1).value == test::rel(e, 1e-9));
  CHECK(std::abs(non_orthogonality(t, 0, 2).value) < 1e-15);
}

TEST_CASE("non-orthogonality does not change when the calibration frame is rotated") {
  TriadMatrix t;
  t.a << 1.001, 0.002, -0.0015, 0.0007, 0.998, 0.0011, -0.0009, 0.0031, 1.0004;
  const Eigen::Matrix3d r =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  TriadMatrix rotated = t;
  rotated.a = t.a * r;  // the same axes written in a rotated frame
  for (const auto& axes : {std::pair{0, 1}, std::pair{0, 2}, std::pair{1, 2}}) {
    const int i = axes.first, j = axes.second;
    CAPTURE(i);
    CAPTURE(j);
    // The Gram matrix is unchanged up to rounding: 1e-9 relative of a ~1e-3 angle.
    CHECK(non_orthogonality(rotated, i, j).value == test::rel(non_orthogonality(t, i, j).value, 1e-9));
    // To first order it is the symmetric part m_ij + m_ji; terms of second order in the
    // ~3e-3 entries are below 2e-5 rad.
    CHECK(std::abs(non_orthogonality(t, i, j).value - (t.a(i, j) + t.a(j, i))) < 2e-5);
  }
}

TEST_CASE("the rotation between two triads is recovered with its propagated error") {
  SUBCASE("small and large angles, non-orthogonal triads") {
    for (const double angle : {0.002, 0.5}) {
      CAPTURE(angle);
      const Eigen::Vector3d axis = Eigen::Vector3d(1, 1, 0.5).normalized();
      const Eigen::Matrix3d q = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
      TriadMatrix from;
      from.a << 1.002, 0.001, 0, 0.001, 0.997, 0.0005, 0, 0.0005, 1.001;  // symmetric: unrotated
      TriadMatrix to;
      to.a = from.a * q.transpose();  // every axis of `from` turned by q
      const auto phi = relative_rotation(from, to);
      for (int k = 0; k < 3; ++k) {
        // Exact up to the SVD's rounding (1e-9 of the angle).
        CHECK(phi[static_cast<std::size_t>(k)].value == test::rel(angle * axis[k], 1e-9));
      }
    }
  }
  SUBCASE("standard error: each component is half the difference of two entries") {
    // Near identity phi_z = (A_yx - A_xy) / 2 of `to` minus the same of `from`, so with every
    // entry's standard error sigma and the triads independent, se = hypot(sigma/sqrt 2, sigma/sqrt 2).
    const double sigma = 1e-5;
    TriadMatrix from, to;
    from.covariance = sigma * sigma * Eigen::Matrix<double, 9, 9>::Identity();
    to.covariance = from.covariance;
    to.a = Eigen::AngleAxisd(0.002, Eigen::Vector3d::UnitZ()).toRotationMatrix().transpose();
    const auto phi = relative_rotation(from, to);
    // The gradient differs from +-1/2 by terms of the order of the 2e-3 angle: 1 % covers it.
    CHECK(phi[2].standard_error == test::rel(sigma, 1e-2));
    CHECK(phi[0].standard_error == test::rel(sigma, 1e-2));
  }
}

TEST_CASE("a perfect gyro beside a rotated accelerometer passes (review C finding 6)") {
  // The accelerometer triad is turned 2 mrad about z; the gyro is perfect. Written in the
  // accelerometer frame the gyro matrix is that rotation: cross-axis terms of -+2 mrad, which the
  // old per-term check failed against a 1 mrad sheet.
  const double turn = 0.002;
  const Eigen::Matrix3d gyro =
      Eigen::AngleAxisd(-turn, Eigen::Vector3d::UnitZ()).toRotationMatrix().transpose();
  const auto measured = measured_parameters_from_json(calibration(gyro, 2e-5), "rot.json");
  const DataSheet sheet = parse_data_sheet(kPerAxisSheet, "t3.yaml");
  const auto items = check_compliance(measured, sheet);
  CHECK_FALSE(any_failed(items));
  for (const char* pair : {"xy", "xz", "yz"}) {
    CAPTURE(pair);
    const ComplianceItem* item = find(items, Sensor::gyro, MeasuredQuantity::non_orthogonality, pair);
    REQUIRE(item != nullptr);
    CHECK(item->verdict == Verdict::pass);
    // An exact rotation: orthogonal up to rounding.
    CHECK(std::abs(item->measured.value) < 1e-12);
    // No condition printed: read per axis, so a pair is allowed twice the printed 1 mrad.
    CHECK(item->limit_si == test::rel(2e-3, 1e-12));
    CHECK(item->limit_factor_text == "×2");
    CHECK(item->rule.find("2 x the printed misalignment") != std::string::npos);
  }
  // No per-term cross-axis items: they depend on the frame.
  CHECK(find(items, Sensor::gyro, MeasuredQuantity::cross_axis, "xy") == nullptr);
  // The rotation is reported, never judged.
  const ComplianceItem* rz = find(items, Sensor::gyro, MeasuredQuantity::frame_rotation, "z");
  REQUIRE(rz != nullptr);
  CHECK(rz->verdict == Verdict::not_specified);
  CHECK(rz->rule.find("informational") != std::string::npos);
  // Exact up to rounding (1e-9 of the angle).
  CHECK(rz->measured.value == test::rel(-turn, 1e-9));
  // Interval at the result's 95 %: 1.96 se. phi_z ~ (A_yx - A_xy)/2 of the gyro minus the same
  // of the accelerometer, whose A_xy is fixed at 0 by its convention: se = sigma sqrt(1/2 + 1/4)
  // (1 %: the gradient's deviation from +-1/2 is of the order of the 2e-3 angle).
  CHECK((rz->measured.ci_high - rz->measured.value) ==
        test::rel(1.959964 * 2e-5 * std::sqrt(0.75), 1e-2));
  CHECK(items_checked(items) == 6);
}

TEST_CASE("an axis-to-axis misalignment bounds the non-orthogonality itself, a cross-axis "
          "sensitivity bounds it at twice the printed value") {
  const DataSheet sheet = parse_data_sheet(kSheet, "t2.yaml");
  const double limit = 0.05 * kDeg;
  const auto items = check_compliance(
      {{Sensor::gyro, MeasuredQuantity::non_orthogonality, "xy", 0.8 * limit, 0.7 * limit, 0.9 * limit},
       {Sensor::gyro, MeasuredQuantity::non_orthogonality, "xz", -1.5 * limit, -1.6 * limit, -1.4 * limit},
       {Sensor::accel, MeasuredQuantity::non_orthogonality, "xy", 0.03, 0.029, 0.031}},
      sheet);
  REQUIRE(items.size() == 3);
  CHECK(items[0].verdict == Verdict::pass);
  CHECK(items[0].limit_si == test::rel(limit, 1e-12));
  CHECK(items[0].limit_factor_text.empty());
  CHECK(items[0].rule.find("axis-to-axis") != std::string::npos);
  CHECK(items[1].verdict == Verdict::fail);  // by magnitude: |-1.5 limit| > limit
  CHECK(items[1].compared == test::rel(1.5 * limit, 1e-12));
  // 3 % between two axes is within twice the printed 2 % per axis.
  CHECK(items[2].verdict == Verdict::pass);
  CHECK(items[2].limit_si == test::rel(0.04, 1e-12));
  CHECK(items[2].limit_factor == test::rel(2.0, 1e-15));
}

TEST_CASE("a one-sided density is compared at printed / sqrt(2) and the item says so") {
  const DataSheet sheet = parse_data_sheet(kSheet, "t2.yaml");
  ComplianceOptions options;
  options.convention = DensityConvention::one_sided;
  const double nd = 0.01 * kDeg;
  const auto items = check_compliance(
      {{Sensor::gyro, MeasuredQuantity::white_noise, "x", 0.6 * nd, 0.5 * nd, 0.65 * nd}}, sheet,
      options);
  REQUIRE(items.size() == 1);
  CHECK(items[0].limit_si == test::rel(nd / std::sqrt(2.0), 1e-12));
  CHECK(items[0].limit_factor == test::rel(1 / std::sqrt(2.0), 1e-15));
  CHECK(items[0].limit_factor_text == "/√2");
  CHECK(items[0].limit_text == "0.01 °/s/√Hz");  // the printed value is kept beside it
}

TEST_CASE("nothing is checked when the sheet prints none of the measured items") {
  const DataSheet sheet = parse_data_sheet(kPerAxisSheet, "t3.yaml");
  const auto items = check_compliance(
      {{Sensor::gyro, MeasuredQuantity::white_noise, "x", 1e-5, 9e-6, 1.1e-5},
       {Sensor::accel, MeasuredQuantity::bias, "y", -0.05, -0.06, -0.04}},
      sheet);
  CHECK(items.size() == 2);
  CHECK(items_checked(items) == 0);
  CHECK(overall_verdict(items) == "nothing to check");
  CHECK(compared_by_magnitude(MeasuredQuantity::bias));
  CHECK_FALSE(compared_by_magnitude(MeasuredQuantity::white_noise));
}
