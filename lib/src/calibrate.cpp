// Multi-position calibration: orchestration, gyroscope bias and temperature models, and output
// (calibrate.hpp).
//
// Glossary: K static intervals; d_k the unit gravity-reaction direction of interval k (raw
// accelerometer mean normalised); u_k the calibrated one; Omega Earth rate; lat latitude;
// T0 reference temperature; AICc corrected Akaike criterion.
#include "sigmatau/calibrate.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>

#include "calibrate_internal.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/sampling_limits.hpp"

namespace sigmatau {
namespace {

using detail::make_value;

/// Two gravity directions closer than this [rad] are the same orientation (10 deg: positions of
/// a hand-held calibration differ by tens of degrees; re-placements of one face by a few).
const double kDistinctAngle = 10.0 * std::numbers::pi / 180;
/// Smallest eigenvalue of the directions' scatter matrix (mean of d d^T, trace 1) accepted:
/// uniformly spread directions give 1/3; 0.02 means an rms out-of-plane component of 8 deg,
/// below which the component normal to the plane (or cone axis) is barely excited.
constexpr double kMinScatterEigenvalue = 0.02;
/// The static accelerometer magnitude must be within this fraction of the gravity given
/// (larger deviations mean a wrong unit, not a scale-factor error of a working sensor).
constexpr double kMaxMagnitudeError = 0.2;
/// Chi^2/dof of the gravity-magnitude fit above which the log is refused as not static: a real
/// sensor's unmodelled effects (nonlinearity, g-sensitivity) give at most a few; motion during
/// a "static" interval gives orders of magnitude more.
constexpr double kMaxStaticMisfit = 1000;

std::string direction_name(int axis, int sign) {
  return std::string(sign > 0 ? "+" : "-") + "xyz"[axis];
}

/// The half-axes never within 45 deg of a measured gravity direction.
std::string missing_directions(const std::vector<Eigen::Vector3d>& d) {
  std::string out;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign : {1, -1}) {
      bool seen = false;
      for (const auto& v : d) seen = seen || sign * v[axis] > std::sqrt(0.5);
      if (!seen) out += (out.empty() ? "" : ", ") + direction_name(axis, sign);
    }
  return out;
}

TriadCalibration accel_result(const detail::AccelFit& f, double confidence, int intervals) {
  TriadCalibration t;
  t.matrix_estimated = true;
  t.matrix = f.matrix;
  t.parameter_names = f.parameter_names;
  t.covariance = f.covariance;
  const auto se = [&](int i) { return std::sqrt(f.covariance(i, i)); };
  t.matrix_se = Eigen::Matrix3d::Constant(std::nan(""));
  const int index[3][3] = {{0, -1, -1}, {3, 1, -1}, {4, 5, 2}};
  for (int i = 0; i < 3; ++i) {
    t.scale_factor[static_cast<std::size_t>(i)] = make_value(f.params[i], se(i), confidence);
    t.bias[static_cast<std::size_t>(i)] = make_value(f.params[6 + i], se(6 + i), confidence);
    for (int j = 0; j < 3; ++j) {
      if (index[i][j] >= 0) t.matrix_se(i, j) = se(index[i][j]);
      if (i != j && index[i][j] >= 0)
        t.misalignment[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] =
            make_value(f.params[index[i][j]], se(index[i][j]), confidence);
    }
  }
  t.invariant = f.matrix * f.matrix.transpose();
  t.static_intervals = intervals;
  t.residual_rms = f.residual_rms;
  t.chi2 = f.chi2;
  t.dof = f.dof;
  t.covariance_scale = f.scale;
  return t;
}

/// Chooses the accelerometer's temperature degrees per axis (1 or 2) by AICc over all eight
/// combinations. Returns the fit and fills `axes` with each axis's two AICc values.
detail::AccelFit accel_with_temperature(const std::vector<StaticInterval>& iv, double g, double t0,
                                        std::array<BiasTemperatureAxis, 3>& axes) {
  std::array<detail::AccelFit, 8> fits;
  int best = -1;
  for (int mask = 0; mask < 8; ++mask) {
    const std::array<int, 3> deg{1 + (mask & 1), 1 + ((mask >> 1) & 1), 1 + ((mask >> 2) & 1)};
    const int params = 12 + (mask & 1) + ((mask >> 1) & 1) + ((mask >> 2) & 1);
    if (static_cast<int>(iv.size()) <= params + 1) continue;
    try {
      fits[static_cast<std::size_t>(mask)] = detail::fit_accelerometer(iv, g, t0, deg);
    } catch (const Error&) {
      continue;  // e.g. a quadratic term the temperatures cannot determine
    }
    if (best < 0 || fits[static_cast<std::size_t>(mask)].aicc < fits[static_cast<std::size_t>(best)].aicc)
      best = mask;
  }
  if (best < 0)
    throw Error("accelerometer with temperature: " + std::to_string(iv.size()) +
                " static intervals cannot determine 12 parameters (need >= 14)");
  for (int a = 0; a < 3; ++a) {
    const int lin = best & ~(1 << a), quad = best | (1 << a);
    axes[static_cast<std::size_t>(a)].aicc_linear = fits[static_cast<std::size_t>(lin)].params.size()
                                                        ? fits[static_cast<std::size_t>(lin)].aicc
                                                        : INFINITY;
    axes[static_cast<std::size_t>(a)].aicc_quadratic =
        fits[static_cast<std::size_t>(quad)].params.size() ? fits[static_cast<std::size_t>(quad)].aicc
                                                           : INFINITY;
  }
  return fits[static_cast<std::size_t>(best)];
}

void fill_accel_temperature(const detail::AccelFit& f, double confidence,
                            std::array<BiasTemperatureAxis, 3>& axes) {
  Eigen::Index k = 9;
  for (int a = 0; a < 3; ++a) {
    auto& ax = axes[static_cast<std::size_t>(a)];
    ax.degree = f.degree[static_cast<std::size_t>(a)];
    ax.linear = make_value(f.params[k], std::sqrt(f.covariance(k, k)), confidence);
    ++k;
    if (ax.degree == 2) {
      ax.quadratic = make_value(f.params[k], std::sqrt(f.covariance(k, k)), confidence);
      ++k;
    }
  }
}

void check_options(const CalibrationOptions& o) {
  if (!(o.gravity > 0) || !std::isfinite(o.gravity)) throw Error("calibrate: gravity must be > 0");
  if (!(o.confidence > 0 && o.confidence < 1))
    throw Error("calibrate: the confidence level must be in (0, 1)");
}

}  // namespace

CalibrationResult calibrate(const CalibrationInput& in, const CalibrationOptions& o) {
  check_options(o);
  checked_rate_hz(in.rate_hz, "calibrate: rate_hz");
  return detail::calibrate_samples(detail::InputSamples(in), o);
}

CalibrationResult detail::calibrate_samples(const CalibrationSamples& in,
                                            const CalibrationOptions& o) {
  check_options(o);
  CalibrationResult res;
  res.gravity = o.gravity;
  res.confidence = o.confidence;
  res.reference_temperature_k = o.reference_temperature_k;
  res.detection = detail::detect_static(in, o);
  const auto& iv = res.detection.intervals;
  char text[256];
  if (iv.empty()) {
    std::snprintf(text, sizeof text,
                  "calibrate: no static interval of at least %g s: the log seems to be moving "
                  "throughout (detector window %lld samples, threshold %g x the 25th percentile "
                  "of the window variance; %d quiet runs drifted like slow motion)",
                  o.min_interval_s, static_cast<long long>(res.detection.window_samples),
                  kStaticThresholdFactor, res.detection.rejected_moving);
    throw Error(text);
  }
  // Units and orientations.
  std::vector<double> ratios;
  std::vector<Eigen::Vector3d> d;
  for (const auto& s : iv) {
    ratios.push_back(s.accel_mean.norm() / o.gravity);
    d.push_back(s.accel_mean.normalized());
  }
  std::nth_element(ratios.begin(), ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2), ratios.end());
  const double median_ratio = ratios[ratios.size() / 2];
  if (!(std::abs(median_ratio - 1) <= kMaxMagnitudeError)) {
    std::snprintf(text, sizeof text,
                  "calibrate: the static accelerometer magnitude is %.4g x the gravity %.6g m/s^2: "
                  "are the accelerometer columns in m/s^2 (see --accel-unit)?",
                  median_ratio, o.gravity);
    throw Error(text);
  }
  std::vector<Eigen::Vector3d> centres;
  for (const auto& v : d) {
    bool known = false;
    for (const auto& c : centres) known = known || std::acos(std::clamp(v.dot(c), -1.0, 1.0)) < kDistinctAngle;
    if (!known) centres.push_back(v);
  }
  res.orientations = static_cast<int>(centres.size());
  if (res.orientations < o.min_orientations) {
    const std::string missing = missing_directions(centres);
    throw Error("calibrate: " + std::to_string(iv.size()) +
                (iv.size() == 1 ? " static interval" : " static intervals") + " but only " +
                std::to_string(res.orientations) +
                (res.orientations == 1 ? " distinct orientation" : " distinct orientations") +
                " (need >= " +
                std::to_string(o.min_orientations) + ")" +
                (missing.empty() ? std::string("; add positions between those measured")
                                 : "; gravity was never near " + missing));
  }
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& v : centres) scatter += v * v.transpose() / static_cast<double>(centres.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  if (!(eig.eigenvalues()[0] >= kMinScatterEigenvalue)) {
    const Eigen::Vector3d n = eig.eigenvectors().col(0);
    std::snprintf(text, sizeof text,
                  "calibrate: the %d orientations lie near one plane or cone: gravity hardly ever "
                  "has a component along (%.2f, %.2f, %.2f) (scatter eigenvalue %.3g < %.3g); add "
                  "positions tilted towards that axis",
                  res.orientations, n.x(), n.y(), n.z(), eig.eigenvalues()[0], kMinScatterEigenvalue);
    throw Error(text);
  }
  // Temperature.
  const double t0 = o.reference_temperature_k;
  res.has_temperature = in.has_temperature();
  bool use_temperature = false;
  if (res.has_temperature) {
    res.temperature_min_k = res.temperature_max_k = iv[0].temperature_k;
    for (const auto& s : iv) {
      res.temperature_min_k = std::min(res.temperature_min_k, s.temperature_k);
      res.temperature_max_k = std::max(res.temperature_max_k, s.temperature_k);
    }
    use_temperature = res.temperature_max_k - res.temperature_min_k >= detail::kMinTemperatureSpan;
  }
  // Accelerometer.
  detail::AccelFit accel;
  std::array<BiasTemperatureAxis, 3> accel_axes{};
  std::string accel_note;
  bool accel_temperature = false;
  if (use_temperature) {
    try {
      accel = accel_with_temperature(iv, o.gravity, t0, accel_axes);
      accel_temperature = true;
    } catch (const Error& e) {
      accel_note = e.what();
    }
  }
  if (!accel_temperature) accel = detail::fit_accelerometer(iv, o.gravity, t0, {0, 0, 0});
  if (accel.dof > 0 && accel.chi2 / accel.dof > kMaxStaticMisfit) {
    std::snprintf(text, sizeof text,
                  "calibrate: the gravity-magnitude fit leaves residuals %.3g times their noise "
                  "(chi^2/dof = %.3g): the \"static\" intervals are moving, or this is not a "
                  "multi-position log",
                  std::sqrt(accel.chi2 / accel.dof), accel.chi2 / accel.dof);
    throw Error(text);
  }
  res.accel = accel_result(accel, o.confidence, static_cast<int>(iv.size()));
  if (accel_temperature) {
    fill_accel_temperature(accel, o.confidence, accel_axes);
    res.accel.temperature = accel_axes;
  }
  res.accel.note = accel_note;
  if (!in.has_gyro()) return res;

  // Gyroscope: a first bias model with G = I, the matrix from the rotations (which needs the
  // bias to separate it from the Earth rate in each static reading), then the final bias model.
  TriadCalibration gyro;
  gyro.static_intervals = static_cast<int>(iv.size());
  const Eigen::Matrix3d ainv = accel.matrix.inverse();
  std::vector<double> x;
  std::vector<Eigen::Vector3d> down;
  for (const auto& s : iv) {
    x.push_back(s.temperature_k - t0);
    down.push_back(-(ainv * (s.accel_mean - detail::accel_bias_at(accel.params, accel.degree,
                                                                  s.temperature_k, t0)))
                        .normalized());
  }
  // The Earth rate in each interval: the intervals' attitudes relative to the first, chained
  // from the integrated rotations, carry one unknown Earth rate w_0 into every interval
  // (calibrate_earth_rate.cpp). First pass: G = I and each whole reading as the bias in the
  // integration (the Earth rate ignored across a rotation: an attitude error of ~Omega times the
  // rotation's duration, ~1e-4 rad, which moves the projected Earth rate by ~1e-8 rad/s).
  std::vector<Eigen::Vector3d> readings;
  for (const auto& s : iv) readings.push_back(s.gyro_mean);
  Eigen::Matrix3d g = Eigen::Matrix3d::Identity();
  const detail::GyroBiasFit first =
      detail::fit_gyro_bias(iv, down, detail::interval_attitudes(in, iv, g, readings), g,
                            o.latitude_rad, x, use_temperature);
  std::vector<Eigen::Vector3d> interval_bias;
  for (double dt : x) interval_bias.push_back(first.at(dt));
  Eigen::MatrixXd gcov = Eigen::MatrixXd::Zero(9, 9);
  try {
    const detail::GyroMatrixFit f = detail::fit_gyroscope_matrix(in, iv, accel, t0, interval_bias,
                                                                 o.rotation_memory_bytes);
    g = f.matrix;
    gcov = f.covariance;
    gyro.matrix_estimated = true;
    gyro.rotations = f.rotations;
    gyro.residual_rms = f.residual_rms;
    gyro.chi2 = f.chi2;
    gyro.dof = f.dof;
    gyro.covariance_scale = f.scale;
  } catch (const Error& e) {
    gyro.note = e.what();
  }
  gyro.matrix = g;
  gyro.matrix_se = Eigen::Matrix3d::Constant(std::nan(""));
  if (gyro.matrix_estimated) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const double se = std::sqrt(gcov(3 * i + j, 3 * i + j));
        gyro.matrix_se(i, j) = se;
        if (i == j)
          gyro.scale_factor[static_cast<std::size_t>(i)] = make_value(g(i, i) - 1, se, o.confidence);
        else
          gyro.misalignment[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)] =
              make_value(g(i, j), se, o.confidence);
      }
    gyro.invariant = g * g.transpose();
  }
  const detail::GyroBiasFit final_bias = detail::fit_gyro_bias(
      iv, down, detail::interval_attitudes(in, iv, g, interval_bias), g, o.latitude_rad, x,
      use_temperature);
  if (final_bias.heading) {
    gyro.earth_rate = final_bias.earth;
    gyro.earth_rate_covariance = final_bias.earth_cov;
  }
  std::array<BiasTemperatureAxis, 3> gyro_axes = final_bias.axes;
  std::vector<std::string> bias_names;
  const double chi2_total = final_bias.chi2;
  Eigen::Index k = 0;
  for (int a = 0; a < 3; ++a) {
    const auto ua = static_cast<std::size_t>(a);
    const Eigen::VectorXd& c = final_bias.c[ua];
    const int degree = final_bias.degree[ua];
    const auto se = [&](int j) { return std::sqrt(final_bias.covariance(k + j, k + j)); };
    gyro.bias[ua] = make_value(c[0], se(0), o.confidence);
    if (use_temperature) {
      gyro_axes[ua].degree = degree;
      gyro_axes[ua].linear = make_value(c[1], se(1), o.confidence);
      if (degree == 2) gyro_axes[ua].quadratic = make_value(c[2], se(2), o.confidence);
    }
    for (int j = 0; j <= degree; ++j)
      bias_names.push_back(j == 0 ? std::string("b_") + "xyz"[a]
                                  : "c" + std::to_string(j) + "_" + "xyz"[a]);
    k += degree + 1;
  }
  if (use_temperature) gyro.temperature = gyro_axes;
  // Covariance: G's 9 entries (row-major) then the bias model (the two estimated separately; the
  // bias coefficients of the three axes are correlated through the shared Earth rate).
  const auto nb = static_cast<Eigen::Index>(bias_names.size());
  const Eigen::Index ng = gyro.matrix_estimated ? 9 : 0;
  gyro.covariance = Eigen::MatrixXd::Zero(ng + nb, ng + nb);
  if (ng) {
    gyro.covariance.topLeftCorner(9, 9) = gcov;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        gyro.parameter_names.push_back(std::string("G_") + "xyz"[i] + "xyz"[j]);
  }
  gyro.covariance.bottomRightCorner(nb, nb) = final_bias.covariance;
  for (const auto& name : bias_names) gyro.parameter_names.push_back(name);
  if (!gyro.matrix_estimated) {
    gyro.chi2 = chi2_total;
  }
  res.gyro = gyro;
  return res;
}

}  // namespace sigmatau
