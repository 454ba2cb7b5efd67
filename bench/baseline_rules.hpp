#pragma once
/// \file baseline_rules.hpp
/// The noise-term read-outs of three widely used tools, re-implemented from the description of
/// their rules (not their code) for bench_fit_baselines. Each function takes the tool's own
/// Allan deviation curve (its tau grid and estimator, built with the factor lists below) and
/// returns what the tool reports, in the curve's unit. Sources (read 2026-11-24 in the stored
/// copies of the repositories and documentation):
///  - MATLAB, "Inertial Sensor Noise Analysis Using Allan Variance" (Navigation / Sensor Fusion
///    Toolbox example, the page that documents allanvar's use for N, B, K): overlapping AVAR at
///    m = unique(ceil(logspace(0, log10(2^floor(log2(L/2))), 100))); for a slope s, the first
///    segment whose log-log slope is closest to s, the line of slope s through its left point;
///    N = line at tau = 1 s (s = -1/2), K = line at tau = 3 s (s = +1/2), B = line (s = 0)
///    / sqrt(2 ln 2 / pi).
///  - gaowenliang/imu_utils (src/gyr_lib/allan_gyr.cpp @7262b35, fitallan_gyr.{h,cpp} @2cdda91,
///    src/acc_lib/fitallan_acc.h @41520b7, launch/*.launch max_cluster = 100): overlapping AVAR at
///    100 log-spaced factors 1 .. largest power of 2 <= L/2 (ceil, consecutive duplicates
///    dropped); least squares (Ceres, dogleg, unweighted) of log(model AVAR) - log(AVAR) with
///    model Q^2/tau^2 + N^2/tau + B^2 + K^2 tau + R^2 tau^2, started from |c| of a linear least
///    squares of the ADEV on tau^(k/2), k = -2..2. Printed: N, B / 0.6642824703, sqrt(3) K,
///    Q / sqrt(3); written to the yaml: gyr_n = sqrt(rate) x model ADEV(1 s) and gyr_w = the
///    smallest model ADEV over the grid. The accelerometer first drops each point below 1 s
///    whose AVAR exceeds all earlier ones (so always the first point).
///  - ori-drs/allan_variance_ros (src/AllanVarianceComputor.cpp @0ef9204, scripts/analysis.py
///    @0817896 and @23599fa, identical rules): non-overlapping AVAR of consecutive bins of
///    int(0.1 p x rate) samples (a last partial bin dropped) at tau = 0.1 p s, p = 1..9999;
///    a line in ln-ln of slope in [-0.5, -0.499] fitted to the points with tau < 10 s, read at
///    tau = 1 s (white noise); a line of slope in [0.5, 0.501] fitted to all points, read at
///    tau = 3 s (random walk); bias instability = the smallest ADEV (no 0.664 factor).
///
/// Glossary: tau averaging time [s]; m averaging factor (tau = m tau0); L samples in the log;
/// adev Allan deviation in the signal's unit (rad/s or m/s^2 here); N, B, K, Q as in
/// noise_model.hpp (SI, continuous-time).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include <Eigen/Dense>

namespace sigmatau::bench {

/// sqrt(2 ln 2 / pi): the ADEV floor of flicker noise per unit B (IEEE 952), as MATLAB's
/// example writes it.
inline const double kMatlabFloorFactor = std::sqrt(2 * std::log(2.0) / std::numbers::pi);
/// The same factor as imu_utils hard-codes it (fitallan_gyr.cpp, getB).
inline constexpr double kImuUtilsFloorFactor = 0.6642824703;
/// Clusters in imu_utils' tau grid (max_cluster in every launch file it ships).
inline constexpr int kImuUtilsClusters = 100;
/// Points in the MATLAB example's tau grid (maxNumM).
inline constexpr int kMatlabPoints = 100;
/// allan_variance_ros: periods p = 1..kRosPeriods-1, tau = kRosPeriodStep_s p.
inline constexpr int kRosPeriods = 10000;
inline constexpr double kRosPeriodStep_s = 0.1;
/// allan_variance_ros fits the white-noise line to tau below this [s] (the row where period
/// == 10 ends the slice).
inline constexpr double kRosWhiteBreak_s = 10.0;
/// Width of the slope bounds in allan_variance_ros' curve_fit call.
inline constexpr double kRosSlopeSlack = 0.001;

/// What one tool reports for one channel, SI. NaN where the tool reports nothing.
struct BaselineEstimate {
  double quantization = std::numeric_limits<double>::quiet_NaN();      ///< Q
  double white = std::numeric_limits<double>::quiet_NaN();             ///< N
  double bias_instability = std::numeric_limits<double>::quiet_NaN();  ///< B (flicker coeff.)
  double rate_random_walk = std::numeric_limits<double>::quiet_NaN();  ///< K
  /// The ADEV floor the tool reports as "bias instability" where it reports one (ros: the
  /// smallest ADEV; imu_utils: gyr_w, the smallest model ADEV) [signal unit].
  double floor = std::numeric_limits<double>::quiet_NaN();
  /// imu_utils only: the model ADEV at 1 s (its yaml gyr_n / sqrt(rate)) [signal unit].
  double adev_1s = std::numeric_limits<double>::quiet_NaN();
  int iterations = 0;  ///< imu_utils only: solver iterations used
};

/// MATLAB example grid: unique(ceil(logspace(0, log10(2^floor(log2(L/2))), 100))).
inline std::vector<std::int64_t> matlab_example_factors(std::int64_t samples) {
  const double max_m = std::exp2(std::floor(std::log2(static_cast<double>(samples) / 2)));
  std::vector<std::int64_t> m;
  for (int i = 0; i < kMatlabPoints; ++i) {
    const double e = std::log10(max_m) * i / (kMatlabPoints - 1);
    const auto f = static_cast<std::int64_t>(std::ceil(std::pow(10.0, e) - 1e-9 * std::pow(10.0, e)));
    if (m.empty() || f != m.back()) m.push_back(std::max<std::int64_t>(f, 1));
  }
  return m;
}

/// imu_utils grid: a geometric progression of kImuUtilsClusters values from 1 to the largest
/// power of 2 <= L/2 (each the previous times the ratio), ceil, consecutive duplicates dropped.
inline std::vector<std::int64_t> imu_utils_factors(std::int64_t samples) {
  std::int64_t half = samples / 2, max_stride = 1;
  for (int shift = 0; half; ++shift) {
    half >>= 1;
    max_stride = std::int64_t{1} << shift;
  }
  // The tool passes log10(max_stride) and the exponent 1 / (clusters - 1) as float.
  const double ratio = std::pow(static_cast<double>(std::pow(10.0f, std::log10(static_cast<float>(max_stride)))),
                                static_cast<double>(1.0f / (kImuUtilsClusters - 1)));
  std::vector<std::int64_t> m;
  double value = 1;
  for (int i = 0; i < kImuUtilsClusters; ++i, value *= ratio) {
    const auto f = static_cast<std::int64_t>(std::ceil(value));
    if (m.empty() || f != m.back()) m.push_back(f);
  }
  return m;
}

/// allan_variance_ros grid: bin sizes int(0.1 p x rate) for p = 1..9999 (the tau it records is
/// 0.1 p whatever the truncation); entries with a bin of 0 samples are skipped.
struct RosGrid {
  std::vector<std::int64_t> m;
  std::vector<double> tau_s;
};
inline RosGrid allan_variance_ros_grid(double rate_hz) {
  RosGrid g;
  for (int p = 1; p < kRosPeriods; ++p) {
    const double period_s = p * kRosPeriodStep_s;
    const auto bin = static_cast<std::int64_t>(period_s * rate_hz);
    if (bin < 1) continue;
    g.m.push_back(bin);
    g.tau_s.push_back(period_s);
  }
  return g;
}

/// The MATLAB example's read-outs from an ADEV curve (tau ascending, adev > 0).
inline BaselineEstimate matlab_example_rule(const std::vector<double>& tau,
                                            const std::vector<double>& adev) {
  const std::size_t n = tau.size();
  std::vector<double> lt(n), la(n), slope(n - 1);
  for (std::size_t i = 0; i < n; ++i) {
    lt[i] = std::log10(tau[i]);
    la[i] = std::log10(adev[i]);
  }
  for (std::size_t i = 0; i + 1 < n; ++i) slope[i] = (la[i + 1] - la[i]) / (lt[i + 1] - lt[i]);
  // Intercept (log10 at tau = 1 s) of the line of slope s through the first segment whose
  // slope is closest to s.
  const auto intercept = [&](double s) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < slope.size(); ++i) {
      if (std::abs(slope[i] - s) < std::abs(slope[best] - s)) best = i;
    }
    return la[best] - s * lt[best];
  };
  BaselineEstimate e;
  e.white = std::pow(10.0, intercept(-0.5));
  e.rate_random_walk = std::pow(10.0, 0.5 * std::log10(3.0) + intercept(0.5));
  e.bias_instability = std::pow(10.0, intercept(0.0) - std::log10(kMatlabFloorFactor));
  return e;
}

/// Least squares line y = s x + b with s constrained to [s_lo, s_hi] (the cost is quadratic in
/// s once b is profiled out, so the constrained optimum is the clamped free one).
inline std::pair<double, double> bounded_slope_line(const std::vector<double>& x,
                                                    const std::vector<double>& y, double s_lo,
                                                    double s_hi) {
  const double n = static_cast<double>(x.size());
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    mx += x[i] / n;
    my += y[i] / n;
  }
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
  }
  const double s = std::clamp(sxx > 0 ? sxy / sxx : s_lo, s_lo, s_hi);
  return {s, my - s * mx};
}

/// allan_variance_ros' read-outs (scripts/analysis.py) from its ADEV table.
inline BaselineEstimate allan_variance_ros_rule(const std::vector<double>& tau,
                                                const std::vector<double>& adev) {
  std::vector<double> lx, ly, wx, wy;
  for (std::size_t i = 0; i < tau.size(); ++i) {
    lx.push_back(std::log(tau[i]));
    ly.push_back(std::log(adev[i]));
    if (tau[i] < kRosWhiteBreak_s - 1e-9) {
      wx.push_back(lx.back());
      wy.push_back(ly.back());
    }
  }
  BaselineEstimate e;
  const auto [sw, bw] = bounded_slope_line(wx, wy, -0.5, -0.5 + kRosSlopeSlack);
  e.white = std::exp(bw + sw * std::log(1.0));
  const auto [sk, bk] = bounded_slope_line(lx, ly, 0.5, 0.5 + kRosSlopeSlack);
  e.rate_random_walk = std::exp(bk + sk * std::log(3.0));
  e.floor = *std::min_element(adev.begin(), adev.end());
  return e;
}

/// imu_utils' fit (FitAllanGyr / FitAllanAcc) of an OAVAR curve given as ADEV [signal unit]
/// at tau [s]. `tool_unit` is what one signal unit is in the tool's units (gyro: 57.3 x 3600,
/// deg/h per rad/s; accelerometer: 1). The solver is a Levenberg-Marquardt with Marquardt's
/// diagonal scaling and Ceres' default stopping rules (50 iterations, relative cost change
/// 1e-6, gradient 1e-10, step 1e-8), not Ceres' dogleg: same cost, same start.
inline BaselineEstimate imu_utils_rule(std::vector<double> tau, const std::vector<double>& adev,
                                       bool accelerometer, double tool_unit) {
  std::vector<double> s2;
  {
    std::vector<double> kept_tau;
    double running_max = 0;
    for (std::size_t i = 0; i < tau.size(); ++i) {
      const double v = adev[i] * adev[i] * tool_unit * tool_unit;
      if (accelerometer && tau[i] < 1) {
        if (running_max < v) {
          running_max = v;
          continue;
        }
      }
      s2.push_back(v);
      kept_tau.push_back(tau[i]);
    }
    tau = kept_tau;
  }
  const auto n = static_cast<Eigen::Index>(tau.size());
  // Start: |c| of the least squares ADEV ~ sum_k c_k tau^(k/2), k = -2..2 (normal equations,
  // inverted as the tool does).
  Eigen::MatrixXd f(n, 5);
  Eigen::VectorXd y(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    y(i) = std::sqrt(s2[static_cast<std::size_t>(i)]);
    for (int k = 0; k < 5; ++k) f(i, k) = std::pow(std::sqrt(tau[static_cast<std::size_t>(i)]), k - 2);
  }
  const Eigen::MatrixXd a = f.transpose() * f;
  Eigen::VectorXd p = (a.inverse() * (f.transpose() * y)).cwiseAbs();

  const auto basis = [](double t) {
    return Eigen::Matrix<double, 5, 1>(1 / (t * t), 1 / t, 1, t, t * t);
  };
  const auto model = [&](const Eigen::VectorXd& q, double t) {
    return basis(t).dot(q.cwiseProduct(q));
  };
  const auto residuals = [&](const Eigen::VectorXd& q) {
    Eigen::VectorXd r(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const auto ii = static_cast<std::size_t>(i);
      r(i) = std::log10(model(q, tau[ii])) - std::log10(s2[ii]);
    }
    return r;
  };
  Eigen::VectorXd r = residuals(p);
  double cost = 0.5 * r.squaredNorm();
  double lambda = 1e-4;  // Ceres' initial trust radius 1e4 corresponds to a small damping
  int it = 0;
  bool converged = false;
  for (; it < 50 && !converged; ++it) {
    Eigen::MatrixXd j(n, 5);
    for (Eigen::Index i = 0; i < n; ++i) {
      const double t = tau[static_cast<std::size_t>(i)];
      const double m = model(p, t);
      const auto g = basis(t);
      for (int k = 0; k < 5; ++k) j(i, k) = 2 * p(k) * g(k) / (m * std::log(10.0));
    }
    const Eigen::VectorXd grad = j.transpose() * r;
    if (grad.lpNorm<Eigen::Infinity>() <= 1e-10) break;
    const Eigen::MatrixXd jtj = j.transpose() * j;
    bool stepped = false;
    for (int attempt = 0; attempt < 30 && !stepped; ++attempt) {
      Eigen::MatrixXd damped = jtj;
      for (int k = 0; k < 5; ++k) damped(k, k) += lambda * std::max(jtj(k, k), 1e-300);
      const Eigen::VectorXd step = damped.ldlt().solve(-grad);
      const Eigen::VectorXd trial = p + step;
      const Eigen::VectorXd rt = residuals(trial);
      const double trial_cost = 0.5 * rt.squaredNorm();
      if (std::isfinite(trial_cost) && trial_cost < cost) {
        const double change = (cost - trial_cost) / cost;
        const double step_size = step.norm() / (p.norm() + 1e-8);
        p = trial;
        r = rt;
        cost = trial_cost;
        lambda = std::max(lambda / 3, 1e-12);
        stepped = true;
        converged = change <= 1e-6 || step_size <= 1e-8;
      } else {
        lambda *= 4;
      }
    }
    if (!stepped) break;
  }
  BaselineEstimate e;
  e.iterations = it;
  const double unit = tool_unit;
  e.quantization = std::abs(p(0)) / std::sqrt(3.0) / unit;
  e.white = std::abs(p(1)) / unit;
  e.bias_instability = std::abs(p(2)) / kImuUtilsFloorFactor / unit;
  e.rate_random_walk = std::sqrt(3.0) * std::abs(p(3)) / unit;
  double floor = std::numeric_limits<double>::infinity();
  for (const double t : tau) floor = std::min(floor, std::sqrt(model(p, t)));
  e.floor = floor / unit;
  e.adev_1s = std::sqrt(model(p, 1.0)) / unit;
  return e;
}

}  // namespace sigmatau::bench
