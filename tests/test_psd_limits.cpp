// Welch segments longer than what is fed (issue 28): the accumulator allocates its segment-sized
// buffers only once a segment is complete, so a segment longer than the log costs the samples
// fed and ends in the "shorter than one segment" Error (a segment of 2^31 - 1 on a 3000-sample
// log ended in bad_alloc; one of 1e8 took 1.5 GB a channel); a segment FFTW cannot transform is
// refused when the accumulator is made.
#include <cmath>
#include <random>
#include <vector>

#include "sigmatau/error.hpp"
#include "sigmatau/psd.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

std::vector<double> white(std::size_t n) {
  std::mt19937_64 rng(9);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<double> x(n);
  for (double& v : x) v = noise(rng);
  return x;
}

WelchOptions segment(std::int64_t length) {
  WelchOptions o;
  o.segment_length = length;
  return o;
}

}  // namespace

TEST_CASE("a segment longer than the samples fed is the shorter-than-one-segment Error") {
  const std::vector<double> x = white(3000);
  for (const std::int64_t length : {std::int64_t{3001}, std::int64_t{100000000}, kMaxSegmentLength}) {
    INFO("segment " << length);
    WelchAccumulator welch(100.0, segment(length));
    welch.add(x);
    CHECK(welch.segments() == 0);
    CHECK_THROWS_WITH_AS(welch.result(), doctest::Contains("the log is shorter than one segment"),
                         Error);
  }
}

TEST_CASE("a segment FFTW cannot transform is refused when the accumulator is made") {
  CHECK_THROWS_WITH_AS(WelchAccumulator(100.0, segment(kMaxSegmentLength + 1)),
                       doctest::Contains("segment_length must be at most 2147483647 samples"),
                       Error);
}

TEST_CASE("allocating at the first complete segment gives the same PSD, fed in any pieces") {
  const std::vector<double> x = white(5000);
  const PsdCurve whole = welch_psd(x, 100.0, segment(1024));
  WelchAccumulator pieces(100.0, segment(1024));
  for (std::size_t i = 0; i < x.size(); i += 700) {
    pieces.add(std::span<const double>(x.data() + i, std::min<std::size_t>(700, x.size() - i)));
  }
  const PsdCurve fed = pieces.result();
  REQUIRE(fed.psd.size() == whole.psd.size());
  CHECK(fed.segments == whole.segments);
  for (std::size_t k = 0; k < fed.psd.size(); ++k) CHECK(fed.psd[k] == whole.psd[k]);  // same sums
}
