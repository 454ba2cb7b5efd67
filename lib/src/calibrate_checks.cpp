// Plausibility checks of a calibration (unit mix-ups) and the notes beside its numbers
// (calibrate_checks.hpp).
//
// Glossary: u_k the calibrated gravity direction of static interval k (A^-1 (a_k - b),
// normalised); w the gyroscope rate [rad/s]; dt the sample interval [s]; "turned" the angle
// between u_k and u_k+1; "path" the sum of |w - bias| dt across the rotation between them.
#include "sigmatau/calibrate_checks.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "calibrate_internal.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/units.hpp"

namespace sigmatau {
namespace {

/// Histogram of log10 of the magnitude [m/s^2]: bins of 1e-3 over [1e-8, 1e8]; smaller values
/// (a zero row) fall into the first bin, larger into the last.
constexpr double kLogLow = -8, kLogHigh = 8, kLogStep = 1e-3;

/// Histogram of the temperature column [K]: bins of 0.1 K over [-1000 K, 2000 K] (a column in a
/// wrong unit can be anything; out-of-range values fall into the end bins).
constexpr double kTempLow = -1000, kTempHigh = 2000, kTempStep = 0.1;

/// Index of the histogram bin that holds the lower median (rank (rows + 1) / 2, 1-based) of the
/// `rows` values counted in `count`.
std::size_t lower_median_bin(const std::vector<std::int64_t>& count, std::int64_t rows) {
  const std::int64_t half = (rows + 1) / 2;
  std::int64_t seen = 0;
  std::size_t bin = 0;
  for (; bin < count.size(); ++bin) {
    seen += count[bin];
    if (seen >= half) break;
  }
  return bin;
}

/// What a temperature column below (`low`) or above the IMU range probably is.
const char* temperature_unit_advice(bool low) {
  return low ? ": is the column in degC (--temp-unit degC)?"
             : ": is the column in K (--temp-unit K) or in raw counts?";
}

std::string prefixed(const std::string& path, const std::string& text) {
  return path.empty() ? text : path + ": " + text;
}

}  // namespace

double median_accel_magnitude(const CalibrationLog& log, double rate_hz, bool increments) {
  const std::int64_t rows = log.rows();
  if (rows == 0) return 0;
  const auto bins = static_cast<std::size_t>(std::lround((kLogHigh - kLogLow) / kLogStep)) + 1;
  std::vector<std::int64_t> count(bins, 0);
  const int c = log.channels();
  const double scale = increments ? rate_hz : 1.0;
  log.read(0, rows, [&](std::int64_t, std::int64_t n, const double* v) {
    for (std::int64_t r = 0; r < n; ++r) {
      const double* row = v + r * c;
      const double m = std::hypot(row[0], row[1], row[2]) * scale;
      const double x = m > 0 ? (std::log10(m) - kLogLow) / kLogStep : 0.0;
      const auto bin = static_cast<std::size_t>(std::clamp(x, 0.0, static_cast<double>(bins - 1)));
      ++count[bin];
    }
  });
  const std::size_t bin = lower_median_bin(count, rows);
  return std::pow(10.0, kLogLow + (static_cast<double>(bin) + 0.5) * kLogStep);
}

void check_accel_unit(double median_magnitude, double gravity, const std::string& unit_given,
                      double unit_factor, bool increments, const std::string& path) {
  const double ratio = median_magnitude / gravity;
  if (ratio <= kMaxAccelMagnitudeFactor && ratio >= 1 / kMaxAccelMagnitudeFactor) return;
  // The columns' SI factor would be unit_factor / ratio; name a common unit within 20 % of it.
  std::string suggestion = ": is that their unit?";
  const std::vector<const char*> rates{"m/s^2", "g", "mg", "ug", "cm/s^2", "mm/s^2", "ft/s^2"};
  const std::vector<const char*> velocities{"m/s", "mm/s", "cm/s", "ft/s"};
  for (const char* candidate : increments ? velocities : rates) {
    const double f = parse_unit(candidate).factor;
    if (std::abs(f * ratio / unit_factor - 1) <= 0.2 && candidate != unit_given) {
      suggestion =
          std::string(": they look like ") + candidate + " (--accel-unit " + candidate + ")";
      break;
    }
  }
  char text[400];
  std::snprintf(text, sizeof text,
                "calibrate: the median accelerometer magnitude is %.4g x the gravity %.6g m/s^2 "
                "with the columns read in %s (--accel-unit %s)%s. A calibration log, mostly "
                "static, has a median within a factor %g of the gravity",
                ratio, gravity, unit_given.c_str(), unit_given.c_str(), suggestion.c_str(),
                kMaxAccelMagnitudeFactor);
  throw Error(prefixed(path, text));
}

void check_gyro_unit(const CalibrationResult& r, const std::string& unit_given,
                     const std::string& path) {
  if (!r.gyro || !r.gyro->matrix_estimated || r.gyro->dof <= 0) return;
  const TriadCalibration& g = *r.gyro;
  const double chi2_dof = g.chi2 / g.dof;
  if (!(g.residual_rms > kMaxGyroRotationMisfit && chi2_dof > kMinGyroMisfitChi2PerDof)) return;
  char text[512];
  std::snprintf(
      text, sizeof text,
      "calibrate: the gyroscope misses the rotations between the static intervals by "
      "%.3g rad (%.3g deg) rms, chi^2/dof %.3g: a working gyroscope in the right unit "
      "misses them by under %.2g rad. Are the gyro columns in %s (--gyro-unit %s; degrees "
      "read as radians turn every rotation 57 times too far)? Otherwise the gyroscope "
      "saturated during the rotations, or the sample rate is wrong (--time-column, "
      "--rate)",
      g.residual_rms, g.residual_rms * kDegreesPerRadian, chi2_dof, kMaxGyroRotationMisfit,
      unit_given.c_str(), unit_given.c_str());
  throw Error(prefixed(path, text));
}

void check_gyro_rotation_angles(const CalibrationLog& log, double rate_hz, bool increments,
                                const CalibrationResult& r, const std::string& unit_given,
                                const std::string& path) {
  if (!log.has_gyro() || !r.gyro) return;
  const auto& iv = r.detection.intervals;
  const Eigen::Matrix3d ainv = r.accel.matrix.inverse();
  const Eigen::Vector3d ab(r.accel.bias[0].value, r.accel.bias[1].value, r.accel.bias[2].value);
  const int c = log.channels();
  const double dt = 1 / rate_hz, to_rate = increments ? rate_hz : 1.0;
  int tested = 0, short_paths = 0, missed = 0;
  double worst = INFINITY;     // smallest ratio path / gravity angle
  std::vector<double> misses;  // [rad]
  for (std::size_t k = 0; k + 1 < iv.size(); ++k) {
    const Eigen::Vector3d u0 = (ainv * (iv[k].accel_mean - ab)).normalized();
    const Eigen::Vector3d u1 = (ainv * (iv[k + 1].accel_mean - ab)).normalized();
    const double turned = std::acos(std::clamp(u0.dot(u1), -1.0, 1.0));
    if (turned < kMinTestedGravityTurn || iv[k + 1].first <= iv[k].last + 1) continue;
    // The bias (and Earth rate) of the two rests, removed from each step [rad/s].
    const Eigen::Vector3d bias = (iv[k].gyro_mean + iv[k + 1].gyro_mean) / 2;
    double travelled = 0;                               // [rad]
    Eigen::Matrix3d rot = Eigen::Matrix3d::Identity();  // frame of rest k+1 in that of rest k
    log.read(iv[k].last + 1, iv[k + 1].first, [&](std::int64_t, std::int64_t n, const double* v) {
      for (std::int64_t i = 0; i < n; ++i) {
        const double* row = v + i * c;
        const Eigen::Vector3d step =
            (Eigen::Vector3d(row[3], row[4], row[5]) * to_rate - bias) * dt;  // [rad]
        travelled += step.norm();
        rot = rot * detail::exp_so3(step);
      }
    });
    ++tested;
    const double ratio = travelled / turned;
    worst = std::min(worst, ratio);
    if (ratio < kMinGyroPathRatio) ++short_paths;
    // The raw gyroscope (G = I) must carry gravity from rest k onto rest k+1.
    const double miss = std::acos(std::clamp((rot.transpose() * u0).dot(u1), -1.0, 1.0));
    misses.push_back(miss);
    if (miss > kMaxRawGyroMisfit) ++missed;
  }
  if (tested >= 3 && 2 * missed >= tested && 2 * short_paths < tested) {
    std::sort(misses.begin(), misses.end());
    char text[560];
    std::snprintf(text, sizeof text,
                  "calibrate: the gyroscope, read in %s (--gyro-unit %s), integrated across the "
                  "rotations, misses where gravity went by more than %.0f deg in %d of %d "
                  "rotations (median %.0f deg); a working gyroscope misses by its gain and "
                  "misalignment errors, a few %% of the angle. Are the gyro columns in %s "
                  "(degrees read as radians turn every rotation 57 times too far)? Otherwise the "
                  "sample rate is wrong (--time-column, --rate) or the gyroscope saturated",
                  unit_given.c_str(), unit_given.c_str(), kMaxRawGyroMisfit * kDegreesPerRadian,
                  missed, tested, misses[misses.size() / 2] * kDegreesPerRadian,
                  unit_given.c_str());
    throw Error(prefixed(path, text));
  }
  if (tested < 3 || 2 * short_paths < tested) return;
  char text[560];
  std::snprintf(
      text, sizeof text,
      "calibrate: the gyroscope, read in %s (--gyro-unit %s), turned less than %g times "
      "the angle gravity turned in the sensor frame in %d of %d rotations (down to %.3g "
      "times): a rotation cannot turn gravity further than the sensor turned. Are the "
      "gyro columns in %s (radians read as degrees give 1/57 of the angle)? Otherwise the "
      "sample rate "
      "is too high (--time-column, --rate) or the gyroscope saturated",
      unit_given.c_str(), unit_given.c_str(), kMinGyroPathRatio, short_paths, tested, worst,
      unit_given.c_str());
  throw Error(prefixed(path, text));
}

double median_temperature_k(const CalibrationLog& log) {
  const std::int64_t rows = log.rows();
  if (!log.has_temperature() || rows == 0) return 0;
  const auto bins = static_cast<std::size_t>(std::lround((kTempHigh - kTempLow) / kTempStep)) + 1;
  std::vector<std::int64_t> count(bins, 0);
  const int c = log.channels();
  log.read(0, rows, [&](std::int64_t, std::int64_t n, const double* v) {
    for (std::int64_t r = 0; r < n; ++r) {
      const double x = (v[r * c + c - 1] - kTempLow) / kTempStep;
      ++count[static_cast<std::size_t>(std::clamp(x, 0.0, static_cast<double>(bins - 1)))];
    }
  });
  const std::size_t bin = lower_median_bin(count, rows);
  return kTempLow + (static_cast<double>(bin) + 0.5) * kTempStep;
}

void check_temperature_unit(double median_k, const std::string& unit_given,
                            const std::string& path) {
  if (median_k >= kMinImuTemperatureK && median_k <= kMaxImuTemperatureK) return;
  const bool low = median_k < kMinImuTemperatureK;
  char text[512];
  std::snprintf(text, sizeof text,
                "calibrate: the temperature column, read in %s (--temp-unit %s), has a median of "
                "%.4g K (%.4g degC), %s any IMU's range (%g K to %g K)%s",
                unit_given.c_str(), unit_given.c_str(), median_k, median_k - 273.15,
                low ? "below" : "above", kMinImuTemperatureK, kMaxImuTemperatureK,
                temperature_unit_advice(low));
  throw Error(prefixed(path, text));
}

void check_temperature_unit(const CalibrationResult& r, const std::string& unit_given,
                            const std::string& path) {
  if (!r.has_temperature) return;
  const bool low = r.temperature_min_k < kMinImuTemperatureK;
  const bool high = r.temperature_max_k > kMaxImuTemperatureK;
  if (!low && !high) return;
  char text[512];
  std::snprintf(text, sizeof text,
                "calibrate: the temperature column, read in %s (--temp-unit %s), gives %.5g K to "
                "%.5g K (%.5g to %.5g degC) over the static intervals, %s any IMU's range "
                "(%g K to %g K)%s",
                unit_given.c_str(), unit_given.c_str(), r.temperature_min_k, r.temperature_max_k,
                r.temperature_min_k - 273.15, r.temperature_max_k - 273.15, low ? "below" : "above",
                kMinImuTemperatureK, kMaxImuTemperatureK,
                temperature_unit_advice(low));
  throw Error(prefixed(path, text));
}

double mean_interval_temperature_k(const CalibrationResult& r) {
  if (!r.has_temperature || r.detection.intervals.empty()) return 0;
  double sum = 0;
  for (const auto& s : r.detection.intervals) sum += s.temperature_k;
  return sum / static_cast<double>(r.detection.intervals.size());
}

std::vector<std::string> calibration_notes(const CalibrationResult& r) {
  std::vector<std::string> notes;
  const double span = r.temperature_max_k - r.temperature_min_k;
  const auto triad = [&](const TriadCalibration& t, const char* name) {
    if (!t.matrix_estimated)
      notes.push_back(std::string(name) + ": matrix not estimated, only the bias: " + t.note);
    // As many parameters as equations: the fit passes through the data, the residuals cannot
    // test the model, and the intervals rest on the noise alone (6 faces + 3 in one plane gave
    // cross-axis intervals of +-370 % and no word).
    if (t.matrix_estimated && t.dof <= 0)
      notes.push_back(std::string(name) + ": the fit has " + std::to_string(t.dof) +
                      " degrees of freedom (as many parameters as equations): its residuals "
                      "cannot test the model; rest the IMU in more orientations");
    if (!r.has_temperature || t.temperature) return;
    char reason[160];
    if (span < detail::kMinTemperatureSpan)
      std::snprintf(reason, sizeof reason,
                    "the static intervals span only %.3g K of temperature (under %g K)", span,
                    detail::kMinTemperatureSpan);
    const std::string why = span < detail::kMinTemperatureSpan ? std::string(reason)
                            : t.matrix_estimated && !t.note.empty()
                                ? t.note
                                : std::string("the static intervals do not determine it");
    char where[160];
    std::snprintf(where, sizeof where,
                  "its bias holds at the log's mean temperature %.2f degC, not at T0 = %.2f degC",
                  mean_interval_temperature_k(r) - 273.15, r.reference_temperature_k - 273.15);
    std::string note = std::string(name) + ": no bias temperature model (" + why + "); " + where;
    if (span >= detail::kMinTemperatureSpan) {
      std::snprintf(where, sizeof where,
                    "; its drift over the %.3g K the log spans stays in the residuals and can "
                    "pull the other parameters",
                    span);
      note += where;
    }
    notes.push_back(note);
  };
  triad(r.accel, "accelerometer");
  if (r.gyro) triad(*r.gyro, "gyroscope");
  return notes;
}

}  // namespace sigmatau
