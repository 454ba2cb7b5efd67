// The log-scale likelihood the joint fit's model selection uses (lib/src/fit_log_likelihood.cpp):
// the chi-squared bias of ln v, independence of the level, and the skew a Gaussian misses.
// An internal class: included from lib/src (tests link the static library).
#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include "../lib/src/fit_internal.hpp"
#include "test_support.hpp"

namespace {

using sigmatau::detail::LogScaleLikelihood;

}  // namespace

TEST_CASE("one point with 2 degrees of freedom: the likeliest mean is v e^gamma") {
  // v = mu chi2_2 / 2 is exponential with mean mu, and E ln v = ln mu - gamma (Euler's
  // constant): the deviance of mean mu is minimal at mu = v e^gamma, not at mu = v. The EDF
  // comes from the reference: nu = 2 mu^2 / sigma = 2 for mu = 1, sigma = 1.
  Eigen::VectorXd v(1), ref(1);
  v << 0.3;
  ref << 1.0;
  const LogScaleLikelihood like(v, ref, Eigen::MatrixXd::Identity(1, 1));
  const auto dev_at = [&](double mean) {
    Eigen::VectorXd mu(1);
    mu << mean;
    return like.deviance(mu);
  };
  const double best = 0.3 * std::exp(std::numbers::egamma);
  // 1 % either side costs more (the deviance is a parabola in ln mu with curvature
  // 2 / trigamma(1) = 1.2, so a 1 % step adds ~6e-5, far above rounding).
  CHECK(dev_at(best) < dev_at(best * 1.01));
  CHECK(dev_at(best) < dev_at(best / 1.01));
  CHECK(dev_at(best) < dev_at(0.3));
  // At the minimum only ln det C = ln trigamma(1) = ln(pi^2 / 6) is left.
  SIGMATAU_CHECK_REL(dev_at(best), std::log(std::numbers::pi * std::numbers::pi / 6), 1e-12);
}

TEST_CASE("the log-scale deviance does not depend on the level of the curve") {
  // Scaling v and the model mean by c and the covariance by c^2 changes neither an EDF nor a
  // log ratio: the deviance is the same to rounding (1e-12 relative).
  Eigen::VectorXd v(3), mu(3);
  v << 2.0, 1.1, 0.7;
  mu << 1.8, 1.0, 1.0;
  Eigen::MatrixXd sigma(3, 3);
  sigma << 0.05, 0.02, 0.01,  //
      0.02, 0.10, 0.06,       //
      0.01, 0.06, 0.40;
  const double c = 1e-9;
  const LogScaleLikelihood one(v, mu, sigma);
  const LogScaleLikelihood scaled(c * v, c * mu, c * c * sigma);
  Eigen::VectorXd model(3);
  model << 1.9, 1.2, 0.9;
  SIGMATAU_CHECK_REL(scaled.deviance(c * model), one.deviance(model), 1e-12);
  // A mean that is not > 0 everywhere has no likelihood.
  model(2) = 0;
  CHECK(std::isinf(one.deviance(model)));
}

TEST_CASE("at 3 degrees of freedom a point 3x high costs 4x what a point 3x low does") {
  // v = mu chi2_3 / 3: E ln v = ln mu + b with b = psi(3/2) - ln(3/2) = 2 - gamma - 2 ln 2
  // - ln 1.5 = -0.369. Measured from the centre mu e^b, v = 3 mu is ln 3 - b = 1.47 away and
  // v = mu / 3 only ln 3 + b = 0.73, so the high point costs ((ln 3 - b) / (ln 3 + b))^2 = 4.05
  // times as much. A Gaussian in v with the model's variance would charge them (2 / (2/3))^2 =
  // 9 to 1, which is what made a high last point add K or R.
  Eigen::VectorXd mu(1);
  mu << 1.0;
  const Eigen::MatrixXd sigma = Eigen::MatrixXd::Constant(1, 1, 2.0 / 3.0);  // nu = 3
  const double b = 2 - std::numbers::egamma - 2 * std::numbers::ln2 - std::log(1.5);
  const auto dev_at = [&](double v) {
    Eigen::VectorXd x(1);
    x << v;
    return LogScaleLikelihood(x, mu, sigma).deviance(mu);
  };
  const double centre = dev_at(std::exp(b));
  const double ratio = (dev_at(3.0) - centre) / (dev_at(1.0 / 3.0) - centre);
  const double ln3 = std::log(3.0);
  // 1e-9: digamma and trigamma to double precision; the difference of deviances loses ~3 digits.
  SIGMATAU_CHECK_REL(ratio, std::pow((ln3 - b) / (ln3 + b), 2), 1e-9);
  CHECK(ratio < 4.1);
}
