#pragma once
// Internal (allan_stream.cpp): the one-pass noise identification state of the stream mode: sums
// of a series and of its lag-1 products, for the series differenced 0..3 times, from which the
// lag-1 autocorrelation of each is formed at the end (Riley & Greenhall 2004).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <new>
#include <vector>

#include "allan_dd.hpp"

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

/// Sums of a series and of its lag-1 products, with the first value subtracted (a shift changes
/// no autocorrelation, and it keeps a drifting series from cancelling). Each block is summed in
/// kLanes plain-double lanes and carried in double-double.
struct AcfSums {
  std::int64_t n = 0;
  double shift = 0, first = 0, last = 0;
  DoubleDouble s1, s2, s12;
  /// Adds a[0..len).
  void add_block(const double* a, std::size_t len);
  /// Lag-1 autocorrelation (Riley & Greenhall 2004 eq. 2) from the sums; NaN if constant.
  double r1() const;
};

/// Noise identification state of one averaging factor.
struct NoiseState {
  AcfSums sums[4];           ///< z differenced 0..3 times
  double previous[4] = {};   ///< last value of each differenced series
  std::vector<double> kept;  ///< the first values of x[k m] (B1 ratio, while few exist)
  std::int64_t next_k = 0;   ///< next k whose x[k m] is read
  Doubles batch;  ///< new z values of the current chunk
  Doubles spare;  ///< scratch of flush()
  /// Adds the batch to the sums of each difference order, then clears it.
  void flush();
};

}  // namespace sigmatau::detail
