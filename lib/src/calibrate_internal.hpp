#pragma once
// Internal pieces of the calibration (calibrate.hpp): the Levenberg-Marquardt solver, the
// accelerometer and gyroscope fits and the temperature regression.
#include <Eigen/Core>

#include <functional>
#include <string>
#include <vector>

#include "sigmatau/calibrate.hpp"

namespace sigmatau::detail {

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
/// static reading is the Earth rate, which turns with the body during a rotation.
GyroMatrixFit fit_gyroscope_matrix(const CalibrationInput& input,
                                   const std::vector<StaticInterval>& intervals,
                                   const AccelFit& accel, double reference_temperature_k,
                                   const std::vector<Eigen::Vector3d>& interval_bias);

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
