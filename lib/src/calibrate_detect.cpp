// Static-interval detector for multi-position calibration (calibrate.hpp), streaming over the
// samples in three passes (the floors, the runs and their means, the covariances of the runs), so
// that a log in a temporary file (calibrate_log.hpp) is never held in memory; the sums are taken
// in the order of the former whole-log code, so the intervals are the same to the last bit.
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
#include "sigmatau/sampling_limits.hpp"

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
/// Long dwells have long batches (a tenth of the dwell), over which a MEMS bias drifts: with a
/// BMI088-class pair (accelerometer flicker B = 0.1 mg) and 600 s dwells every interval's mean
/// ratio is 5-18, and the fixed limit refused them all as slow motion. The limit is therefore kMaxBatchRatio times the median of
/// the candidates' mean ratios (a calibration log is mostly static dwells, so the median is the
/// sensor's own drift at this dwell length), that factor held to 1..kMaxDriftFactor.
constexpr double kMaxDriftFactor = 100;
/// What tells motion from drift once the limit is raised: a turn moves the batch means by as much
/// as it spreads the samples, so their variance ratio nears its ceiling, the samples per batch
/// (a log tumbling at 20 deg/s: 0.9-1.0 of it), while a drifting bias stays a small part of the
/// samples' spread (600 s dwells: 0.002). Past kMaxBatchRatio, a run whose worst ratio is over
/// this fraction of that ceiling is moving whatever the limit.
constexpr double kMaxTrendFraction = 0.5;

/// Values of sample r of `rows` converted for the detector: accelerometer and gyroscope as
/// rates (increments times the rate, as the whole-log code did), temperature as stored.
struct Converted {
  std::array<double, 7> v{};
};

Converted converted(const detail::SampleRows& rows, std::int64_t r, bool gyro, bool temperature,
                    bool increments, double rate_hz) {
  Converted c;
  for (int a = 0; a < 3; ++a) {
    const auto ua = static_cast<std::size_t>(a);
    c.v[ua] = rows.value(detail::kAccelChannel + a, r);
    if (increments) c.v[ua] *= rate_hz;
    if (gyro) {
      c.v[3 + ua] = rows.value(detail::kGyroChannel + a, r);
      if (increments) c.v[3 + ua] *= rate_hz;
    }
  }
  if (temperature) c.v[6] = rows.value(detail::kTemperatureChannel, r);
  return c;
}

/// First invalid sample of each kind (-1: none), found while streaming; reported in the order
/// accelerometer, gyroscope, temperature.
struct Invalid {
  std::int64_t accel = -1, gyro = -1, temperature = -1;
  void check(const Converted& c, std::int64_t i, bool gyro_present, bool temperature_present) {
    for (int a = 0; a < 3; ++a) {
      if (accel < 0 && !std::isfinite(c.v[static_cast<std::size_t>(a)])) accel = i;
      if (gyro_present && gyro < 0 && !std::isfinite(c.v[static_cast<std::size_t>(3 + a)]))
        gyro = i;
    }
    if (temperature_present && temperature < 0 && !(c.v[6] > 0 && std::isfinite(c.v[6])))
      temperature = i;
  }
  void raise() const {
    const auto at = [](std::int64_t i) { return std::to_string(i + 1); };
    if (accel >= 0) throw Error("calibrate: non-finite accelerometer value at sample " + at(accel));
    if (gyro >= 0) throw Error("calibrate: non-finite gyroscope value at sample " + at(gyro));
    if (temperature >= 0)
      throw Error("calibrate: temperatures must be finite and > 0 K (check --temp-unit)");
  }
};

/// Streams every sample once: calls sample(i, c) on each sample i as converted, and statistic(i,
/// sa, sg) for each i in [h, n-h) in ascending order (sg = 0 without gyroscope) as soon as its
/// window is complete, i.e. right after sample(i + h, ...).
template <class OnSample, class OnStatistic>
void stream_statistics(const detail::CalibrationSamples& in, std::int64_t w, OnSample&& sample,
                       OnStatistic&& statistic) {
  const bool gyro = in.has_gyro(), temperature = in.has_temperature();
  const std::int64_t h = (w - 1) / 2;
  detail::WindowStatistic wa(w), wg(w);
  in.for_each(0, in.rows(), [&](const detail::SampleRows& rows) {
    for (std::int64_t r = 0; r < rows.count; ++r) {
      const std::int64_t i = rows.first + r;
      const Converted c = converted(rows, r, gyro, temperature, in.increments(), in.rate_hz());
      sample(i, c);
      const bool ready = wa.push(c.v.data(), 1);
      if (gyro) wg.push(c.v.data() + 3, 1);
      if (ready) statistic(i - h, wa.value(), gyro ? wg.value() : 0.0);
    }
  });
}

/// A run of static samples with the sums of its means (same order as the whole-log code).
struct Run {
  std::int64_t first = 0, last = 0;
  Eigen::Vector3d accel_sum = Eigen::Vector3d::Zero(), gyro_sum = Eigen::Vector3d::Zero();
  double temperature_sum = 0;
};

/// Covariance and batch sums of one candidate interval, from its means.
struct Spread {
  Eigen::Matrix3d accel = Eigen::Matrix3d::Zero(), gyro = Eigen::Matrix3d::Zero();
  std::array<std::array<double, kBatches>, 6> batch{};  // sums per axis (accel, gyro) and batch
};

Spread spread_of(const detail::CalibrationSamples& in, const StaticInterval& s) {
  Spread out;
  const bool gyro = in.has_gyro();
  const std::int64_t n = s.last - s.first + 1;
  const std::int64_t per = n / kBatches;
  in.for_each(s.first, s.last + 1, [&](const detail::SampleRows& rows) {
    for (std::int64_t r = 0; r < rows.count; ++r) {
      const Converted c = converted(rows, r, gyro, false, in.increments(), in.rate_hz());
      const std::int64_t k = rows.first + r - s.first;
      Eigen::Vector3d d;
      for (int a = 0; a < 3; ++a) d[a] = c.v[static_cast<std::size_t>(a)] - s.accel_mean[a];
      out.accel += d * d.transpose();
      if (gyro) {
        for (int a = 0; a < 3; ++a) d[a] = c.v[static_cast<std::size_t>(3 + a)] - s.gyro_mean[a];
        out.gyro += d * d.transpose();
      }
      if (per >= 2 && k < per * kBatches) {
        auto& b = out.batch;
        const auto batch = static_cast<std::size_t>(k / per);
        for (std::size_t a = 0; a < (gyro ? 6u : 3u); ++a) b[a][batch] += c.v[a];
      }
    }
  });
  out.accel /= static_cast<double>(n - 1);
  out.gyro /= static_cast<double>(n - 1);
  return out;
}

/// Ratio of the observed variance of batch means to the white-noise prediction, per axis, summed
/// into `sum` with its count (the caller pools them).
void batch_ratio(const std::array<double, kBatches>& sums, std::int64_t n, double sample_var,
                 double& sum, int& count, double& worst) {
  const std::int64_t per = n / kBatches;
  if (per < 2) return;
  if (!(sample_var > 0)) return;
  std::array<double, kBatches> means{};
  double grand = 0;
  for (int b = 0; b < kBatches; ++b) {
    means[static_cast<std::size_t>(b)] =
        sums[static_cast<std::size_t>(b)] / static_cast<double>(per);
    grand += means[static_cast<std::size_t>(b)] / kBatches;
  }
  double var = 0;
  for (double m : means) var += (m - grand) * (m - grand);
  var /= (kBatches - 1);
  const double ratio = var / (sample_var / static_cast<double>(per));
  sum += ratio;
  ++count;
  worst = std::max(worst, ratio);
}

}  // namespace

StaticDetection detect_static_intervals(const CalibrationInput& in, const CalibrationOptions& o) {
  checked_rate_hz(in.rate_hz, "calibrate: rate_hz");
  return detail::detect_static(detail::InputSamples(in), o);
}

namespace detail {

StaticDetection detect_static(const CalibrationSamples& in, const CalibrationOptions& o) {
  checked_rate_hz(in.rate_hz(), "calibrate: rate_hz");
  const bool gyro = in.has_gyro();
  const bool temperature = in.has_temperature();
  const std::int64_t samples = in.rows();
  const auto validate = [&] {
    Invalid bad;
    in.for_each(0, samples, [&](const SampleRows& rows) {
      for (std::int64_t r = 0; r < rows.count; ++r)
        bad.check(converted(rows, r, gyro, temperature, in.increments(), in.rate_hz()),
                  rows.first + r, gyro, temperature);
    });
    bad.raise();
  };
  if (!(o.window_s > 0) || !(o.min_interval_s > 0)) {
    validate();
    throw Error("calibrate: window and minimum interval must be > 0 s");
  }

  StaticDetection d;
  std::int64_t w = std::max<std::int64_t>(kMinWindowSamples,
                                          std::llround(o.window_s * in.rate_hz()));
  if (w % 2 == 0) ++w;  // centred windows
  d.window_samples = w;
  if (samples < w) {
    validate();
    throw Error("calibrate: the log (" + std::to_string(samples) +
                " samples) is shorter than one detector window (" + std::to_string(w) + ")");
  }
  // Pass 1 checks the values and starts the selection of the floors; further passes (only for
  // logs of more than ~2 million samples) narrow it down.
  const std::int64_t windows = samples - (w - 1);
  StreamQuantile qa(kFloorQuantile, windows), qg(kFloorQuantile, gyro ? windows : 0);
  Invalid bad;
  stream_statistics(
      in, w, [&](std::int64_t i, const Converted& c) { bad.check(c, i, gyro, temperature); },
      [&](std::int64_t, double sa, double sg) {
        qa.add(sa);
        if (gyro) qg.add(sg);
      });
  bad.raise();
  bool done = qa.end_pass();
  if (gyro) done = qg.end_pass() && done;
  while (!done) {
    stream_statistics(
        in, w, [](std::int64_t, const Converted&) {},
        [&](std::int64_t, double sa, double sg) {
          if (!qa.done()) qa.add(sa);
          if (gyro && !qg.done()) qg.add(sg);
        });
    done = qa.done() || qa.end_pass();
    if (gyro && !qg.done()) done = qg.end_pass() && done;
  }
  d.accel_floor = qa.value();
  d.accel_threshold = kStaticThresholdFactor * d.accel_floor;
  if (gyro) {
    d.gyro_floor = qg.value();
    d.gyro_threshold = kStaticThresholdFactor * d.gyro_floor;
  }

  // Pass 2: the runs of static samples and the sums of their means. A sample's statistic is
  // known h samples after it, so the samples wait in a ring of h + 1.
  const std::int64_t h = (w - 1) / 2;
  const auto min_len = static_cast<std::int64_t>(std::ceil(o.min_interval_s * in.rate_hz()));
  const std::int64_t keep = std::max<std::int64_t>(min_len, 3);
  std::vector<Converted> ring(static_cast<std::size_t>(h + 1));
  std::vector<StaticInterval> candidates;
  Run run;
  bool in_run = false;
  const auto close = [&] {
    in_run = false;
    if (run.last - run.first + 1 < keep) return;
    StaticInterval s;
    s.first = run.first;
    s.last = run.last;
    s.start_s = static_cast<double>(run.first) / in.rate_hz();
    s.end_s = static_cast<double>(run.last) / in.rate_hz();
    const double count = static_cast<double>(run.last - run.first + 1);
    s.accel_mean = run.accel_sum / count;
    if (gyro) s.gyro_mean = run.gyro_sum / count;
    if (temperature) s.temperature_k = run.temperature_sum / count;
    candidates.push_back(s);
  };
  stream_statistics(
      in, w,
      [&](std::int64_t i, const Converted& c) { ring[static_cast<std::size_t>(i % (h + 1))] = c; },
      [&](std::int64_t i, double sa, double sg) {
        const bool is_static = sa <= d.accel_threshold && (!gyro || sg <= d.gyro_threshold);
        if (!is_static) {
          if (in_run) close();
          return;
        }
        if (!in_run) {
          run = Run{};
          run.first = i;
          in_run = true;
        }
        run.last = i;
        const Converted& c = ring[static_cast<std::size_t>(i % (h + 1))];
        for (int a = 0; a < 3; ++a) {
          run.accel_sum[a] += c.v[static_cast<std::size_t>(a)];
          if (gyro) run.gyro_sum[a] += c.v[static_cast<std::size_t>(3 + a)];
        }
        if (temperature) run.temperature_sum += c.v[6];
      });
  if (in_run) close();

  // Pass 3, over the candidates only: covariances and the batch-means ratios, then the check.
  struct Ratios {
    double sum = 0, worst = 0;
    int count = 0;
  };
  std::vector<Ratios> ratios(candidates.size());
  std::vector<double> mean_ratios;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    StaticInterval& s = candidates[k];
    Ratios& r = ratios[k];
    const Spread sp = spread_of(in, s);
    const std::int64_t n = s.last - s.first + 1;
    const double count = static_cast<double>(n);
    s.accel_cov = sp.accel / count;
    for (int a = 0; a < 3; ++a)
      batch_ratio(sp.batch[static_cast<std::size_t>(a)], n, sp.accel(a, a), r.sum, r.count,
                  r.worst);
    if (gyro) {
      s.gyro_sample_cov = sp.gyro;
      s.gyro_cov = s.gyro_sample_cov / count;
      for (int a = 0; a < 3; ++a)
        batch_ratio(sp.batch[static_cast<std::size_t>(3 + a)], n, sp.gyro(a, a), r.sum, r.count,
                    r.worst);
    }
    if (r.count > 0) mean_ratios.push_back(r.sum / r.count);
  }
  double drift = 1;
  if (!mean_ratios.empty()) {
    const auto mid = mean_ratios.begin() + static_cast<std::ptrdiff_t>(mean_ratios.size() / 2);
    std::nth_element(mean_ratios.begin(), mid, mean_ratios.end());
    drift = std::clamp(*mid, 1.0, kMaxDriftFactor);
  }
  d.batch_ratio_limit = kMaxBatchRatio * drift;
  double ratio_sum = 0;
  int ratio_count = 0;
  for (std::size_t k = 0; k < candidates.size(); ++k) {
    const double per = static_cast<double>((candidates[k].last - candidates[k].first + 1) / kBatches);
    const double worst = ratios[k].worst;
    const bool trend = worst > kMaxBatchRatio && (worst - 1) > kMaxTrendFraction * (per - 1);
    if (worst > d.batch_ratio_limit || trend) {
      ++d.rejected_moving;
    } else {
      ratio_sum += ratios[k].sum;
      ratio_count += ratios[k].count;
      d.intervals.push_back(candidates[k]);
    }
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

}  // namespace detail
}  // namespace sigmatau
