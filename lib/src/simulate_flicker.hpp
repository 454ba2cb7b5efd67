#pragma once
// Exact L-tap Kasdin flicker by FFT overlap-save (internal to the simulator).
#include <cstdint>

namespace sigmatau::detail {

/// The filter h_0 = 1, h_k = h_{k-1} (k - 1/2) / k, k < L, as the spectrum of its 2L-point
/// zero-padded DFT (scaled by 1/(2L) so that forward, multiply, backward is a convolution), and
/// the FFTW plans. Immutable after construction; shared by all channels and threads.
///
/// Two consecutive output blocks are made by one complex transform: the input of block 2p goes
/// in the real part and that of block 2p + 1 in the imaginary part; h is real, so the real and
/// imaginary parts of the circular convolution are the two blocks' convolutions. A 2L complex
/// FFT costs about what a 2L real one does at these sizes (memory-bound), so this halves the
/// FFT work per sample.
class FlickerFilter {
 public:
  explicit FlickerFilter(std::int64_t taps);
  ~FlickerFilter();
  FlickerFilter(const FlickerFilter&) = delete;
  FlickerFilter& operator=(const FlickerFilter&) = delete;
  std::int64_t taps() const { return taps_; }

  /// Per-thread scratch: 2L complex (FFTW-aligned).
  class Workspace {
   public:
    explicit Workspace(std::int64_t taps);
    ~Workspace();
    Workspace(const Workspace&) = delete;
    Workspace& operator=(const Workspace&) = delete;
    void* data;  // fftw_complex[2L]
  };

  /// Unit-variance-innovation flicker samples [2 pair L, (2 pair + 2) L) of the stream `key`
  /// into out[0..2L): y_k = sum_{j<L} h_j w_{k-j}, with w the stream's unit normals (indices from
  /// (2 pair - 1) L, so negative indices are used for the first block).
  void block_pair(Workspace& ws, std::uint64_t key, std::int64_t pair, double* out) const;

 private:
  std::int64_t taps_;
  void* spectrum_;      // fftw_complex[L + 1]: H_k, k <= L (H_{2L-k} = conj H_k)
  void* forward_;       // fftw_plan complex forward, size 2L, in place on Workspace::data
  void* backward_;      // fftw_plan complex backward, size 2L, in place
};

}  // namespace sigmatau::detail
