// Welch PSD on FFTW and the white-noise density read from it.
//
// Glossary: L segment length, S step between segment starts (L - overlap), K segments averaged,
// w[n] window, U = sum w^2, X_k = sum_n w[n] x[n] e^{-2 pi i k n / L}. One-sided periodogram
// P_k = c_k |X_k|^2 / (f_s U) with c_k = 2 except at DC and Nyquist (c = 1).
// EDF (Welch 1967, eq. for overlapped segments; white-noise assumption):
//   var ratio = (1/K) [1 + 2 sum_{j=1}^{K-1} (1 - j/K) rho(j S)],
//   rho(s) = (sum_n w[n] w[n+s])^2 / U^2,  edf = 2 / var ratio (halved at DC and Nyquist).
// Neighbouring bins of one periodogram are correlated by the window; for white noise the power
// correlation of bins d apart is r_d = |sum_n w[n]^2 e^{-2 pi i d n / L}|^2 / U^2.
#include "sigmatau/psd.hpp"

#include <fftw3.h>

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>
#include <string>
#include <utility>

#include "fftw_planner.hpp"
#include "phase_store.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/sampling_limits.hpp"

namespace sigmatau {
namespace {

/// Bins farther apart than this have a window power correlation below 1e-6 for every window
/// offered, so they are treated as independent.
constexpr int kMaxCorrelatedBins = 8;

/// Automatic band search: log-binned at this many bins per decade ...
constexpr int kBandSearchPerDecade = 5;
/// ... a band is flat when every log bin in it is within this fraction of the band's mean level
/// (plus three standard errors of the bin, sqrt(2/edf) in ln P). Data sheets quote noise density
/// to one or two digits; a level flat to 10 % in PSD reads N to 5 %, while bias instability (PSD
/// ~1/f) or rate random walk (~1/f^2) change the level by far more than that over a band.
constexpr double kFlatTolerance = 0.10;
/// ... and at least this wide [decades], so the level averages many bins.
constexpr double kMinBandDecades = 0.3;
/// The top of the band stays below this fraction of Nyquist, where anti-alias filters roll off.
constexpr double kMaxBandFractionOfNyquist = 0.8;

std::vector<double> make_window(Window window, std::int64_t length) {
  std::vector<double> w(static_cast<std::size_t>(length));
  const double two_pi = 2.0 * std::numbers::pi;
  for (std::int64_t n = 0; n < length; ++n) {
    const double x = two_pi * static_cast<double>(n) / static_cast<double>(length);  // periodic
    switch (window) {
      case Window::hann: w[n] = 0.5 - 0.5 * std::cos(x); break;
      case Window::blackman_harris:  // 4-term, -92 dB (Harris 1978)
        w[n] = 0.35875 - 0.48829 * std::cos(x) + 0.14128 * std::cos(2 * x) -
               0.01168 * std::cos(3 * x);
        break;
      case Window::rectangular: w[n] = 1.0; break;
    }
  }
  return w;
}

/// Power correlation r_d of periodogram bins d apart (d = 1..kMaxCorrelatedBins), white noise.
std::vector<double> compute_bin_correlations(const std::vector<double>& w) {
  double u = 0;
  for (double v : w) u += v * v;
  std::vector<double> r(kMaxCorrelatedBins + 1, 0.0);
  r[0] = 1.0;
  const double length = static_cast<double>(w.size());
  for (int d = 1; d <= kMaxCorrelatedBins; ++d) {
    std::complex<double> sum = 0;
    for (std::size_t n = 0; n < w.size(); ++n) {
      const double phase = -2.0 * std::numbers::pi * d * static_cast<double>(n) / length;
      sum += w[n] * w[n] * std::complex<double>(std::cos(phase), std::sin(phase));
    }
    r[d] = std::norm(sum) / (u * u);
  }
  return r;
}

/// bin_correlations of a window, computed once per window and length in the process: each
/// call costs kMaxCorrelatedBins x length sines and cosines (0.15 s at a 2^20 segment), and
/// analyze asks twice per channel (log binning and the noise-density band).
const std::vector<double>& bin_correlations(Window window, std::int64_t length) {
  static std::mutex mutex;
  static std::map<std::pair<Window, std::int64_t>, std::vector<double>> known;
  std::lock_guard lock(mutex);
  auto it = known.find({window, length});
  if (it == known.end()) {
    it = known.emplace(std::make_pair(window, length),
                       compute_bin_correlations(make_window(window, length)))
             .first;
  }
  return it->second;
}

/// Variance-inflation factor of a mean of `count` consecutive bins (>= 1).
double correlated_mean_factor(const std::vector<double>& r, std::int64_t count) {
  double factor = 1.0;
  for (int d = 1; d <= kMaxCorrelatedBins && d < count; ++d) {
    factor += 2.0 * (1.0 - static_cast<double>(d) / static_cast<double>(count)) * r[d];
  }
  return factor;
}

}  // namespace

Window parse_window(std::string_view text) {
  if (text == "hann" || text == "hanning") return Window::hann;
  if (text == "blackman-harris" || text == "blackmanharris") return Window::blackman_harris;
  if (text == "rectangular" || text == "boxcar" || text == "none") return Window::rectangular;
  throw Error("unknown window \"" + std::string(text) +
              "\"; expected hann, blackman-harris or rectangular");
}

Detrend parse_detrend(std::string_view text) {
  if (text == "none") return Detrend::none;
  if (text == "mean" || text == "constant") return Detrend::mean;
  if (text == "linear") return Detrend::linear;
  throw Error("unknown detrend \"" + std::string(text) + "\"; expected none, mean or linear");
}

std::string_view to_string(Window window) {
  switch (window) {
    case Window::hann: return "hann";
    case Window::blackman_harris: return "blackman-harris";
    case Window::rectangular: return "rectangular";
  }
  return "?";
}

std::string_view to_string(Detrend detrend) {
  switch (detrend) {
    case Detrend::none: return "none";
    case Detrend::mean: return "mean";
    case Detrend::linear: return "linear";
  }
  return "?";
}

std::int64_t default_segment_length(std::int64_t samples) {
  std::int64_t length = 16;
  while (length * 2 <= samples / kDefaultSegmentDivisor && length * 2 <= kMaxDefaultSegmentLength) {
    length *= 2;
  }
  return length;
}

struct WelchAccumulator::Impl {
  double rate_hz = 0;
  WelchOptions options;
  std::int64_t length = 0;
  std::int64_t step = 0;
  std::vector<double> window;
  double window_power = 0;  // U
  std::vector<double> pending;
  double* in = nullptr;
  fftw_complex* out = nullptr;
  fftw_plan plan = nullptr;
  std::vector<double> power_sum;  // sum over segments of |X_k|^2
  std::int64_t segments = 0;
  /// The segments are transformed divided by this power of two, chosen from the first segment
  /// (phase_store.hpp value_scale_for: 1 unless its largest |x| is beyond about 1e-100..1e100,
  /// so that |X_k|^2 neither overflows nor underflows); 0 before the first segment.
  double value_scale = 0.0;
  double largest = 0.0;  // largest |x| transformed, for the message of an unrepresentable PSD

  ~Impl() {
    std::lock_guard lock(detail::fftw_planner_mutex());
    if (plan) fftw_destroy_plan(plan);
    fftw_free(in);
    fftw_free(out);
  }

  /// The segment-sized buffers and the plan, made when the first segment is complete: a
  /// segment longer than the log then costs nothing before result() says so (a segment of 1e8
  /// on a 3000-sample log spent 1.5 GB and 16 s, one of 2^31 - 1 ended in bad_alloc).
  void allocate() {
    window = make_window(options.window, length);
    for (double v : window) window_power += v * v;
    power_sum.assign(static_cast<std::size_t>(length / 2 + 1), 0.0);
    std::lock_guard lock(detail::fftw_planner_mutex());
    in = fftw_alloc_real(static_cast<std::size_t>(length));
    out = fftw_alloc_complex(static_cast<std::size_t>(length / 2 + 1));
    if (!in || !out) throw Error("PSD: out of memory for a segment of " + std::to_string(length));
    // FFTW_ESTIMATE: planning cost is negligible and results do not depend on timing measurements.
    plan = fftw_plan_dft_r2c_1d(static_cast<int>(length), in, out, FFTW_ESTIMATE);
  }

  void process_segment(const double* x) {
    double segment_largest = 0.0;
    for (std::int64_t n = 0; n < length; ++n) segment_largest = std::max(segment_largest, std::fabs(x[n]));
    largest = std::max(largest, segment_largest);
    if (value_scale == 0.0) value_scale = detail::value_scale_for(segment_largest);
    if (value_scale == 1.0) {
      for (std::int64_t n = 0; n < length; ++n) in[n] = x[n];
    } else {
      for (std::int64_t n = 0; n < length; ++n) in[n] = x[n] / value_scale;
    }
    if (options.detrend == Detrend::mean) {
      double mean = 0;
      for (std::int64_t n = 0; n < length; ++n) mean += in[n];
      mean /= static_cast<double>(length);
      for (std::int64_t n = 0; n < length; ++n) in[n] -= mean;
    } else if (options.detrend == Detrend::linear) {
      // Least squares a + b (n - c), c the centre, so the two normal equations decouple.
      const double c = 0.5 * static_cast<double>(length - 1);
      double sy = 0, sny = 0, snn = 0;
      for (std::int64_t n = 0; n < length; ++n) {
        const double t = static_cast<double>(n) - c;
        sy += in[n];
        sny += t * in[n];
        snn += t * t;
      }
      const double a = sy / static_cast<double>(length);
      const double b = sny / snn;
      for (std::int64_t n = 0; n < length; ++n) in[n] -= a + b * (static_cast<double>(n) - c);
    }
    for (std::int64_t n = 0; n < length; ++n) in[n] *= window[n];
    fftw_execute(plan);
    for (std::size_t k = 0; k < power_sum.size(); ++k) {
      power_sum[k] += out[k][0] * out[k][0] + out[k][1] * out[k][1];
    }
    ++segments;
  }
};

WelchAccumulator::WelchAccumulator(double rate_hz, const WelchOptions& options,
                                   std::int64_t expected_samples)
    : impl_(std::make_unique<Impl>()) {
  checked_rate_hz(rate_hz, "PSD: rate_hz");
  if (!(options.overlap >= 0 && options.overlap < 1)) {
    throw Error("PSD: overlap must be in [0, 1), got " + std::to_string(options.overlap));
  }
  std::int64_t length = options.segment_length;
  if (length == 0) {
    if (expected_samples <= 0) throw Error("PSD: give a segment length (--segment N)");
    length = default_segment_length(expected_samples);
  }
  if (length < 4) throw Error("PSD: segment length must be >= 4 samples, got " + std::to_string(length));
  if (length > kMaxSegmentLength) {
    throw Error("PSD: segment_length must be at most " + std::to_string(kMaxSegmentLength) +
                " samples (FFTW's transform length is an int), got " + std::to_string(length));
  }
  auto& d = *impl_;
  d.rate_hz = rate_hz;
  d.options = options;
  d.length = length;
  d.step = std::max<std::int64_t>(1, length - static_cast<std::int64_t>(std::llround(options.overlap * static_cast<double>(length))));
}

WelchAccumulator::~WelchAccumulator() = default;
WelchAccumulator::WelchAccumulator(WelchAccumulator&&) noexcept = default;
WelchAccumulator& WelchAccumulator::operator=(WelchAccumulator&&) noexcept = default;

void WelchAccumulator::add(std::span<const double> samples) {
  auto& d = *impl_;
  std::size_t used = 0;
  const auto length = static_cast<std::size_t>(d.length);
  const auto step = static_cast<std::size_t>(d.step);
  while (used < samples.size()) {
    const std::size_t take = std::min(samples.size() - used, length - d.pending.size());
    d.pending.insert(d.pending.end(), samples.begin() + static_cast<std::ptrdiff_t>(used),
                     samples.begin() + static_cast<std::ptrdiff_t>(used + take));
    used += take;
    if (d.pending.size() == length) {
      if (!d.plan) d.allocate();
      d.process_segment(d.pending.data());
      if (step >= length) {
        d.pending.clear();
        // Skip the samples between segments when the step exceeds the length (not reachable
        // with overlap >= 0, kept for clarity of the invariant pending.size() < length).
      } else {
        d.pending.erase(d.pending.begin(), d.pending.begin() + static_cast<std::ptrdiff_t>(step));
      }
    }
  }
}

std::int64_t WelchAccumulator::segments() const { return impl_->segments; }

PsdCurve WelchAccumulator::result() const {
  const auto& d = *impl_;
  if (d.segments == 0) {
    throw Error("PSD: the log is shorter than one segment of " + std::to_string(d.length) +
                " samples; use a shorter --segment");
  }
  PsdCurve curve;
  curve.rate_hz = d.rate_hz;
  curve.segment_length = d.length;
  curve.segments = d.segments;
  curve.window = d.options.window;
  curve.overlap = d.options.overlap;

  // Welch's EDF for K overlapped segments (white noise).
  double ratio = 1.0;
  const double k_segments = static_cast<double>(d.segments);
  for (std::int64_t j = 1; j < d.segments; ++j) {
    const std::int64_t shift = j * d.step;
    if (shift >= d.length) break;
    double c = 0;
    for (std::int64_t n = 0; n + shift < d.length; ++n) c += d.window[n] * d.window[n + shift];
    const double rho = (c * c) / (d.window_power * d.window_power);
    ratio += 2.0 * (1.0 - static_cast<double>(j) / k_segments) * rho;
  }
  const double edf_bin = 2.0 * k_segments / ratio;

  const std::size_t bins = d.power_sum.size();
  const double scale = 1.0 / (d.rate_hz * d.window_power * k_segments);
  for (std::size_t k = 0; k < bins; ++k) {
    const bool edge = (k == 0) || (d.length % 2 == 0 && k == bins - 1);
    curve.frequency_hz.push_back(static_cast<double>(k) * d.rate_hz / static_cast<double>(d.length));
    // Multiplied back by value_scale^2 in two steps (its square alone may overflow); 1 for
    // ordinary data, where this changes no bit.
    const double value = (edge ? 1.0 : 2.0) * scale * d.power_sum[k] * d.value_scale * d.value_scale;
    if (!std::isfinite(value) || (d.power_sum[k] > 0 && value < std::numeric_limits<double>::min())) {
      char largest[32];
      std::snprintf(largest, sizeof largest, "%.3g", d.largest);
      throw Error(std::string("PSD: the samples reach |x| = ") + largest +
                  ", whose power spectral density is beyond the range of a double (about "
                  "1e-308 to 1e308 unit^2/Hz); a PSD is computed where |x|^2 / rate stays in that "
                  "range (|x| from about 1e-150 to 1e150 at 1 Hz): express the samples in "
                  "another unit");
    }
    curve.psd.push_back(value);
    curve.edf.push_back(edge ? edf_bin / 2 : edf_bin);
  }
  return curve;
}

PsdCurve welch_psd(std::span<const double> samples, double rate_hz, const WelchOptions& options) {
  WelchAccumulator accumulator(rate_hz, options, static_cast<std::int64_t>(samples.size()));
  accumulator.add(samples);
  return accumulator.result();
}

PsdCurve log_binned(const PsdCurve& psd, int per_decade) {
  if (per_decade < 1) throw Error("log binning needs at least 1 bin per decade");
  const std::vector<double>& r = bin_correlations(psd.window, psd.segment_length);
  PsdCurve binned = psd;
  binned.frequency_hz.clear();
  binned.psd.clear();
  binned.edf.clear();
  const std::size_t n = psd.psd.size();
  std::size_t k = 1;  // DC dropped
  while (k < n) {
    // Bin edges at 10^(i / per_decade): find the edge above f_k.
    const double position = std::log10(psd.frequency_hz[k]) * per_decade;
    const double upper = std::pow(10.0, (std::floor(position + 1e-9) + 1.0) / per_decade);
    std::size_t end = k;
    double f_sum = 0, p_sum = 0, edf_sum = 0;
    while (end < n && psd.frequency_hz[end] < upper) {
      f_sum += psd.frequency_hz[end];
      p_sum += psd.psd[end];
      edf_sum += psd.edf[end];
      ++end;
    }
    if (end == k) {  // guard: always advance
      f_sum = psd.frequency_hz[k];
      p_sum = psd.psd[k];
      edf_sum = psd.edf[k];
      end = k + 1;
    }
    const auto count = static_cast<std::int64_t>(end - k);
    binned.frequency_hz.push_back(f_sum / static_cast<double>(count));
    binned.psd.push_back(p_sum / static_cast<double>(count));
    binned.edf.push_back(edf_sum / correlated_mean_factor(r, count));
    k = end;
  }
  return binned;
}

namespace {

struct BandLevel {
  double level = 0;  // mean one-sided PSD over the band
  double edf = 0;
  std::int64_t bins = 0;
};

BandLevel band_level(const PsdCurve& psd, const std::vector<double>& r, double f1, double f2) {
  BandLevel b;
  double edf_sum = 0;
  for (std::size_t k = 1; k < psd.psd.size(); ++k) {
    if (psd.frequency_hz[k] >= f1 && psd.frequency_hz[k] <= f2) {
      b.level += psd.psd[k];
      edf_sum += psd.edf[k];
      ++b.bins;
    }
  }
  if (b.bins > 0) {
    b.level /= static_cast<double>(b.bins);
    b.edf = edf_sum / correlated_mean_factor(r, b.bins);
  }
  return b;
}

/// The widest band of the log-binned PSD that is flat (see kFlatTolerance).
std::optional<std::pair<double, double>> detect_flat_band(const PsdCurve& psd) {
  const PsdCurve binned = log_binned(psd, kBandSearchPerDecade);
  const double f_max = kMaxBandFractionOfNyquist * psd.rate_hz / 2;
  std::vector<double> x, y, sigma;
  for (std::size_t i = 0; i < binned.psd.size(); ++i) {
    if (binned.frequency_hz[i] > f_max || !(binned.psd[i] > 0)) continue;
    x.push_back(std::log(binned.frequency_hz[i]));
    y.push_back(std::log(binned.psd[i]));
    sigma.push_back(std::sqrt(2.0 / binned.edf[i]));  // standard error of ln P
  }
  std::optional<std::pair<double, double>> best;
  double best_width = 0;
  const double min_width = kMinBandDecades * std::log(10.0);
  const double tolerance = std::log1p(kFlatTolerance);
  for (std::size_t a = 0; a < x.size(); ++a) {
    double sw = 0, swy = 0;
    for (std::size_t b = a; b < x.size(); ++b) {
      const double w = 1.0 / (sigma[b] * sigma[b]);
      sw += w;
      swy += w * y[b];
      const double width = x[b] - x[a];
      if (width < min_width || width <= best_width) continue;
      const double mean = swy / sw;
      bool flat = true;
      for (std::size_t i = a; i <= b && flat; ++i) {
        flat = std::abs(y[i] - mean) <= tolerance + 3.0 * sigma[i];
      }
      if (flat) {
        best_width = width;
        best = std::make_pair(std::exp(x[a]), std::exp(x[b]));
      }
    }
  }
  return best;
}

}  // namespace

NoiseDensity noise_density(const PsdCurve& psd, std::optional<std::pair<double, double>> band,
                           double confidence) {
  if (!(confidence > 0 && confidence < 1)) {
    throw Error("confidence level must be between 0 and 1, got " + std::to_string(confidence));
  }
  const double nyquist = psd.rate_hz / 2;
  NoiseDensity result;
  if (band) {
    if (!(band->first > 0 && band->second > band->first && band->second <= nyquist * (1 + 1e-12))) {
      throw Error("noise-density band " + std::to_string(band->first) + ":" +
                  std::to_string(band->second) + " Hz must satisfy 0 < f1 < f2 <= Nyquist (" +
                  std::to_string(nyquist) + " Hz)");
    }
  } else {
    band = detect_flat_band(psd);
    result.band_detected = band.has_value();
    if (!band) band = std::make_pair(0.1 * kMaxBandFractionOfNyquist * nyquist,
                                     kMaxBandFractionOfNyquist * nyquist);
  }
  const std::vector<double>& r = bin_correlations(psd.window, psd.segment_length);
  const BandLevel level = band_level(psd, r, band->first, band->second);
  if (level.bins == 0) {
    throw Error("noise-density band " + std::to_string(band->first) + ":" +
                std::to_string(band->second) + " Hz holds no PSD bin (bin width " +
                std::to_string(psd.rate_hz / static_cast<double>(psd.segment_length)) + " Hz)");
  }
  boost::math::chi_squared chi2(level.edf);
  const double upper_q = boost::math::quantile(chi2, (1 + confidence) / 2);
  const double lower_q = boost::math::quantile(chi2, (1 - confidence) / 2);
  result.value = std::sqrt(level.level / 2);
  result.ci_low = std::sqrt(level.level * level.edf / upper_q / 2);
  result.ci_high = std::sqrt(level.level * level.edf / lower_q / 2);
  result.one_sided_asd = std::sqrt(level.level);
  result.band_low_hz = band->first;
  result.band_high_hz = band->second;
  result.edf = level.edf;
  return result;
}

}  // namespace sigmatau
