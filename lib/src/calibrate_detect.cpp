// Static-interval detector for multi-position calibration (calibrate.hpp).
//
// Glossary: w window length [samples], h = (w-1)/2; s_i the window statistic at sample i (sum over
// the three axes of the variance of the samples i-h..i+h); floor the 25th percentile of s over the
// log; n_k samples in interval k; B batches per interval for the batch-means check.
#include <algorithm>
#include <cmath>
#include <string>

#include "calibrate_internal.hpp"
#include "sigmatau/calibrate.hpp"
#include "sigmatau/error.hpp"

namespace sigmatau {
namespace {

/// A window needs at least this many samples for a variance with >= 4 degrees of freedom.
constexpr std::int64_t kMinWindowSamples = 5;
/// Quantile of the window statistic taken as the noise floor: a calibration log is static most
/// of the time (dwells of 10-30 s against rotations of a few seconds), so the lower quarter of
/// the windows is static noise even when half of the log is moving.
constexpr double kFloorQuantile = 0.25;
/// Batches per interval for the batch-means check of correlated noise (10 batches: each batch
/// mean still averages >= 20 samples of a 2 s interval at 100 Hz).
constexpr int kBatches = 10;
/// An interval in which any axis's batch means vary this many times more than white noise
/// predicts is moving slowly, not static. For white noise the ratio is chi^2_9/9 (P(> 10) ~ 1e-15);
/// the correlated noise of real sensors adds little over batches of 0.2-3 s (MEMS: an ADEV floor
/// 0.664 B of 0.05 mg against 100 ug/sqrt(Hz) white noise raises the ratio by ~3 %; a STIM300 by
/// < 1 %), while a slow turn of the gravity direction raises it by orders of magnitude.
constexpr double kMaxBatchRatio = 10;

using Triad = std::array<std::vector<double>, 3>;

/// Window statistic per sample (NaN where the window does not fit).
std::vector<double> window_statistic(const Triad& x, std::int64_t w) {
  const auto n = static_cast<std::int64_t>(x[0].size());
  std::vector<double> s(static_cast<std::size_t>(n), std::nan(""));
  const std::int64_t h = (w - 1) / 2;
  for (int axis = 0; axis < 3; ++axis) {
    const auto& v = x[static_cast<std::size_t>(axis)];
    // Centre on the first value to keep the running sums well conditioned.
    const double c = v.empty() ? 0 : v[0];
    std::vector<double> s1(static_cast<std::size_t>(n + 1), 0.0), s2(s1);
    for (std::int64_t i = 0; i < n; ++i) {
      const double d = v[static_cast<std::size_t>(i)] - c;
      s1[static_cast<std::size_t>(i + 1)] = s1[static_cast<std::size_t>(i)] + d;
      s2[static_cast<std::size_t>(i + 1)] = s2[static_cast<std::size_t>(i)] + d * d;
    }
    const double len = static_cast<double>(2 * h + 1);
    for (std::int64_t i = h; i + h < n; ++i) {
      const auto a = static_cast<std::size_t>(i - h), b = static_cast<std::size_t>(i + h + 1);
      const double m = (s1[b] - s1[a]) / len;
      const double var = std::max(0.0, ((s2[b] - s2[a]) - len * m * m) / (len - 1));
      double& out = s[static_cast<std::size_t>(i)];
      out = (axis == 0 ? 0.0 : out) + var;
    }
  }
  return s;
}

double quantile_of(std::vector<double> v, double q) {
  std::erase_if(v, [](double x) { return std::isnan(x); });
  if (v.empty()) return std::nan("");
  const auto k = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

void mean_and_cov(const Triad& x, std::int64_t first, std::int64_t last, Eigen::Vector3d& mean,
                  Eigen::Matrix3d& sample_cov) {
  const auto n = static_cast<double>(last - first + 1);
  mean.setZero();
  for (std::int64_t i = first; i <= last; ++i)
    for (int a = 0; a < 3; ++a) mean[a] += x[static_cast<std::size_t>(a)][static_cast<std::size_t>(i)];
  mean /= n;
  sample_cov.setZero();
  for (std::int64_t i = first; i <= last; ++i) {
    Eigen::Vector3d d;
    for (int a = 0; a < 3; ++a)
      d[a] = x[static_cast<std::size_t>(a)][static_cast<std::size_t>(i)] - mean[a];
    sample_cov += d * d.transpose();
  }
  sample_cov /= (n - 1);
}

/// Ratio of the observed variance of batch means to the white-noise prediction, per axis, summed
/// into `sum` with its count (the caller pools them).
void batch_ratio(const Triad& x, std::int64_t first, std::int64_t last,
                 const Eigen::Matrix3d& sample_cov, double& sum, int& count, double& worst) {
  const std::int64_t n = last - first + 1;
  const std::int64_t per = n / kBatches;
  if (per < 2) return;
  for (int a = 0; a < 3; ++a) {
    if (!(sample_cov(a, a) > 0)) continue;
    const auto& v = x[static_cast<std::size_t>(a)];
    std::array<double, kBatches> means{};
    double grand = 0;
    for (int b = 0; b < kBatches; ++b) {
      double s = 0;
      for (std::int64_t i = 0; i < per; ++i)
        s += v[static_cast<std::size_t>(first + b * per + i)];
      means[static_cast<std::size_t>(b)] = s / static_cast<double>(per);
      grand += means[static_cast<std::size_t>(b)] / kBatches;
    }
    double var = 0;
    for (double m : means) var += (m - grand) * (m - grand);
    var /= (kBatches - 1);
    const double ratio = var / (sample_cov(a, a) / static_cast<double>(per));
    sum += ratio;
    ++count;
    worst = std::max(worst, ratio);
  }
}

void check_triad(const Triad& x, std::size_t n, const char* what) {
  for (int a = 0; a < 3; ++a) {
    const auto& v = x[static_cast<std::size_t>(a)];
    if (v.size() != n)
      throw Error(std::string("calibrate: the ") + what + " channels must all have " +
                  std::to_string(n) + " samples");
    for (std::size_t i = 0; i < n; ++i)
      if (!std::isfinite(v[i]))
        throw Error(std::string("calibrate: non-finite ") + what + " value at sample " +
                    std::to_string(i + 1));
  }
}

}  // namespace

StaticDetection detect_static_intervals(const CalibrationInput& in, const CalibrationOptions& o) {
  if (!(in.rate_hz > 0) || !std::isfinite(in.rate_hz))
    throw Error("calibrate: the sample rate must be > 0 Hz");
  const std::size_t n = in.accel[0].size();
  check_triad(in.accel, n, "accelerometer");
  const bool gyro = !in.gyro[0].empty();
  if (gyro) check_triad(in.gyro, n, "gyroscope");
  if (!in.temperature_k.empty() && in.temperature_k.size() != n)
    throw Error("calibrate: the temperature column must have one value per sample");
  for (double t : in.temperature_k)
    if (!(t > 0) || !std::isfinite(t))
      throw Error("calibrate: temperatures must be finite and > 0 K (check --temp-unit)");
  if (!(o.window_s > 0) || !(o.min_interval_s > 0))
    throw Error("calibrate: window and minimum interval must be > 0 s");

  StaticDetection d;
  std::int64_t w = std::max<std::int64_t>(kMinWindowSamples,
                                          std::llround(o.window_s * in.rate_hz));
  if (w % 2 == 0) ++w;  // centred windows
  d.window_samples = w;
  const auto samples = static_cast<std::int64_t>(n);
  if (samples < w)
    throw Error("calibrate: the log (" + std::to_string(samples) +
                " samples) is shorter than one detector window (" + std::to_string(w) + ")");
  // Increments: the statistic works on rates (the value per sample times the rate).
  const auto rates = [&](const Triad& x) {
    if (!in.increments) return x;
    Triad r = x;
    for (auto& v : r)
      for (double& e : v) e *= in.rate_hz;
    return r;
  };
  const Triad accel = rates(in.accel);
  const Triad gyr = gyro ? rates(in.gyro) : Triad{};
  const auto sa = window_statistic(accel, w);
  d.accel_floor = quantile_of(sa, kFloorQuantile);
  d.accel_threshold = kStaticThresholdFactor * d.accel_floor;
  std::vector<double> sg;
  if (gyro) {
    sg = window_statistic(gyr, w);
    d.gyro_floor = quantile_of(sg, kFloorQuantile);
    d.gyro_threshold = kStaticThresholdFactor * d.gyro_floor;
  }
  const auto is_static = [&](std::int64_t i) {
    const auto k = static_cast<std::size_t>(i);
    if (!(sa[k] <= d.accel_threshold)) return false;  // NaN (window outside the log) fails
    return !gyro || sg[k] <= d.gyro_threshold;
  };
  const auto min_len = static_cast<std::int64_t>(std::ceil(o.min_interval_s * in.rate_hz));
  double ratio_sum = 0;
  int ratio_count = 0;
  for (std::int64_t i = 0; i < samples;) {
    if (!is_static(i)) {
      ++i;
      continue;
    }
    std::int64_t j = i;
    while (j + 1 < samples && is_static(j + 1)) ++j;
    if (j - i + 1 >= std::max<std::int64_t>(min_len, 3)) {
      StaticInterval s;
      double my_sum = 0, worst = 0;
      int my_count = 0;
      s.first = i;
      s.last = j;
      s.start_s = static_cast<double>(i) / in.rate_hz;
      s.end_s = static_cast<double>(j) / in.rate_hz;
      const double count = static_cast<double>(j - i + 1);
      Eigen::Matrix3d cov;
      mean_and_cov(accel, i, j, s.accel_mean, cov);
      s.accel_cov = cov / count;
      batch_ratio(accel, i, j, cov, my_sum, my_count, worst);
      if (gyro) {
        mean_and_cov(gyr, i, j, s.gyro_mean, s.gyro_sample_cov);
        s.gyro_cov = s.gyro_sample_cov / count;
        batch_ratio(gyr, i, j, s.gyro_sample_cov, my_sum, my_count, worst);
      }
      if (!in.temperature_k.empty()) {
        double t = 0;
        for (std::int64_t k = i; k <= j; ++k) t += in.temperature_k[static_cast<std::size_t>(k)];
        s.temperature_k = t / count;
      }
      if (worst > kMaxBatchRatio) {
        ++d.rejected_moving;
      } else {
        ratio_sum += my_sum;
        ratio_count += my_count;
        d.intervals.push_back(s);
      }
    }
    i = j + 1;
  }
  // Pooled batch-means check: for white noise each ratio has mean 1 and variance 2/(B-1); the
  // pooled mean is applied only when it exceeds 1 by more than 3 of its standard errors, i.e.
  // when the noise is visibly correlated (flicker, random walk) and white-noise standard errors
  // of the means would be too small.
  if (ratio_count > 0) {
    const double pooled = ratio_sum / ratio_count;
    const double se = std::sqrt(2.0 / (kBatches - 1) / ratio_count);
    if (pooled > 1 + 3 * se) {
      d.noise_inflation = pooled;
      for (auto& s : d.intervals) {
        s.accel_cov *= pooled;
        s.gyro_cov *= pooled;
      }
    }
  }
  return d;
}

}  // namespace sigmatau
