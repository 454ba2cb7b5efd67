// Model selection of the joint fit (lib/src/fit_select.cpp): the curve likelihood against the
// exact chi-squared likelihood of one point, and the priors of the ramp and of quantization on
// exact curves.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include "../../lib/src/fit_select.hpp"  // internal interface under test
#include "sigmatau/fit.hpp"
#include "sigmatau/noise_model.hpp"
#include "sigmatau/taus.hpp"
#include "exact_curve.hpp"
#include "test_support.hpp"

namespace {

using namespace sigmatau;

constexpr double kTau0 = 0.01;  // 100 Hz
constexpr std::int64_t kSamples = std::int64_t{1} << 16;

/// An exact theoretical OADEV curve at the octave factors of a log of kSamples.
AllanCurve exact_curve(const NoiseTerms& truth) { return test::exact_oadev_curve(truth, kSamples, kTau0); }

/// -2 ln of the chi-squared density of v = mu chi2_nu / nu, less the part that depends on v only.
double chi_squared_deviance(double v, double mu, double nu) { return nu * v / mu + nu * std::log(mu); }

}  // namespace

TEST_CASE("curve_deviance of one point follows the chi-squared likelihood ratio") {
  // One white-noise point of a 4097-point log at m = 64 (EDF ~ 95) and m = 1024 (EDF ~ 3, the
  // regime of the last octave taus where K and R show). The deviance difference between two
  // model levels mu and s mu at the same v is a log likelihood ratio; the Wilson-Hilferty
  // density it uses must give the chi-squared one's within 0.15 + 5 %: 0.15 is a likelihood
  // ratio within 8 % where the choice is close, and 5 % allows the cube root's error in the
  // far tails (v / mu = 2 at EDF 94 is a 7-sigma point: ratios of e^60, 4 % apart), where
  // either ratio is decisive.
  const std::int64_t n_phase = 4097;
  for (const std::int64_t m : {std::int64_t{64}, std::int64_t{1024}}) {
    const detail::CovarianceBasis basis = detail::build_covariance_basis({m}, n_phase, kTau0, {});
    NoiseTerms unit;
    unit.white = 1.0;
    detail::Design d;
    d.a = Eigen::MatrixXd::Zero(1, detail::kTermCount);
    d.a(0, detail::term_index(NoiseTerm::white)) = sampled_avar(unit, m, Sampling{kTau0, 0, false});
    detail::TermVector theta = detail::TermVector::Zero(detail::kTermCount);
    theta(detail::term_index(NoiseTerm::white)) = 1e-6;
    const double mu = (d.a * theta)(0);
    const double nu = 2 * mu * mu / basis.covariance(Eigen::VectorXd(theta))(0, 0);
    INFO("m = " << m << ", EDF " << nu);
    CHECK(nu > 2.5);
    for (const double r : {0.5, 1.0, 2.0}) {
      d.v = Eigen::VectorXd::Constant(1, r * mu);
      for (const double s : {0.5, 2.0}) {
        const double wh = detail::curve_deviance(d, s * theta, basis) - detail::curve_deviance(d, theta, basis);
        const double exact = chi_squared_deviance(r * mu, s * mu, nu) - chi_squared_deviance(r * mu, mu, nu);
        INFO("v / mu = " << r << ", s = " << s << ": cube root " << wh << ", chi-squared " << exact);
        CHECK(std::abs(wh - exact) <= 0.15 + 0.05 * std::abs(exact));
      }
    }
  }
}

TEST_CASE("a rate ramp is kept when the curve needs it and is otherwise a bound above the truth") {
  const CurveSource source{kTau0, kSamples + 1, 0};
  NoiseTerms t;
  t.white = 4e-4;
  t.bias_instability = 3e-4;
  SUBCASE("a ramp that dominates the last octaves: N, B, R") {
    t.rate_ramp = 1e-4;  // AVAR 0.5 R^2 tau^2 = 100 x the flicker floor at the last tau
    const NoiseFit f = fit_noise(exact_curve(t), source, FitOptions{});
    CHECK(f.joint->model_terms ==
          std::vector<NoiseTerm>{NoiseTerm::white, NoiseTerm::bias_instability, NoiseTerm::rate_ramp});
    // 1e-6: an exact curve, only rounding in the solve remains.
    SIGMATAU_CHECK_REL(f.joint->parameter(NoiseTerm::rate_ramp).value, *t.rate_ramp, 1e-6);
  }
  SUBCASE("a random walk with the same level at the last tau is not taken for a ramp") {
    t.rate_random_walk = 2e-4;
    const NoiseFit f = fit_noise(exact_curve(t), source, FitOptions{});
    CHECK(f.joint->model_terms == std::vector<NoiseTerm>{NoiseTerm::white, NoiseTerm::bias_instability,
                                                         NoiseTerm::rate_random_walk});
    CHECK_FALSE(f.joint->parameter(NoiseTerm::rate_ramp).in_model);
  }
  SUBCASE("a weak ramp (5 x the flicker floor at the last tau only): left out, bounded above the truth") {
    t.rate_ramp = 2e-6;
    const NoiseFit f = fit_noise(exact_curve(t), source, FitOptions{});
    const auto& r = f.joint->parameter(NoiseTerm::rate_ramp);
    INFO("model " << f.joint->model_terms.size() << " terms, R bound " << r.upper_bound);
    CHECK_FALSE(r.in_model);
    CHECK(*t.rate_ramp <= r.upper_bound);
  }
  SUBCASE("--terms with R forces it whatever the prior") {
    t.rate_ramp = 2e-6;
    FitOptions o;
    o.terms = parse_fit_terms("N,B,R");
    const NoiseFit f = fit_noise(exact_curve(t), source, o);
    SIGMATAU_CHECK_REL(f.joint->parameter(NoiseTerm::rate_ramp).value, *t.rate_ramp, 1e-6);
  }
}

TEST_CASE("quantization's prior keeps a Q that shows at the shortest taus and bounds one that does not") {
  const CurveSource source{kTau0, kSamples + 1, 0};
  NoiseTerms t;
  t.white = 4e-4;             // AVAR at tau0: N^2 / tau0 = 1.6e-5
  t.bias_instability = 3e-4;
  SUBCASE("Q at 3.7 % of the AVAR at tau0 (the bench's quantized_gyro share): kept, exact") {
    t.quantization = 4.4e-6;  // 3 Q^2 / tau0^2 = 5.8e-7
    const NoiseFit f = fit_noise(exact_curve(t), source, FitOptions{});
    CHECK(f.joint->model_terms == std::vector<NoiseTerm>{NoiseTerm::quantization, NoiseTerm::white,
                                                         NoiseTerm::bias_instability});
    // 1e-6: an exact curve, only rounding in the solve remains.
    SIGMATAU_CHECK_REL(f.joint->parameter(NoiseTerm::quantization).value, *t.quantization, 1e-6);
  }
  SUBCASE("Q at 1e-6 of the AVAR at tau0: left out, bounded above the truth") {
    t.quantization = 2.3e-8;
    const NoiseFit f = fit_noise(exact_curve(t), source, FitOptions{});
    const auto& q = f.joint->parameter(NoiseTerm::quantization);
    INFO("model " << f.joint->model_terms.size() << " terms, Q bound " << q.upper_bound);
    CHECK_FALSE(q.in_model);
    CHECK(*t.quantization <= q.upper_bound);
  }
}
