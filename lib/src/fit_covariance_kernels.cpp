// Lag correlations of the OAVAR second differences, term by term, in O(1) time per lag.
//
// Glossary (fit_covariance.cpp has the rest):
//   x_j     integrated rate, x_j = sum_{i<=j} y_i [rate x samples]; d^a_k = (x_{k+2m_a} -
//           2 x_{k+m_a} + x_k) / m_a, i.e. coefficients g = (1, -2, 1) at offsets 0, m_a, 2 m_a
//   G(l)    generalized covariance of x: Var(sum_i g_i x_{t_i}) = sum_ij g_i g_j G(t_i - t_j)
//           for coefficients that annihilate polynomials of degree <= 1 (Matheron's intrinsic
//           random functions). The double second difference below annihilates every polynomial
//           of degree <= 3 in l, so G is only needed up to such a polynomial.
//   c_ab(L) = (1 / (m_a m_b)) sum_{i,j=0}^{2} g_i g_j G(d_ij), d_ij = L + j m_b - i m_a
//   u       L - (m_a - m_b); d_ij = u + delta_ij, delta_ij = (j-1) m_b - (i-1) m_a in
//           [-(m_a + m_b), m_a + m_b], so c is even in u and G's kinks at d_ij = 0 put c's
//           breakpoints at L = i m_a - j m_b.
// G per unit squared parameter (the per-sample PSDs of fit_covariance.cpp):
//   Q   [l = 0] / tau0^2: x = e / tau0 up to a constant, e white (spikes only at breakpoints)
//   N   -|l| / (2 tau0): x a random walk with step variance 1 / tau0
//   K   tau0 (|l|^3 - |l|) / 12: x an integrated random walk with step variance tau0
//       (its second difference is tau0 |l| / 2, minus the N form's covariance of y)
//   B   flicker_phase_covariance: y has the generalized covariance K_y(l) = int S_y (cos 2 pi f l
//       - 1) df = -(2/pi) O(|l|), O(n) = sum_{k<=n} 1/(2k-1) (sin^2(l t)/sin t = sum of
//       sin((2k-1) t)); G solves G(l+1) - 2 G(l) + G(l-1) = -K_y(l), G(0) = G(1) = 0, which
//       sums to (2/pi) [(4l^2 - 1)/8 O(l-1) - l(l-1)/2 + (l-1)^2/8], with O(n) = (psi(n + 1/2)
//       - psi(1/2)) / 2 for real n
//   GM  y AR(1) with variance 1, phi = e^-a, a = tau0 / tau_c: G = -Var(x_l - x_0) / 2 =
//       -|l|/2 - phi (l^2 p2(|l| a) - |l| p2(a)) / p1(a)^2, p1(x) = (1 - e^-x)/x,
//       p2(x) = (e^-x - 1 + x)/x^2
// Q, N and K vanish for |u| >= m_a + m_b (all d_ij of one sign: a cubic, annihilated). Beyond
// that B and GM would cancel catastrophically (G ~ l^2 ln l or l^2 against c ~ 1/u^2 or e^-au),
// so their far fields are evaluated in closed form (GM) or as a Taylor series in delta / u (B).
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "fit_covariance_lags.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau::detail {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr std::array<double, 3> kG{1, -2, 1};
/// psi(1/2) = -gamma - 2 ln 2.
constexpr double kDigammaHalf = -std::numbers::egamma - 2 * std::numbers::ln2;
/// psi recurs upward to this argument before its asymptotic series: the first omitted term,
/// 691 / (32760 x^12), is below 1e-16 there.
constexpr double kDigammaAsymptotic = 16;
/// The flicker far field (Taylor series in delta / u) from |u| >= this times (m_a + m_b): its
/// terms shrink by (m_a + m_b) / |u| <= 1/6 per order (summed to kSeriesTolerance), while the
/// direct sum of nine G ~ l^2 ln l loses about (2 x 6)^4 x 16 ~ 3e5 ulps there.
constexpr double kFlickerFarRatio = 6;
constexpr int kFlickerMaxOrder = 26;
/// The Taylor series stop once their next term is below this fraction of the leading one.
constexpr double kSeriesTolerance = 1e-17;
/// p2's power series is used below this argument (its terms fall below 1e-19 by x^20 / 22!).
constexpr double kSeriesBelow = 1;
constexpr int kSeriesTerms = 22;

double digamma(double x) {
  double acc = 0;
  while (x < kDigammaAsymptotic) {
    acc -= 1 / x;
    x += 1;
  }
  const double r = 1 / (x * x);
  return acc + std::log(x) - 0.5 / x -
         r * (1.0 / 12 - r * (1.0 / 120 - r * (1.0 / 252 - r * (1.0 / 240 - r / 132))));
}

/// p2(x) = (e^-x - 1 + x) / x^2, or p2(x) - 1/2 with `minus_half`, series below kSeriesBelow.
double p2(double x, bool minus_half) {
  if (x < kSeriesBelow) {
    double term = 1.0 / 6, sum = minus_half ? 0.0 : 0.5;  // k = 3 term is -x / 6
    double power = x;
    for (int k = 3; k < kSeriesTerms; ++k) {
      sum += (k % 2 ? -1.0 : 1.0) * power * term;
      power *= x;
      term /= static_cast<double>(k + 1);
    }
    return sum;
  }
  return (std::expm1(-x) + x) / (x * x) - (minus_half ? 0.5 : 0.0);
}

/// The far-field expansion of flicker_phase_covariance beyond its annihilated cubic:
/// G = a0 l^2 ln l + a1 ln l + sum_p b_p l^-p (p = 2, 4, 6), from psi(x + 1/2) ~ ln x +
/// 1/(24 x^2) - 7/(960 x^4) + 31/(8064 x^6) - 127/(30720 x^8) (Bernoulli polynomials at 1/2)
/// with O(l - 1) = O(l) - 1/(2l - 1).
constexpr double kFarL2Log = 1 / (2 * kPi);
constexpr double kFarLog = -1 / (8 * kPi);
constexpr std::array<double, 3> kFarInverse{(2 / kPi) * (-7.0 / 3840 - 1.0 / 384),
                                            (2 / kPi) * (31.0 / 32256 + 7.0 / 15360),
                                            (2 / kPi) * (-127.0 / 122880 - 31.0 / 129024)};

/// c_B(u) for |u| >= kFlickerFarRatio (m_a + m_b): sum over even k >= 4 of G^(k)(|u|) M_k / k!
/// / (m_a m_b), M_k = sum_ij g_i g_j delta_ij^k; M_k / (k! u^k) = 4 sum_{r even in [2, k-2]}
/// t_b^r / r! t_a^(k-r) / (k-r)!, t = m / |u|.
double flicker_far(double ma, double mb, double u) {
  const double ta = ma / u, tb = mb / u;
  std::array<double, kFlickerMaxOrder + 1> pa{}, pb{};  // t^r / r!
  pa[0] = pb[0] = 1;
  for (int r = 1; r <= kFlickerMaxOrder; ++r) {
    pa[static_cast<std::size_t>(r)] = pa[static_cast<std::size_t>(r - 1)] * ta / r;
    pb[static_cast<std::size_t>(r)] = pb[static_cast<std::size_t>(r - 1)] * tb / r;
  }
  const double inv_u2 = 1 / (u * u);
  double sum = 0;
  double fact_km3 = 1;  // (k-3)!
  for (int k = 4; k <= kFlickerMaxOrder; k += 2) {
    double mu = 0;
    for (int r = 2; r <= k - 2; r += 2) {
      mu += pb[static_cast<std::size_t>(r)] * pa[static_cast<std::size_t>(k - r)];
    }
    mu *= 4;
    // G^(k)(u) u^k / u^2 for each part (even k): l^2 ln l -> -2 (k-3)!, ln l -> -(k-1)! / u^2,
    // l^-p -> (p+k-1)! / (p-1)! / u^(p+2).
    const double kd = k;
    double d = -2 * kFarL2Log * fact_km3 - kFarLog * fact_km3 * (kd - 2) * (kd - 1) * inv_u2;
    double pow_u = inv_u2 * inv_u2;
    for (std::size_t i = 0; i < kFarInverse.size(); ++i) {
      const int p = 2 * static_cast<int>(i) + 2;
      double ratio = 1;
      for (int j = p; j <= p + k - 1; ++j) ratio *= j;
      d += kFarInverse[i] * ratio * pow_u;
      pow_u *= inv_u2;
    }
    sum += mu * d;
    fact_km3 *= (kd - 2) * (kd - 1);
    // mu_k (k-3)! falls like ((m_a + m_b) / u)^(k-4) against the k = 4 term.
    if (std::pow(ta + tb, k - 2) < kSeriesTolerance) break;
  }
  return sum / (ta * tb);
}

/// The polynomial part of flicker_phase_covariance at large |l| (2/pi) [(C_O/2 - 3/8) l^2 +
/// const], C_O = ln 2 + gamma / 2 the constant of O(n) ~ ln(n)/2 + C_O; its second difference
/// (2/pi) (C_O - 3/4) m^2 is added to the series below so that both forms of the inner second
/// difference carry the same constant (the outer difference cancels only a common constant).
constexpr double kOddConstant = std::numbers::ln2 + std::numbers::egamma / 2;
constexpr double kFarQuadratic = (2 / kPi) * (kOddConstant - 0.75);
/// The inner second difference of flicker_phase_covariance uses the series from |y| >= this
/// times its step (and >= kFlickerSeriesFloor, where the asymptotic G is good to 1e-15): the
/// direct form loses (|y| / m)^2 digits there.
constexpr double kFlickerInnerRatio = 6;
constexpr double kFlickerSeriesFloor = 64;
constexpr int kFlickerInnerOrder = 24;

/// G(y - m) - 2 G(y) + G(y + m) for the flicker G at |y| >= max(6 m, 64): sum over even k >= 2
/// of 2 m^k / k! G^(k)(|y|) with the far-field G, plus kFarQuadratic m^2.
double flicker_inner_series(double y, double m) {
  const double t = m / y, t2 = t * t, inv_y2 = 1 / (y * y);
  double sum = kFarL2Log * m * m * (2 * std::log(y) + 3) + kFarQuadratic * m * m;
  std::array<double, kFarInverse.size()> binom{};  // C(p+k-1, k) for p = 2, 4, 6, from k = 2
  for (std::size_t i = 0; i < binom.size(); ++i) {
    const double p = 2.0 * static_cast<double>(i) + 2;
    binom[i] = p * (p + 1) / 2;
  }
  double tk = t2;
  for (int k = 2; k <= kFlickerInnerOrder; k += 2) {
    const double kd = k;
    double term = -2 * kFarLog * tk / kd;
    if (k >= 4) term += -4 * kFarL2Log * y * y * tk / (kd * (kd - 1) * (kd - 2));
    double inv_yp = inv_y2;
    for (std::size_t i = 0; i < binom.size(); ++i) {
      const double p = 2.0 * static_cast<double>(i) + 2;
      term += 2 * kFarInverse[i] * tk * binom[i] * inv_yp;
      inv_yp *= inv_y2;
      binom[i] *= (p + kd) * (p + kd + 1) / ((kd + 1) * (kd + 2));
    }
    sum += term;
    // The terms fall like t^(k-2) against sum ~ m^2: stop below 1e-17 of it.
    if (tk < kSeriesTolerance * t2) break;
    tk *= t2;
  }
  return sum;
}

}  // namespace

double flicker_phase_covariance(double l) {
  const double n = std::abs(l);
  if (n == 0) return 0;
  const double odd = (digamma(n - 0.5) - kDigammaHalf) / 2;  // O(n - 1)
  return (2 / kPi) * ((4 * n * n - 1) / 8 * odd - n * (n - 1) / 2 + (n - 1) * (n - 1) / 8);
}

PairCorrelation::PairCorrelation(std::int64_t ma, std::int64_t mb, double tau0_s,
                                 std::span<const double> gm_rates)
    : ma_(ma), mb_(mb), tau0_s_(tau0_s) {
  if (gm_rates.size() > kMaxGaussMarkov) {
    throw Error("covariance: at most " + std::to_string(kMaxGaussMarkov) +
                " Gauss-Markov terms are modelled");
  }
  for (const double a : gm_rates) {
    GaussMarkovPair g;
    g.rate = a;
    const double p1 = -std::expm1(-a) / a;
    const double phi = std::exp(-a);
    g.scale = phi / (p1 * p1);
    g.linear = p2(a, false);
    // Far field: -phi / (1 - phi)^2 (1 - e^-a m_a)^2 (1 - e^-a m_b)^2 / (m_a m_b), times
    // e^-a(|u| - m_a - m_b).
    const double ea = -std::expm1(-a * static_cast<double>(ma));
    const double eb = -std::expm1(-a * static_cast<double>(mb));
    const double one_minus_phi = -std::expm1(-a);
    g.far = -phi / (one_minus_phi * one_minus_phi) * ea * ea * eb * eb /
            (static_cast<double>(ma) * static_cast<double>(mb));
    // Inner second difference at |y| >= m_s: -scale e^-a(|y| - m_s) (1 - e^-a m_s)^2 / a^2.
    const double es = std::min(ea, eb);
    g.inner = -g.scale * es * es / (a * a);
    gm_.push_back(g);
  }
}

void PairCorrelation::evaluate(double lag, std::span<double> c) const {
  // c = (1/(m_a m_b)) sum_o g_o D2(y_o): the inner second difference D2 runs over the smaller
  // factor m_s (where the direct sum would cancel worst), the outer one over the larger.
  const double ma = static_cast<double>(ma_), mb = static_cast<double>(mb_);
  const double u = std::abs(lag - (ma - mb));
  const double span = ma + mb;
  const double inv_mm = 1 / (ma * mb);
  const bool a_small = ma_ <= mb_;
  const double ms = a_small ? ma : mb;
  const bool inside = u < span;
  const bool flicker_near = u < kFlickerFarRatio * span;
  const std::size_t n_gm = gm_.size();
  // Gauss-Markov: one representation of G for the whole evaluation (p2 - 1/2 while every
  // |d| a < 1, else p2); they differ by scale l^2 / 2, which only cancels when used throughout.
  std::array<bool, kMaxGaussMarkov> gm_minus_half{};
  std::array<double, kMaxGaussMarkov> gm{};
  for (std::size_t g = 0; g < n_gm; ++g) gm_minus_half[g] = (u + span) * gm_[g].rate < kSeriesBelow;
  double q = 0, n = 0, k = 0, b = 0;
  for (int o = 0; o < 3; ++o) {
    const double go = kG[static_cast<std::size_t>(o)];
    const double y = a_small ? lag + o * mb - ma : lag - o * ma + mb;
    const double ay = std::abs(y);
    const bool near = ay < ms;
    double dq = 0, dn = 0, dk = 0, db = 0;
    std::array<double, kMaxGaussMarkov> dgm{};
    const bool b_series = ay >= std::max(kFlickerInnerRatio * ms, kFlickerSeriesFloor);
    for (int i = 0; i < 3; ++i) {
      const double gi = kG[static_cast<std::size_t>(i)];
      const double d = std::abs(y + (i - 1) * ms);
      if (d == 0) dq += gi;
      if (inside && near) {
        dn += gi * d;
        dk += gi * (d * d * d - d);
        for (std::size_t g = 0; g < n_gm; ++g) {
          const GaussMarkovPair& p = gm_[g];
          const double quad = d * d * p2(d * p.rate, gm_minus_half[g]);
          dgm[g] += gi * (-d / 2 - p.scale * (quad - d * p.linear));
        }
      }
      if (flicker_near && !b_series) db += gi * flicker_phase_covariance(d);
    }
    if (inside && !near) {
      dk = 6 * ms * ms * ay;  // (|l|^3 - |l|) is a cubic on one side: D2 = 6 m^2 |y|
      for (std::size_t g = 0; g < n_gm; ++g) {
        const GaussMarkovPair& p = gm_[g];
        dgm[g] = p.inner * std::exp(-p.rate * (ay - ms)) + (gm_minus_half[g] ? p.scale * ms * ms : 0.0);
      }
    }
    if (flicker_near && b_series) db = flicker_inner_series(ay, ms);
    q += go * dq;
    n += go * dn;
    k += go * dk;
    b += go * db;
    for (std::size_t g = 0; g < n_gm; ++g) gm[g] += go * dgm[g];
  }
  c[0] = q * inv_mm / (tau0_s_ * tau0_s_);
  c[1] = -n * inv_mm / (2 * tau0_s_);
  c[2] = flicker_near ? b * inv_mm : flicker_far(ma, mb, u);
  c[3] = k * inv_mm * tau0_s_ / 12;
  for (std::size_t g = 0; g < n_gm; ++g) {
    c[static_cast<std::size_t>(kLagTerms) + g] =
        inside ? gm[g] * inv_mm : gm_[g].far * std::exp(-gm_[g].rate * (u - span));
  }
}

}  // namespace sigmatau::detail
