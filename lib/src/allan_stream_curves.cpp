// The curves of the stream mode from its finished sums (see allan_stream_curves.hpp), and the
// EDF of a strided estimator (allan_stream.hpp).
#include "allan_stream_curves.hpp"

#include <algorithm>
#include <cmath>

#include "allan_curve_assembly.hpp"
#include "sigmatau/allan_stream.hpp"
#include "sigmatau/confidence.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau {
double strided_equivalent_dof(Statistic statistic, int alpha, std::int64_t m, std::int64_t s,
                              std::int64_t n_phase_points) {
  if (!(s >= 1 && m >= s && m % s == 0)) {
    throw Error("strided_equivalent_dof: the stride must divide m");
  }
  if (s == 1 || statistic == Statistic::adev || statistic == Statistic::hdev) {
    return equivalent_dof(statistic, alpha, m, n_phase_points);
  }
  // The strided estimator reads only the phase at multiples of s: it is the fully overlapping
  // estimator at lag q = m/s of that decimated series (N' = floor((N-1)/s) + 1 points). For the
  // modified variances (F = 1), Greenhall's kernels depend on m only through S = q, so this is
  // the strided EDF exactly; for the unmodified ones it is the same sampling of the same
  // continuous-time noise (for flicker PM the ln m of Table 3 becomes ln q: a slight
  // underestimate of the EDF).
  const std::int64_t q = m / s;
  const std::int64_t n = (n_phase_points - 1) / s + 1;
  const int d = (statistic == Statistic::ohdev) ? 3 : 2;
  const bool modified = statistic == Statistic::mdev || statistic == Statistic::tdev;
  return greenhall_edf(alpha, d, q, modified ? 1 : q, q, n);
}

namespace detail {

AllanCurve stream_curve(Statistic statistic, const StreamTotals& totals, double confidence_level) {
  const std::int64_t N = totals.points;
  AllanCurve curve;
  curve.statistic = statistic;
  curve.confidence_level = confidence_level;
  const std::int64_t max_m = max_averaging_factor(statistic, N, totals.kind);
  // The noise type as compute_allan_curve takes it (every power of two is identified, and
  // every factor of the decade grid in a decade run).
  const auto identify_at = [&](std::int64_t m) {
    const auto it = std::lower_bound(totals.noise_factors.begin(), totals.noise_factors.end(), m);
    SIGMATAU_ASSERT(it != totals.noise_factors.end() && *it == m, "noise state for every m");
    return totals.noise[static_cast<std::size_t>(it - totals.noise_factors.begin())].identify(
        statistic, totals.kind, m, totals.tau0_s);
  };
  for (const auto& tau : totals.taus) {
    if (tau.statistic != statistic || tau.m > max_m || tau.terms <= 0) continue;
    const double md = static_cast<double>(tau.m);
    const double scale = totals.kind == DataKind::rate ? 1.0 / md : 1.0 / (md * totals.tau0_s);
    const double mean_square = tau.sum.value() / static_cast<double>(tau.terms);
    double variance = 0.0;
    switch (statistic) {
      case Statistic::adev:
      case Statistic::oadev:
        variance = mean_square / 2.0;
        break;
      case Statistic::hdev:
      case Statistic::ohdev:
        variance = mean_square / 6.0;
        break;
      case Statistic::mdev:
        variance = mean_square / (2.0 * md * md);
        break;
      case Statistic::tdev: {
        const double tau_s = md * totals.tau0_s;
        variance = mean_square / (2.0 * md * md) * (tau_s * tau_s / 3.0);
        break;
      }
      case Statistic::totdev:
        break;
    }
    variance *= scale * scale;
    CurvePoint point;
    point.value = {md * totals.tau0_s, tau.m, tau.terms, std::sqrt(variance) * totals.value_scale};
    check_representable(statistic, point.value);
    const std::int64_t averages = (N - 1) / tau.m;
    const std::int64_t kept_m = kept_noise_factor(statistic, N, tau.m);
    if (tau.m != kept_m && averages <= kept_noise_threshold(statistic)) {
      point.confidence.noise.alpha = identify_at(kept_m).alpha;
      point.confidence.noise.method = NoiseIdentification::Method::kept;
    } else {
      point.confidence.noise = identify_at(tau.m);
    }
    point.confidence.edf =
        strided_equivalent_dof(statistic, point.confidence.noise.alpha, tau.m, tau.stride, N);
    point.confidence.interval =
        chi_squared_interval(point.value.dev, point.confidence.edf, confidence_level);
    curve.points.push_back(point);
  }
  return curve;
}

}  // namespace detail
}  // namespace sigmatau
