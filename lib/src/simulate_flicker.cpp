// Exact L-tap Kasdin flicker by FFT overlap-save, two blocks per complex transform.
//
// Glossary: L taps (a power of two); block b = output samples [bL, (b+1)L); pair p = blocks 2p
// and 2p + 1. Block b needs the input segment w[(b-1)L .. (b+1)L) (2L unit normals); the 2L-point
// circular convolution with h (zero-padded) is exact (no wrap-around) for outputs i >= L - 1, of
// which [L, 2L) are kept. Pair p: z_i = w[(2p-1)L + i] + i w[2pL + i], i < 2L (3L normals), one
// complex forward FFT, times H (h real: H_{2L-k} = conj H_k), one backward FFT; Re -> block 2p,
// Im -> block 2p + 1.
// Kasdin 1995, Proc. IEEE 83(5), eq. for the fractional integrator (1 - z^-1)^(-alpha/2), alpha=1.
#include "simulate_flicker.hpp"

#include <fftw3.h>

#include <mutex>
#include <new>

#include "fftw_planner.hpp"
#include "simulate_random.hpp"

namespace sigmatau::detail {

FlickerFilter::Workspace::Workspace(std::int64_t taps) {
  data = fftw_alloc_complex(static_cast<std::size_t>(2 * taps));
  if (!data) throw std::bad_alloc();
}

FlickerFilter::Workspace::~Workspace() { fftw_free(data); }

FlickerFilter::FlickerFilter(std::int64_t taps) : taps_(taps) {
  const std::int64_t n = 2 * taps;
  Workspace ws(taps);
  auto* z = static_cast<fftw_complex*>(ws.data);
  auto* spectrum = fftw_alloc_complex(static_cast<std::size_t>(taps + 1));
  if (!spectrum) throw std::bad_alloc();
  spectrum_ = spectrum;
  {
    std::lock_guard lock(fftw_planner_mutex());
    forward_ = fftw_plan_dft_1d(static_cast<int>(n), z, z, FFTW_FORWARD, FFTW_ESTIMATE);
    backward_ = fftw_plan_dft_1d(static_cast<int>(n), z, z, FFTW_BACKWARD, FFTW_ESTIMATE);
  }
  // h_k by the recursion, in long double (rounding grows like k eps; 1e-13 at k = 2^26).
  long double h = 1.0L;
  for (std::int64_t k = 0; k < n; ++k) {
    if (k > 0 && k < taps) h *= (static_cast<long double>(k) - 0.5L) / k;
    z[k][0] = k < taps ? static_cast<double>(h) : 0.0;
    z[k][1] = 0.0;
  }
  fftw_execute_dft(static_cast<fftw_plan>(forward_), z, z);
  const double scale = 1.0 / static_cast<double>(n);
  for (std::int64_t i = 0; i <= taps; ++i) {
    spectrum[i][0] = z[i][0] * scale;
    spectrum[i][1] = z[i][1] * scale;
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

void FlickerFilter::block_pair(Workspace& ws, std::uint64_t key, std::int64_t pair,
                               double* out) const {
  const std::int64_t L = taps_;
  const std::int64_t n = 2 * L;
  // The normals go straight into the interleaved array: Re z = w[(2p-1)L .. (2p+1)L), then
  // Im z[0, L) = Re z[L, 2L) (the same normals) and Im z[L, 2L) = w[(2p+1)L .. (2p+2)L).
  auto* z = static_cast<fftw_complex*>(ws.data);
  const std::int64_t first = (2 * pair - 1) * L;
  fill_normal_strided(key, first, n, &z[0][0], 2);
  for (std::int64_t i = 0; i < L; ++i) z[i][1] = z[L + i][0];
  fill_normal_strided(key, first + n, L, &z[L][1], 2);
  fftw_execute_dft(static_cast<fftw_plan>(forward_), z, z);
  const auto* h = static_cast<const fftw_complex*>(spectrum_);
  for (std::int64_t k = 0; k < n; ++k) {
    const std::int64_t j = k <= L ? k : n - k;
    const double hr = h[j][0];
    const double hi = k <= L ? h[j][1] : -h[j][1];
    const double re = z[k][0] * hr - z[k][1] * hi;
    const double im = z[k][0] * hi + z[k][1] * hr;
    z[k][0] = re;
    z[k][1] = im;
  }
  fftw_execute_dft(static_cast<fftw_plan>(backward_), z, z);
  for (std::int64_t i = 0; i < L; ++i) {
    out[i] = z[L + i][0];
    out[L + i] = z[L + i][1];
  }
}

}  // namespace sigmatau::detail
