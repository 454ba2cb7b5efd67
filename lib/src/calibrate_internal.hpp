#pragma once
// Internal pieces of the calibration (calibrate.hpp): the Levenberg-Marquardt solver, the
// accelerometer and gyroscope fits and the temperature regression.
#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sigmatau/calibrate.hpp"
#include "sigmatau/calibrate_log.hpp"

namespace sigmatau::detail {

/// Channel order of a calibration row: ax, ay, az, gx, gy, gz, temperature.
inline constexpr int kAccelChannel = 0, kGyroChannel = 3, kTemperatureChannel = 6;

/// Temperature span of the static intervals [K] below which no temperature dependence is fitted
/// (the coefficient would be an extrapolation of noise); the notes (calibrate_checks.cpp) say so.
inline constexpr double kMinTemperatureSpan = 1.0;

/// Consecutive rows of a calibration log: value(c, r) is channel c of row first + r, as stored
/// (rates or increments in SI, temperature in K).
struct SampleRows {
  std::int64_t first = 0;
  std::int64_t count = 0;
  std::array<const double*, 7> column{};  ///< nullptr for a channel the log does not have
  std::ptrdiff_t stride = 1;              ///< between rows [values]
  double value(int channel, std::int64_t r) const {
    return column[static_cast<std::size_t>(channel)][r * stride];
  }
};

/// The samples the calibration reads, as often as it needs, in row order: the vectors of a
/// CalibrationInput or a CalibrationLog (in memory or in its temporary file).
class CalibrationSamples {
 public:
  virtual ~CalibrationSamples() = default;
  virtual std::int64_t rows() const = 0;
  virtual bool has_gyro() const = 0;
  virtual bool has_temperature() const = 0;
  virtual double rate_hz() const = 0;
  virtual bool increments() const = 0;
  /// Calls each() on consecutive pieces that together cover rows [begin, end).
  virtual void for_each(std::int64_t begin, std::int64_t end,
                        const std::function<void(const SampleRows&)>& each) const = 0;
};

/// CalibrationInput's vectors as CalibrationSamples (no copy). Throws Error when the channels
/// have unequal lengths (the same messages as before).
class InputSamples final : public CalibrationSamples {
 public:
  explicit InputSamples(const CalibrationInput& input);
  std::int64_t rows() const override;
  bool has_gyro() const override { return !in_.gyro[0].empty(); }
  bool has_temperature() const override { return !in_.temperature_k.empty(); }
  double rate_hz() const override { return in_.rate_hz; }
  bool increments() const override { return in_.increments; }
  void for_each(std::int64_t begin, std::int64_t end,
                const std::function<void(const SampleRows&)>& each) const override;

 private:
  const CalibrationInput& in_;
};

/// A CalibrationLog with its rate as CalibrationSamples.
class LogSamples final : public CalibrationSamples {
 public:
  LogSamples(const CalibrationLog& log, double rate_hz, bool increments)
      : log_(log), rate_hz_(rate_hz), increments_(increments) {}
  std::int64_t rows() const override { return log_.rows(); }
  bool has_gyro() const override { return log_.has_gyro(); }
  bool has_temperature() const override { return log_.has_temperature(); }
  double rate_hz() const override { return rate_hz_; }
  bool increments() const override { return increments_; }
  void for_each(std::int64_t begin, std::int64_t end,
                const std::function<void(const SampleRows&)>& each) const override;

 private:
  const CalibrationLog& log_;
  double rate_hz_;
  bool increments_;
};

/// detect_static_intervals over any samples (calibrate_detect.cpp).
StaticDetection detect_static(const CalibrationSamples& samples, const CalibrationOptions& options);

/// calibrate over any samples (calibrate.cpp).
CalibrationResult calibrate_samples(const CalibrationSamples& samples,
                                    const CalibrationOptions& options);

/// The detector's window statistic as the rows stream past (calibrate_window.cpp): for sample i,
/// the sum over three axes of the variance of samples i-h..i+h (w = 2h+1 odd), from running sums
/// centred on each axis's first value, in the same order of operations as over the whole log.
class WindowStatistic {
 public:
  explicit WindowStatistic(std::int64_t w);
  /// Feeds the next sample (three axes). Returns true when the statistic of sample
  /// pushed() - 1 - h is complete (then value() holds it).
  bool push(const double* v, std::ptrdiff_t stride);
  double value() const { return value_; }

 private:
  std::int64_t w_, pushed_ = 0;
  std::array<double, 3> centre_{}, s1_{}, s2_{};
  std::vector<std::array<double, 6>> ring_;  // prefix sums s1, s2 of the last w+1 prefixes
  double value_ = 0;
};

/// The exact k-th smallest of a stream of non-negative doubles, k = floor(q (n-1)) of the n
/// non-NaN values, in bounded memory: each pass either collects the values that share the
/// candidates' leading bits (when few enough) or histograms their next bits (calibrate_window.cpp).
/// The bit patterns of non-negative doubles sort like their values, so the result is the value
/// std::nth_element would give.
class StreamQuantile {
 public:
  /// q in [0, 1]; `expected` values per pass (n if known, to collect at once when small).
  StreamQuantile(double q, std::int64_t expected);
  void add(double v);
  /// Ends a pass; returns true when the quantile is known (value(); NaN without values).
  bool end_pass();
  bool done() const { return done_; }
  double value() const { return value_; }

 private:
  double q_;
  std::int64_t count_ = 0;      // non-NaN values of the first pass
  bool first_pass_ = true;
  std::int64_t k_ = 0;          // rank within the current prefix group
  std::int64_t group_ = 0;      // values in the current prefix group (or expected)
  std::uint64_t prefix_ = 0;
  int prefix_bits_ = 0, bits_ = 0;  // leading bits fixed; bits histogrammed this pass
  bool collecting_ = false, done_ = false;
  std::vector<std::int64_t> histogram_;
  std::vector<double> collected_;
  double value_ = 0;
  void start_pass();
};

/// Whitened residuals r(p) (each of unit variance under the noise model).
using Residuals = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

struct LmResult {
  Eigen::VectorXd p;
  Eigen::MatrixXd jacobian;  ///< of the whitened residuals at p
  double chi2 = 0;
  int iterations = 0;
};

/// Central-difference Jacobian with absolute step `step` on every parameter.
Eigen::MatrixXd numeric_jacobian(const Residuals& r, const Eigen::VectorXd& p, double step);

/// Levenberg-Marquardt (Marquardt's diagonal scaling) from p0; stops when the relative chi^2
/// decrease and the step are below 1e-12 or after 100 iterations.
LmResult levenberg_marquardt(const Residuals& r, const Eigen::VectorXd& p0, double step);

/// Inverse of J^T J; throws Error naming `what` when its column-scaled condition number exceeds
/// kMaxCondition (the data do not determine every parameter).
Eigen::MatrixXd covariance_of(const Eigen::MatrixXd& jacobian, const std::string& what);

/// Condition number of the column-scaled normal matrix above which a fit is refused: beyond
/// 1e10, double-precision normal equations lose every significant digit of the weakest
/// combination (1e16 / 1e10 leaves 6 digits at best for the others).
inline constexpr double kMaxCondition = 1e10;

/// chi^2 inflation: returns chi2/dof when chi2 exceeds the 99% quantile of chi^2(dof), else 1.
double covariance_scale(double chi2, int dof);

/// Fills a CalibratedValue from value and standard error at the two-sided `confidence`.
CalibratedValue make_value(double value, double se, double confidence);

/// The accelerometer's bias temperature model: per axis the degree (0: no temperature terms).
struct AccelFit {
  Eigen::Matrix3d matrix;        // lower-triangular A
  Eigen::Vector3d bias;          // b0
  Eigen::VectorXd params;        // all parameters (see parameter_names)
  Eigen::MatrixXd covariance;
  std::vector<std::string> parameter_names;
  std::array<int, 3> degree{};   // temperature degree per axis
  double chi2 = 0;
  int dof = 0;
  double residual_rms = 0;
  double scale = 1;
  double aicc = 0;
};

/// Fits the accelerometer on the intervals; `degree` per axis (0 without temperature).
AccelFit fit_accelerometer(const std::vector<StaticInterval>& intervals, double gravity,
                           double reference_temperature_k, const std::array<int, 3>& degree);

/// The accelerometer's bias at temperature T [m/s^2] for parameters p.
Eigen::Vector3d accel_bias_at(const Eigen::VectorXd& p, const std::array<int, 3>& degree,
                              double temperature_k, double reference_temperature_k);
/// Lower-triangular A from parameters p (the first six: s_x, s_y, s_z, m_yx, m_zx, m_zy).
Eigen::Matrix3d accel_matrix(const Eigen::VectorXd& p);

/// The gyroscope's rotation fit: G = I + T_g (row-major 9 parameters), covariance including the
/// accelerometer fit's uncertainty. Throws Error when the rotations do not determine G.
struct GyroMatrixFit {
  Eigen::Matrix3d matrix = Eigen::Matrix3d::Identity();
  Eigen::MatrixXd covariance;
  int rotations = 0;
  double chi2 = 0;
  int dof = 0;
  double residual_rms = 0;  // [rad]
  double scale = 1;
};
/// `interval_bias` is the gyroscope bias at each interval (a first bias model): the rest of each
/// static reading is the Earth rate, which turns with the body during a rotation. Only the samples
/// of the rotations are read; their integration steps are kept in memory up to
/// `step_memory_bytes`, beyond in a temporary file.
GyroMatrixFit fit_gyroscope_matrix(const CalibrationSamples& samples,
                                   const std::vector<StaticInterval>& intervals,
                                   const AccelFit& accel, double reference_temperature_k,
                                   const std::vector<Eigen::Vector3d>& interval_bias,
                                   std::int64_t step_memory_bytes);

/// The rotation matrix of rotation vector v (angle |v| [rad] about v / |v|); I for |v| < 1e-300.
Eigen::Matrix3d exp_so3(const Eigen::Vector3d& v);

/// Calls step(dz) for each integration step of the gyroscope from the last sample of interval a
/// to the first of interval b: rate samples by the trapezoid, or the increments in between, less
/// the bias interpolated linearly in time from ba (at a's centre) to bb (at b's) [rad, raw axes].
void rotation_steps(const CalibrationSamples& samples, const StaticInterval& a,
                    const StaticInterval& b, const Eigen::Vector3d& ba, const Eigen::Vector3d& bb,
                    const std::function<void(const Eigen::Vector3d&)>& step);

/// Attitude C_k of every static interval relative to the first (C_0 = I; a vector v_k in the
/// frame of interval k is C_k v_k in the frame of interval 0), chained from the calibrated
/// rotations R_k between consecutive intervals, relative to the local level, as in
/// fit_gyroscope_matrix: C_{k+1} = C_k R_k. `g` the gyroscope matrix, `interval_bias` the bias
/// at each interval [rad/s].
std::vector<Eigen::Matrix3d> interval_attitudes(const CalibrationSamples& samples,
                                                const std::vector<StaticInterval>& intervals,
                                                const Eigen::Matrix3d& g,
                                                const std::vector<Eigen::Vector3d>& interval_bias);

/// The gyroscope's bias model (calibrate_earth_rate.cpp): per axis b0 [+ c1 dT [+ c2 dT^2]]
/// (rad/s, rad/s/K, rad/s/K^2), fitted to the static readings together with the Earth rate.
struct GyroBiasFit {
  /// true: the Earth rate of interval k is G C_k^T w_0 with w_0 (the Earth rate in the frame of
  /// interval 0) estimated; false: its horizontal part (all of it without a latitude) entered
  /// each interval's variance as independent noise.
  bool heading = false;
  std::array<int, 3> degree{};
  std::array<Eigen::VectorXd, 3> c;  ///< per axis: b0, c1, c2 up to its degree
  /// Of the coefficients in the order x (b0, c1, ...), y, z, after the chi^2 scale.
  Eigen::MatrixXd covariance;
  std::array<BiasTemperatureAxis, 3> axes{};  ///< AICc values (with temperature)
  Eigen::Vector3d earth = Eigen::Vector3d::Zero();      ///< w_0 [rad/s] (heading)
  Eigen::Matrix3d earth_cov = Eigen::Matrix3d::Zero();  ///< its covariance [(rad/s)^2]
  double chi2 = 0;
  /// The bias at temperature offset dt = T - T0 [rad/s].
  Eigen::Vector3d at(double dt) const;
};

/// Fits the gyroscope bias on the static intervals. `down` the calibrated unit down direction per
/// interval, `attitude` the C_k of interval_attitudes (empty: the Earth rate as noise), `dt` the
/// intervals' T - T0 [K], `temperature` whether to fit the temperature terms (degrees chosen by
/// AICc). Falls back to the noise model when the heading model cannot be determined.
GyroBiasFit fit_gyro_bias(const std::vector<StaticInterval>& intervals,
                          const std::vector<Eigen::Vector3d>& down,
                          const std::vector<Eigen::Matrix3d>& attitude, const Eigen::Matrix3d& g,
                          const std::optional<double>& latitude_rad, const std::vector<double>& dt,
                          bool temperature);

/// Weighted polynomial regression y_k = sum_d c_d x_k^d (d = 0..degree) with known variances;
/// returns coefficients, their covariance and chi^2.
struct PolyFit {
  Eigen::VectorXd c;
  Eigen::MatrixXd covariance;
  double chi2 = 0;
};
PolyFit weighted_polynomial(const std::vector<double>& x, const std::vector<double>& y,
                            const std::vector<double>& variance, int degree);

/// AICc = chi^2 + 2p + 2p(p+1)/(n-p-1) (infinite when n <= p + 1).
double aicc(double chi2, int parameters, int observations);

}  // namespace sigmatau::detail
