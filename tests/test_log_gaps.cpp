// Gap and non-increasing time stamp policies of the reader (GapPolicy), on the hand-made
// tests/data/logs/gap.csv (intervals in ms: 10,10,11,9,10,40,10,0,10,9,11; the 40 ms gap ends at
// row 6 on line 10, the duplicated stamp is row 8 on line 12) and on constructed logs.
#include <cmath>
#include <string>
#include <vector>

#include "sigmatau/error.hpp"
#include "sigmatau/log_reader.hpp"
#include "test_support.hpp"

using namespace sigmatau;
using sigmatau::test::rel;

namespace {

LogOptions gap_csv(GapPolicy policy) {
  LogOptions o;
  o.path = (test::test_data_dir() / "logs" / "gap.csv").string();
  o.time_column = "t_ms";
  o.time_unit = TimeUnit::ms;
  o.gaps = policy;
  return o;
}

}  // namespace

TEST_CASE("report (the default) reads through and locates the first duplicate and the gap") {
  CHECK(LogOptions{}.gaps == GapPolicy::report);
  const Log log = read_log(gap_csv(GapPolicy::report));
  CHECK(log.channels[0].size() == 12);
  CHECK(log.timing.first_non_increasing_row == 8);
  CHECK(log.timing.first_non_increasing_line == 12);
  CHECK(log.timing.first_non_increasing_step_s == 0.0);
  CHECK(log.timing.largest_gap_s == rel(0.040, 1e-12));  // 1e-12: one rounding of 40/1e3
  CHECK(log.timing.largest_gap_line == 10);
  CHECK(log.timing.segment_starts.empty());
}

TEST_CASE("error: the first problem (the gap) is named with its line, length, count, options") {
  try {
    read_log(gap_csv(GapPolicy::error));
    FAIL("no exception");
  } catch (const ParseError& e) {
    INFO(e.what());
    CHECK(e.line() == 10);
    CHECK(e.message().find("time stamp gap of 40 ms (4 nominal intervals of 10 ms)") !=
          std::string::npos);
    CHECK(e.message().find("1 gap in all") != std::string::npos);
    // The duplicated stamp after it is named too (rows out of order show as gaps around a
    // backwards step, and only the gaps used to be named).
    CHECK(e.message().find("1 duplicated or backwards stamp, the first at line 12") !=
          std::string::npos);
    CHECK(e.message().find("before data row 6") != std::string::npos);
    CHECK(e.message().find("--gaps split") != std::string::npos);
    CHECK(e.message().find("--gaps fill") != std::string::npos);
  }
}

TEST_CASE("split: segments start at 0, after the gap and at the duplicated stamp") {
  const Log log = read_log(gap_csv(GapPolicy::split));
  CHECK(log.timing.segment_starts == std::vector<std::int64_t>{0, 6, 8});
  CHECK(log.channels[0].size() == 12);
}

TEST_CASE("fill refuses non-increasing stamps, at their line") {
  CHECK_THROWS_WITH_AS(read_log(gap_csv(GapPolicy::fill)),
                       doctest::Contains(":12: duplicated time stamp"), ParseError);
}

TEST_CASE("fill_gaps interpolates the missing samples linearly and counts them") {
  Log log;
  log.path = "constructed";
  log.t_s = {0.00, 0.01, 0.02, 0.05, 0.06};  // 0.02 -> 0.05: 3 intervals, 2 samples missing
  log.channels = {{0, 1, 2, 5, 6}, {10, 10, 10, 40, 40}};
  log.timing.rate_hz = 100;
  CHECK(fill_gaps(log) == 2);
  CHECK(log.timing.filled_samples == 2);
  REQUIRE(log.t_s.size() == 7);
  // Expected values by hand: linear between (0.02, 2 | 10) and (0.05, 5 | 40); 1e-12 covers
  // the rounding of the stamps' decimal fractions.
  CHECK(log.t_s[3] == rel(0.03, 1e-12));
  CHECK(log.t_s[4] == rel(0.04, 1e-12));
  CHECK(log.channels[0] == std::vector<double>{0, 1, 2, 3, 4, 5, 6});
  CHECK(log.channels[1][3] == rel(20, 1e-15));
  CHECK(log.channels[1][4] == rel(30, 1e-15));
  CHECK(fill_gaps(log) == 0);  // nothing left to fill
  // A stamp jump that would more than double the log is refused, and the log is untouched.
  Log jump = log;
  jump.t_s.back() = 1000.0;
  CHECK_THROWS_WITH_AS(fill_gaps(jump), doctest::Contains("use --gaps split"), Error);
  CHECK(jump.channels[0].size() == 7);
  Log untimed;
  untimed.channels = {{1, 2}};
  CHECK_THROWS_AS(fill_gaps(untimed), Error);
}

TEST_CASE("policy names") {
  CHECK(parse_gap_policy("split") == GapPolicy::split);
  CHECK(parse_nonfinite_policy("skip") == NonFinitePolicy::skip_row);
  CHECK_THROWS_WITH_AS(parse_gap_policy("ignore"), doctest::Contains("expected error, split"),
                       Error);
  CHECK_THROWS_AS(parse_nonfinite_policy(""), Error);
}
