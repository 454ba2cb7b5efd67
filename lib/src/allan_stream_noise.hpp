#pragma once
// Internal (allan_stream*.cpp): the one-pass noise identification of the stream mode. For each
// averaging factor m the series z at m (confidence.cpp's series_at: m-sample means for rate and
// increment input, the phase decimated to m for phase input) is fed once; for z differenced
// 0..3 times, sums of the values and of their squares and lag-1 products are kept, from which
// the lag-1 autocorrelation is formed at the end (Riley & Greenhall 2004), as identify_noise
// does on the whole series. While fewer than kMinAcfPoints values exist, the B1 ratio of the
// first few values decides (as compute_allan_curve does on a short series).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <vector>

#include "allan_dd.hpp"
#include "sigmatau/allan.hpp"
#include "sigmatau/confidence.hpp"

namespace sigmatau::detail {

/// An allocator whose resize() leaves new doubles uninitialised (they are always written before
/// they are read): the stream's buffers grow and shrink every chunk, and zero-filling them cost
/// more than the arithmetic.
template <class T>
struct UninitialisedAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UninitialisedAllocator<U>;
  };
  UninitialisedAllocator() = default;
  template <class U>
  UninitialisedAllocator(const UninitialisedAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};
/// Buffer of doubles that resize() does not zero-fill.
using Doubles = std::vector<double, UninitialisedAllocator<double>>;

/// Sums of one series and of its lag-1 products, with the series' first value subtracted (a
/// shift changes no autocorrelation, and it keeps a drifting series from cancelling).
struct AcfSums {
  std::int64_t n = 0;        ///< values so far
  double shift = 0;          ///< the first value
  double last = 0;           ///< the last value minus shift (the first one minus shift is 0)
  DoubleDouble s1, s2, s12;  ///< sum of b, of b^2, of b_{i-1} b_i (b = value - shift)
  /// Lag-1 autocorrelation (Riley & Greenhall 2004 eq. 2) from the sums; NaN if constant.
  double r1() const;
};

/// out[j] = ((h[j] - h[j-1]) + (l[j] - l[j-1])) * inv_m for j < count: the m-sample means z
/// from the double-double phase at multiples of m (h, l; h[-1], l[-1] readable).
void mean_rates(const double* h, const double* l, std::size_t count, double inv_m, double* out);

/// Fewest points at m for the lag-1 ACF (confidence.cpp, Riley & Greenhall 2004).
constexpr std::int64_t kMinAcfPoints = 30;

/// Noise identification state of one averaging factor.
class NoiseSums {
 public:
  /// Series summed: z differenced 0 .. orders - 1 times (orders 3 for Allan-type statistics,
  /// 4 when a Hadamard one is computed: identify() differences at most d_max times).
  explicit NoiseSums(int orders);

  /// Adds z values to the sums: buffer[kHistory .. kHistory + count) holds them, and add()
  /// writes the last kHistory earlier values to buffer[0 .. kHistory) (its own scratch).
  void add(double* buffer, std::size_t count);

  /// Keeps x[k m] (the phase at multiples of m, rounded to double) while the B1 ratio may
  /// still need it.
  void keep(double x) {
    if (static_cast<std::int64_t>(kept_.size()) <= kMinAcfPoints) kept_.push_back(x);
  }
  bool wants_kept() const { return static_cast<std::int64_t>(kept_.size()) <= kMinAcfPoints; }

  /// The noise at this m for `statistic` (difference order as identify_noise), from data of
  /// `kind` at sample interval tau0_s [s].
  NoiseIdentification identify(Statistic statistic, DataKind kind, std::int64_t m,
                               double tau0_s) const;

  std::int64_t next_k = 0;  ///< next k whose x[k m] is read
  std::size_t memory_bytes() const;

  static constexpr int kLanes = 8;
  /// Earlier z values a new value needs: z differenced 3 times, and its lag-1 product.
  static constexpr std::size_t kHistory = 4;

 private:
  int orders_;
  std::int64_t count_ = 0;  ///< z values so far
  AcfSums sums_[4];
  double lanes_[4][3][kLanes] = {};  ///< per series: s1, s2, s12 lanes since the last carry()
  std::int64_t uncarried_ = 0;       ///< z values in the lanes
  /// Values the lanes take before carry() (each plain-double lane sum stays about as short as
  /// the exact sums' blocks: ~2k values; carrying less often than every chunk halves its cost).
  static constexpr std::int64_t kCarryEvery = 16384;
  /// Carries the plain-double lane sums into the double-double sums and brings n and last up
  /// to date.
  void carry();
  double history_[kHistory] = {};    ///< the last kHistory z values (oldest first)
  std::vector<double> kept_;
};

}  // namespace sigmatau::detail
