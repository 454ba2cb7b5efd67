// The gyroscope's bias from the static intervals, with the Earth rate each of them sees
// (calibrate.hpp step 3).
//
// Glossary: K static intervals; y_k the mean gyro reading of interval k and V_k its covariance;
// G the gyroscope matrix; b(dT) = b0 + c1 dT [+ c2 dT^2] per axis, dT = T_k - T0; C_k the attitude
// of interval k relative to interval 0 (interval_attitudes: the calibrated rotations between
// consecutive intervals, chained); w_0 the Earth rate in the frame of interval 0; d_k the unit
// down direction of interval k (calibrated accelerometer); Omega the Earth rate; lat the latitude.
//
// Heading model: y_k = G C_k^T w_0 + b(dT_k) + v_k, Cov v_k = V_k. The Earth rate is fixed in the
// Earth frame and so in the local level, relative to which the rotations R_k are integrated (the
// Earth rate is removed step by step), so C_k^T w_0 is its value in interval k with no further
// term for the turning of the local level. With a latitude, w_0 = -Omega sin(lat) d_0 + E h
// (E a basis of the plane normal to d_0; the vertical part is removed per interval as
// -Omega sin(lat) G d_k, and h, two numbers, is estimated); without, w_0 is three unknowns. The
// norms |h| = Omega cos(lat) and |w_0| = Omega are not imposed: the model stays linear, so the
// weighted least squares is exact and its covariance honest with no iteration or prior, at the
// cost of one degree of freedom among 3K; the estimated norm is reported for comparison.
// A schedule's headings are tied to its tilts, so the horizontal Earth rate does not average
// out across the intervals: treating it as independent noise (the fallback) biases b by up to
// ~Omega cos(lat) / 3 on an axis.
#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/QR>

#include <cmath>

#include "calibrate_internal.hpp"
#include "sigmatau/earth.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau::detail {
namespace {

/// Floor added to every interval's reading variance [(rad/s)^2]: (1e-12 rad/s)^2, far below the
/// mean of any real gyroscope over seconds (a navigation-grade FOG averages to ~1e-8 rad/s), so
/// it changes no weight; it keeps a noise-free simulation's zero covariance invertible.
constexpr double kMinVariance = 1e-24;

/// Columns of the bias coefficients: axis a's start and the total count.
std::array<Eigen::Index, 3> offsets(const std::array<int, 3>& degree, Eigen::Index& total) {
  std::array<Eigen::Index, 3> off{};
  total = 0;
  for (std::size_t a = 0; a < 3; ++a) {
    off[a] = total;
    total += degree[a] + 1;
  }
  return off;
}

/// The heading model for fixed degrees. Throws Error when the data do not determine it.
GyroBiasFit heading_fit(const std::vector<StaticInterval>& iv, const std::vector<Eigen::Vector3d>& down,
                        const std::vector<Eigen::Matrix3d>& att, const Eigen::Matrix3d& g,
                        const std::optional<double>& lat, const std::vector<double>& dt,
                        const std::array<int, 3>& degree) {
  const auto n = static_cast<Eigen::Index>(iv.size());
  const Eigen::Index ne = lat ? 2 : 3;
  Eigen::Index nb = 0;
  const auto off = offsets(degree, nb);
  const Eigen::Index np = nb + ne;
  if (3 * n <= np) throw Error("gyroscope bias: too few intervals for the heading model");
  Eigen::MatrixXd basis(3, ne);
  if (lat) {
    const Eigen::Vector3d e1 = down[0].unitOrthogonal();
    basis.col(0) = e1;
    basis.col(1) = down[0].cross(e1);
  } else {
    basis = Eigen::Matrix3d::Identity();
  }
  Eigen::MatrixXd a(3 * n, np);
  Eigen::VectorXd y(3 * n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const auto uk = static_cast<std::size_t>(k);
    const Eigen::LLT<Eigen::Matrix3d> llt(iv[uk].gyro_cov + kMinVariance * Eigen::Matrix3d::Identity());
    if (llt.info() != Eigen::Success) throw Error("gyroscope bias: a reading covariance is not positive");
    const Eigen::Matrix3d w = llt.matrixL().solve(Eigen::Matrix3d::Identity());
    Eigen::Vector3d yk = iv[uk].gyro_mean;
    if (lat) yk -= g * (-kEarthRate * std::sin(*lat) * down[uk]);
    Eigen::MatrixXd xk = Eigen::MatrixXd::Zero(3, np);
    for (std::size_t ax = 0; ax < 3; ++ax)
      for (int d = 0; d <= degree[ax]; ++d)
        xk(static_cast<Eigen::Index>(ax), off[ax] + d) = std::pow(dt[uk], d);
    xk.rightCols(ne) = g * att[uk].transpose() * basis;
    a.middleRows(3 * k, 3) = w * xk;
    y.segment<3>(3 * k) = w * yk;
  }
  const Eigen::MatrixXd cov = covariance_of(a, "gyroscope bias with the Earth rate");
  const Eigen::VectorXd p = a.colPivHouseholderQr().solve(y);
  GyroBiasFit f;
  f.heading = true;
  f.degree = degree;
  f.chi2 = (y - a * p).squaredNorm();
  const double scale = covariance_scale(f.chi2, static_cast<int>(3 * n - np));
  for (std::size_t ax = 0; ax < 3; ++ax) f.c[ax] = p.segment(off[ax], degree[ax] + 1);
  f.covariance = scale * cov.topLeftCorner(nb, nb);
  const Eigen::MatrixXd hcov = scale * cov.bottomRightCorner(ne, ne);
  f.earth = basis * p.tail(ne);
  if (lat) f.earth += -kEarthRate * std::sin(*lat) * down[0];
  f.earth_cov = basis * hcov * basis.transpose();
  return f;
}

/// The fallback: per axis, the Earth rate's unknown part as independent noise in each interval
/// (its variance added to the reading's), a weighted polynomial per axis.
GyroBiasFit noise_fit(const std::vector<StaticInterval>& iv, const std::vector<Eigen::Vector3d>& down,
                      const Eigen::Matrix3d& g, const std::optional<double>& lat,
                      const std::vector<double>& dt, bool temperature) {
  const int n = static_cast<int>(iv.size());
  std::array<std::vector<double>, 3> y, var;
  for (std::size_t k = 0; k < iv.size(); ++k) {
    Eigen::Vector3d earth = Eigen::Vector3d::Zero();
    Eigen::Matrix3d earth_cov;
    if (lat) {
      earth = g * (-kEarthRate * std::sin(*lat) * down[k]);
      const double h = kEarthRate * std::cos(*lat);
      earth_cov = g * (h * h / 2 * (Eigen::Matrix3d::Identity() - down[k] * down[k].transpose())) *
                  g.transpose();
    } else {
      earth_cov = g * (kEarthRate * kEarthRate / 3 * Eigen::Matrix3d::Identity()) * g.transpose();
    }
    for (int a = 0; a < 3; ++a) {
      y[static_cast<std::size_t>(a)].push_back(iv[k].gyro_mean[a] - earth[a]);
      var[static_cast<std::size_t>(a)].push_back(iv[k].gyro_cov(a, a) + earth_cov(a, a));
    }
  }
  GyroBiasFit m;
  std::array<Eigen::MatrixXd, 3> cov;
  for (std::size_t a = 0; a < 3; ++a) {
    int degree = 0;
    PolyFit best = weighted_polynomial(dt, y[a], var[a], 0);
    if (temperature) {
      const PolyFit lin = weighted_polynomial(dt, y[a], var[a], 1);
      m.axes[a].aicc_linear = aicc(lin.chi2, 2, n);
      m.axes[a].aicc_quadratic = INFINITY;
      best = lin;
      degree = 1;
      if (n > 4) {
        try {
          const PolyFit quad = weighted_polynomial(dt, y[a], var[a], 2);
          m.axes[a].aicc_quadratic = aicc(quad.chi2, 3, n);
          if (m.axes[a].aicc_quadratic < m.axes[a].aicc_linear) {
            best = quad;
            degree = 2;
          }
        } catch (const Error&) {
        }
      }
    }
    best.covariance *= covariance_scale(best.chi2, n - degree - 1);
    m.chi2 += best.chi2;
    m.c[a] = best.c;
    m.degree[a] = degree;
    cov[a] = best.covariance;
  }
  Eigen::Index nb = 0;
  const auto off = offsets(m.degree, nb);
  m.covariance = Eigen::MatrixXd::Zero(nb, nb);
  for (std::size_t a = 0; a < 3; ++a)
    m.covariance.block(off[a], off[a], m.degree[a] + 1, m.degree[a] + 1) = cov[a];
  return m;
}

}  // namespace

Eigen::Vector3d GyroBiasFit::at(double dt) const {
  Eigen::Vector3d b;
  for (std::size_t a = 0; a < 3; ++a) {
    b[static_cast<Eigen::Index>(a)] = 0;
    for (int d = 0; d <= degree[a]; ++d) b[static_cast<Eigen::Index>(a)] += c[a][d] * std::pow(dt, d);
  }
  return b;
}

GyroBiasFit fit_gyro_bias(const std::vector<StaticInterval>& iv, const std::vector<Eigen::Vector3d>& down,
                          const std::vector<Eigen::Matrix3d>& attitude, const Eigen::Matrix3d& g,
                          const std::optional<double>& latitude_rad, const std::vector<double>& dt,
                          bool temperature) {
  if (attitude.size() == iv.size() && !iv.empty()) {
    if (!temperature) {
      try {
        return heading_fit(iv, down, attitude, g, latitude_rad, dt, {0, 0, 0});
      } catch (const Error&) {
      }
    } else {
      // Degrees per axis (1 or 2) by AICc over all eight combinations, as for the accelerometer.
      std::array<GyroBiasFit, 8> fits;
      std::array<double, 8> score;
      score.fill(INFINITY);
      int best = -1;
      const int obs = 3 * static_cast<int>(iv.size());
      for (int mask = 0; mask < 8; ++mask) {
        const std::array<int, 3> deg{1 + (mask & 1), 1 + ((mask >> 1) & 1), 1 + ((mask >> 2) & 1)};
        const auto um = static_cast<std::size_t>(mask);
        try {
          fits[um] = heading_fit(iv, down, attitude, g, latitude_rad, dt, deg);
        } catch (const Error&) {
          continue;  // e.g. a quadratic term the temperatures cannot determine
        }
        const int params = deg[0] + deg[1] + deg[2] + 3 + (latitude_rad ? 2 : 3);
        score[um] = aicc(fits[um].chi2, params, obs);
        if (best < 0 || score[um] < score[static_cast<std::size_t>(best)]) best = mask;
      }
      if (best >= 0) {
        GyroBiasFit f = fits[static_cast<std::size_t>(best)];
        for (int a = 0; a < 3; ++a) {
          f.axes[static_cast<std::size_t>(a)].aicc_linear = score[static_cast<std::size_t>(best & ~(1 << a))];
          f.axes[static_cast<std::size_t>(a)].aicc_quadratic = score[static_cast<std::size_t>(best | (1 << a))];
        }
        return f;
      }
    }
  }
  return noise_fit(iv, down, g, latitude_rad, dt, temperature);
}

}  // namespace sigmatau::detail
