// Exact L-tap Kasdin flicker by FFT overlap-save.
//
// Glossary: L taps (a power of two); block b = output samples [bL, (b+1)L); the input segment is
// w[(b-1)L .. (b+1)L) (2L unit normals); the 2L-point circular convolution with h (zero-padded)
// is exact (no wrap-around) for outputs 2L-1 >= i >= L-1, of which [L, 2L) are kept.
// Kasdin 1995, Proc. IEEE 83(5), eq. for the fractional integrator (1 - z^-1)^(-alpha/2), alpha=1.
#include "simulate_flicker.hpp"

#include <fftw3.h>

#include <mutex>

#include "fftw_planner.hpp"
#include <new>

#include "simulate_random.hpp"

namespace sigmatau::detail {
FlickerFilter::Workspace::Workspace(std::int64_t taps) {
  time = fftw_alloc_real(static_cast<std::size_t>(2 * taps));
  freq = fftw_alloc_complex(static_cast<std::size_t>(taps + 1));
  if (!time || !freq) throw std::bad_alloc();
}

FlickerFilter::Workspace::~Workspace() {
  fftw_free(time);
  fftw_free(freq);
}

FlickerFilter::FlickerFilter(std::int64_t taps) : taps_(taps) {
  const std::int64_t n = 2 * taps;
  Workspace ws(taps);
  auto* spectrum = fftw_alloc_complex(static_cast<std::size_t>(taps + 1));
  if (!spectrum) throw std::bad_alloc();
  spectrum_ = spectrum;
  {
    std::lock_guard lock(fftw_planner_mutex());
    forward_ = fftw_plan_dft_r2c_1d(static_cast<int>(n), ws.time,
                                    static_cast<fftw_complex*>(ws.freq), FFTW_ESTIMATE);
    backward_ = fftw_plan_dft_c2r_1d(static_cast<int>(n), static_cast<fftw_complex*>(ws.freq),
                                     ws.time, FFTW_ESTIMATE);
  }
  // h_k by the recursion, in long double (rounding grows like k eps; 1e-13 at k = 2^26).
  long double h = 1.0L;
  for (std::int64_t k = 0; k < n; ++k) {
    if (k > 0 && k < taps) h *= (static_cast<long double>(k) - 0.5L) / k;
    ws.time[k] = k < taps ? static_cast<double>(h) : 0.0;
  }
  fftw_execute_dft_r2c(static_cast<fftw_plan>(forward_), ws.time,
                       static_cast<fftw_complex*>(ws.freq));
  const double scale = 1.0 / static_cast<double>(n);
  auto* freq = static_cast<fftw_complex*>(ws.freq);
  for (std::int64_t i = 0; i <= taps; ++i) {
    spectrum[i][0] = freq[i][0] * scale;
    spectrum[i][1] = freq[i][1] * scale;
  }
}

FlickerFilter::~FlickerFilter() {
  {
    std::lock_guard lock(fftw_planner_mutex());
    fftw_destroy_plan(static_cast<fftw_plan>(forward_));
    fftw_destroy_plan(static_cast<fftw_plan>(backward_));
  }
  fftw_free(spectrum_);
}

void FlickerFilter::block(Workspace& ws, std::uint64_t key, std::int64_t b, double* out) const {
  const std::int64_t L = taps_;
  fill_normal(key, (b - 1) * L, 2 * L, ws.time);
  auto* freq = static_cast<fftw_complex*>(ws.freq);
  const auto* h = static_cast<const fftw_complex*>(spectrum_);
  fftw_execute_dft_r2c(static_cast<fftw_plan>(forward_), ws.time, freq);
  for (std::int64_t i = 0; i <= L; ++i) {
    const double re = freq[i][0] * h[i][0] - freq[i][1] * h[i][1];
    const double im = freq[i][0] * h[i][1] + freq[i][1] * h[i][0];
    freq[i][0] = re;
    freq[i][1] = im;
  }
  fftw_execute_dft_c2r(static_cast<fftw_plan>(backward_), freq, ws.time);
  for (std::int64_t i = 0; i < L; ++i) out[i] = ws.time[L + i];
}

}  // namespace sigmatau::detail
