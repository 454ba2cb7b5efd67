#pragma once
// Exact L-tap Kasdin flicker by FFT overlap-save (internal to the simulator).
#include <cstdint>
#include <vector>

namespace sigmatau::detail {

/// The filter h_0 = 1, h_k = h_{k-1} (k - 1/2) / k, k < L, as a spectrum of the 2L-point real FFT
/// (scaled by 1/(2L) so that forward, multiply, backward is a convolution), and the FFTW plans.
/// Immutable after construction; shared by all channels and threads.
class FlickerFilter {
 public:
  explicit FlickerFilter(std::int64_t taps);
  ~FlickerFilter();
  FlickerFilter(const FlickerFilter&) = delete;
  FlickerFilter& operator=(const FlickerFilter&) = delete;
  std::int64_t taps() const { return taps_; }

  /// Per-thread scratch (2L reals and L+1 complex, FFTW-aligned).
  class Workspace {
   public:
    explicit Workspace(std::int64_t taps);
    ~Workspace();
    Workspace(const Workspace&) = delete;
    Workspace& operator=(const Workspace&) = delete;
    double* time;
    void* freq;  // fftw_complex*
  };

  /// Unit-variance-innovation flicker samples [block L, (block + 1) L) of the stream `key` into
  /// out[0..L): sum_{j<L} h_j w_{k-j}, with w the stream's unit normals (indices from
  /// (block - 1) L, so negative indices are used for the first block).
  void block(Workspace& ws, std::uint64_t key, std::int64_t block, double* out) const;

 private:
  std::int64_t taps_;
  void* spectrum_;      // fftw_complex[L + 1]
  void* forward_;       // fftw_plan r2c, size 2L
  void* backward_;      // fftw_plan c2r, size 2L
};

}  // namespace sigmatau::detail
