// The static detector's streaming pieces (calibrate_internal.hpp): the window statistic as the
// samples pass, and the exact quantile of a stream of non-negative doubles in bounded memory.
//
// Glossary: w window length [samples], h = (w-1)/2; S1_p, S2_p the running sums of d and d^2
// over the first p samples of an axis, d = value - (the axis's first value); the statistic of
// sample i uses S_{i+h+1} - S_{i-h}. Quantile: n values, k = floor(q (n-1)) the rank sought;
// u the 64-bit pattern of a value (sign bit 0 for the non-negative values, so u orders like the
// value); a prefix group is the values whose u starts with the bits fixed so far.
#include <algorithm>
#include <bit>
#include <cmath>

#include "calibrate_internal.hpp"

namespace sigmatau::detail {
namespace {

/// Bits histogrammed per pass: 2^20 counters (8 MiB) narrow the group by ~2^-8 in relative
/// value per pass (11 exponent bits plus 8 mantissa bits after the sign), so the group left
/// after one pass usually holds ~1 % of the values.
constexpr int kHistogramBits = 20;
/// A group this small is collected and selected with nth_element (16 MiB of doubles).
constexpr std::int64_t kCollectMax = std::int64_t{1} << 21;

}  // namespace

WindowStatistic::WindowStatistic(std::int64_t w)
    : w_(w), ring_(static_cast<std::size_t>(w + 1), std::array<double, 6>{}) {}

bool WindowStatistic::push(const double* v, std::ptrdiff_t stride) {
  if (pushed_ == 0)
    for (int a = 0; a < 3; ++a) centre_[static_cast<std::size_t>(a)] = v[a * stride];
  auto& slot = ring_[static_cast<std::size_t>((pushed_ + 1) % (w_ + 1))];
  for (int a = 0; a < 3; ++a) {
    const auto ua = static_cast<std::size_t>(a);
    const double d = v[a * stride] - centre_[ua];
    s1_[ua] = s1_[ua] + d;
    s2_[ua] = s2_[ua] + d * d;
    slot[ua] = s1_[ua];
    slot[3 + ua] = s2_[ua];
  }
  ++pushed_;
  if (pushed_ < w_) return false;
  // Prefix b = pushed_ is the slot just written; prefix a = pushed_ - w (prefix 0 is all zeros).
  const auto& lo = ring_[static_cast<std::size_t>((pushed_ - w_) % (w_ + 1))];
  const double len = static_cast<double>(w_);
  value_ = 0.0;
  for (int a = 0; a < 3; ++a) {
    const auto ua = static_cast<std::size_t>(a);
    const double m = (slot[ua] - lo[ua]) / len;
    const double var = std::max(0.0, ((slot[3 + ua] - lo[3 + ua]) - len * m * m) / (len - 1));
    value_ = value_ + var;
  }
  return true;
}

StreamQuantile::StreamQuantile(double q, std::int64_t expected) : q_(q), group_(expected) {
  start_pass();
}

void StreamQuantile::start_pass() {
  collecting_ = group_ <= kCollectMax;
  if (collecting_) {
    collected_.clear();
    collected_.reserve(static_cast<std::size_t>(std::max<std::int64_t>(group_, 0)));
    std::vector<std::int64_t>().swap(histogram_);
  } else {
    bits_ = std::min(kHistogramBits, 64 - prefix_bits_);
    histogram_.assign(std::size_t{1} << bits_, 0);
  }
}

void StreamQuantile::add(double v) {
  if (std::isnan(v)) return;
  if (first_pass_) ++count_;
  const auto u = std::bit_cast<std::uint64_t>(v);
  if (prefix_bits_ > 0 && (u >> (64 - prefix_bits_)) != prefix_) return;
  if (collecting_) {
    collected_.push_back(v);
  } else {
    const std::uint64_t rest = prefix_bits_ > 0 ? (u << prefix_bits_) : u;
    ++histogram_[static_cast<std::size_t>(rest >> (64 - bits_))];
  }
}

bool StreamQuantile::end_pass() {
  if (first_pass_) {
    first_pass_ = false;
    if (count_ == 0) {
      value_ = std::nan("");
      done_ = true;
      return true;
    }
    k_ = static_cast<std::int64_t>(q_ * static_cast<double>(count_ - 1));
  }
  if (collecting_) {
    const auto k = static_cast<std::ptrdiff_t>(k_);
    std::nth_element(collected_.begin(), collected_.begin() + k, collected_.end());
    value_ = collected_[static_cast<std::size_t>(k)];
    std::vector<double>().swap(collected_);
    done_ = true;
    return true;
  }
  std::int64_t below = 0;
  std::size_t bucket = 0;
  while (below + histogram_[bucket] <= k_) below += histogram_[bucket++];
  k_ -= below;
  group_ = histogram_[bucket];
  prefix_ = (prefix_bits_ > 0 ? (prefix_ << bits_) : 0) | bucket;
  prefix_bits_ += bits_;
  if (prefix_bits_ == 64) {  // every bit fixed: the value itself
    value_ = std::bit_cast<double>(prefix_);
    std::vector<std::int64_t>().swap(histogram_);
    done_ = true;
    return true;
  }
  start_pass();
  return false;
}

}  // namespace sigmatau::detail
