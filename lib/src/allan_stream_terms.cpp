// The sum of one strided estimator of the stream mode (see allan_stream_terms.hpp).
#include "allan_stream_terms.hpp"

#include <algorithm>

#include "allan_sums.hpp"

namespace sigmatau::detail {
namespace {

/// Terms per call of the lane kernel (each lane's plain-double sum stays short, as in
/// allan_sums).
constexpr std::int64_t kKernelTerms = 2048;

}  // namespace

void StridedTerms::run(const Level& source) {
  // P[k] is known for k < points too (it lags x by one; P[points] follows with the next point,
  // so MDEV terms end one point later than they could: finish_running_sum() adds the last).
  const std::int64_t end = running_sum ? source.p_end() : source.x_end();
  const std::int64_t span = static_cast<std::int64_t>(order) * lag;
  const double* hh = running_sum ? source.ph.data() : source.xh.data();
  const double* ll = running_sum ? source.pl.data() : source.xl.data();
  if (step == 1) {
    while (next + span < end) {
      const std::int64_t len = std::min(kKernelTerms, end - span - next);
      sum.add(sum_squares(hh, ll, order, lag, next - source.begin, len));
      terms += len;
      next += len;
    }
  } else {
    double acc = 0.0;
    for (; next + span < end; next += step) {
      acc += sum_squares(hh, ll, order, lag, next - source.begin, 1);
      ++terms;
    }
    sum.add(acc);
  }
}

void StridedTerms::finish_running_sum(const Level& source, DoubleDouble p_total,
                                      std::int64_t points) {
  // Levels whose stride divides N hold P[N] as their next entry.
  if (!running_sum || points % source.stride != 0) return;
  Level extended = source;
  extended.ph.push_back(p_total.hi);
  extended.pl.push_back(p_total.lo);
  const std::int64_t span = 3 * lag;
  const std::int64_t end = extended.p_end();
  for (; next + span < end; next += step) {
    sum.add(sum_squares(extended.ph.data(), extended.pl.data(), 3, lag, next - extended.begin, 1));
    ++terms;
  }
}

}  // namespace sigmatau::detail
