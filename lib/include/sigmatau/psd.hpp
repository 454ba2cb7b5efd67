#pragma once
/// \file psd.hpp
/// Power spectral density by Welch's method (P. D. Welch, "The use of fast Fourier transform for
/// the estimation of power spectra", IEEE Trans. Audio Electroacoust. 15(2), 1967) on FFTW,
/// streaming over segments, and the white-noise density read from it.
///
/// Conventions: the PSD is ONE-SIDED, in unit^2/Hz: white noise of per-sample standard deviation
/// sigma at rate f_s has the level 2 sigma^2 / f_s on 0 < f < f_s/2. The noise density N that
/// data sheets, Kalibr and Allan variance use (AVAR = N^2/tau) is the square root of the
/// TWO-SIDED level: N = sqrt(psd/2), so sigma = N sqrt(f_s); the one-sided amplitude spectral
/// density is sqrt(2) N (../shared/THEORY.md, section 0, facts 1-3).

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace sigmatau {

/// Taper applied to each Welch segment.
enum class Window { hann, blackman_harris, rectangular };
/// What is removed from each Welch segment before the window: nothing, its mean, or its
/// least-squares line.
enum class Detrend { none, mean, linear };

/// "hann" | "blackman-harris" | "rectangular"; "none" | "mean" | "linear". Throw Error otherwise.
Window parse_window(std::string_view text);
Detrend parse_detrend(std::string_view text);
std::string_view to_string(Window window);
std::string_view to_string(Detrend detrend);

/// How a Welch PSD averages its segments.
struct WelchOptions {
  std::int64_t segment_length = 0;  ///< samples per segment; 0: default_segment_length of the
                                    ///< log length
  double overlap = 0.5;             ///< fraction of a segment shared with the next, in [0, 1)
  Window window = Window::hann;
  Detrend detrend = Detrend::mean;  ///< applied to each segment before windowing
};

/// A one-sided PSD.
struct PsdCurve {
  double rate_hz = 0;                 ///< sample rate of the series [Hz]
  std::int64_t segment_length = 0;    ///< samples per Welch segment
  std::int64_t segments = 0;          ///< number of averaged segments
  Window window = Window::hann;       ///< taper used
  double overlap = 0;                 ///< fraction of a segment shared with the next, in [0, 1)
  std::vector<double> frequency_hz;   ///< bin centres [Hz]
  std::vector<double> psd;            ///< one-sided, unit^2/Hz
  std::vector<double> edf;            ///< equivalent degrees of freedom of each value
};

/// Longest segment default_segment_length chooses [samples].
inline constexpr std::int64_t kMaxDefaultSegmentLength = std::int64_t{1} << 20;
/// default_segment_length takes the largest power of two not above samples / this.
inline constexpr std::int64_t kDefaultSegmentDivisor = 8;
/// The smallest sample count whose default segment length is kMaxDefaultSegmentLength (2^23):
/// from there on the default no longer depends on the count.
inline constexpr std::int64_t kDefaultSegmentSaturation =
    kDefaultSegmentDivisor * kMaxDefaultSegmentLength;

/// Longest segment accepted [samples]: FFTW's transform length is an int.
inline constexpr std::int64_t kMaxSegmentLength = 2147483647;

/// Segment length used when WelchOptions::segment_length is 0: the largest power of two not
/// above samples / kDefaultSegmentDivisor (so at least ~15 segments at 50 % overlap), clamped
/// to [16, kMaxDefaultSegmentLength].
std::int64_t default_segment_length(std::int64_t samples);

/// Streaming Welch accumulator: feed samples in blocks of any size; result() is available at any
/// time (once one segment is complete). Owns its FFTW plan and buffers.
class WelchAccumulator {
 public:
  /// Throws Error on a rate outside checked_rate_hz's range, segment_length < 4 (after
  /// choosing the default) or above kMaxSegmentLength, or overlap outside [0, 1).
  /// segment_length 0 needs `expected_samples` to choose it. The segment's buffers (about 36
  /// bytes per sample of the segment: samples, window, FFT input and output, power sums) are
  /// allocated once the first segment is complete, so a segment longer than the samples fed
  /// costs only those samples.
  WelchAccumulator(double rate_hz, const WelchOptions& options, std::int64_t expected_samples = 0);
  ~WelchAccumulator();
  WelchAccumulator(WelchAccumulator&&) noexcept;
  WelchAccumulator& operator=(WelchAccumulator&&) noexcept;

  void add(std::span<const double> samples);
  std::int64_t segments() const;
  /// The averaged PSD. Throws Error when no complete segment was seen ("log shorter than one
  /// segment of N samples").
  PsdCurve result() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Welch PSD of a whole series (convenience over WelchAccumulator).
PsdCurve welch_psd(std::span<const double> samples, double rate_hz, const WelchOptions& options);

/// Welch PSD over several contiguous stretches of one channel (rate samples at rate_hz [Hz],
/// e.g. the segments of a log read with GapPolicy::split): every stretch at least one Welch
/// segment long is averaged on its own, and the stretches' PSDs are combined weighted by their
/// number of Welch segments, which is the Welch average over every window that fits inside a
/// stretch (no window spans a gap); EDFs add. The segment length is options.segment_length, or
/// default_segment_length of the longest stretch when 0. Throws Error when no stretch holds one
/// Welch segment, and like welch_psd otherwise.
PsdCurve welch_psd_stretches(std::span<const std::span<const double>> stretches, double rate_hz,
                             const WelchOptions& options);

/// Averages a PSD into `per_decade` logarithmically spaced bins (for plots); each output value
/// is the mean of the input bins it covers, its frequency their mean and its EDF their sum
/// (corrected for window correlation between neighbouring bins). DC is dropped.
PsdCurve log_binned(const PsdCurve& psd, int per_decade);

/// White-noise density read from a flat band of the PSD.
struct NoiseDensity {
  double value = 0;          ///< N = sqrt(two-sided level) [unit/sqrt(Hz)] (data-sheet / Kalibr)
  double ci_low = 0;         ///< lower confidence bound of N at the requested level [unit/sqrt(Hz)]
  double ci_high = 0;        ///< upper confidence bound of N [unit/sqrt(Hz)]
  double one_sided_asd = 0;  ///< sqrt(one-sided level) = sqrt(2) N [unit/sqrt(Hz)]
  double band_low_hz = 0;    ///< lower edge of the band averaged [Hz]
  double band_high_hz = 0;   ///< upper edge of the band averaged [Hz]
  double edf = 0;            ///< equivalent degrees of freedom of the band average
  bool band_detected = false;  ///< true when the band was found automatically
};

/// Reads the noise density over [band_low_hz, band_high_hz] when given, otherwise over the
/// widest flat band found automatically (5 log bins per decade, every bin within 10 % of the
/// band's level plus its statistical error, at least 0.3 decades, below 0.8 Nyquist; falls back
/// to the decade below 0.8 Nyquist). Throws Error when the band holds
/// no bins or lies outside (0, Nyquist].
NoiseDensity noise_density(const PsdCurve& psd, std::optional<std::pair<double, double>> band,
                           double confidence = 0.683);

}  // namespace sigmatau
