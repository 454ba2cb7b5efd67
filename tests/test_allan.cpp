// Allan-family estimators on inputs small enough to check by hand, on the published NBS / NIST
// SP 1065 test sets, on edge cases, and the tau grids of taus.hpp.
#include <cmath>
#include <cstdint>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "sigmatau/allan.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/phase_series.hpp"
#include "sigmatau/taus.hpp"
#include "test_support.hpp"

using namespace sigmatau;
using test::rel;

namespace {

constexpr Statistic kAllStatistics[] = {Statistic::adev, Statistic::oadev, Statistic::mdev,
                                        Statistic::tdev, Statistic::hdev,  Statistic::ohdev,
                                        Statistic::totdev};

/// Hand arithmetic below is done in exact decimals; the code rounds in binary64, so results agree
/// to a few ulps: 1e-14 relative.
constexpr double kHandTolerance = 1e-14;

double dev_at(const PhaseSeries& series, Statistic statistic, std::int64_t m) {
  const std::int64_t factors[] = {m};
  const auto points = compute_deviation(series, statistic, factors);
  REQUIRE(points.size() == 1);
  return points[0].dev;
}

std::int64_t n_at(const PhaseSeries& series, Statistic statistic, std::int64_t m) {
  const std::int64_t factors[] = {m};
  const auto points = compute_deviation(series, statistic, factors);
  REQUIRE(points.size() == 1);
  return points[0].n_terms;
}

/// The NIST SP 1065 section 12.4 1000-point set, generated exactly (Park-Miller LCG, 2^31 - 1).
std::vector<double> nist_1000_point_frequency() {
  std::vector<double> y;
  std::int64_t n = 1234567890;
  for (int i = 0; i < 1000; ++i) {
    y.push_back(static_cast<double>(n) / 2147483647.0);
    n = (16807 * n) % 2147483647;
  }
  return y;
}

std::vector<double> read_numbers(const std::filesystem::path& path) {
  std::ifstream in(path);
  REQUIRE(in.good());
  std::vector<double> v;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    v.push_back(std::stod(line));
  }
  return v;
}

std::vector<std::vector<std::string>> read_csv(const std::filesystem::path& path) {
  std::ifstream in(path);
  REQUIRE(in.good());
  std::vector<std::vector<std::string>> rows;
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {  // first non-comment line names the columns
      header = false;
      continue;
    }
    std::vector<std::string> fields;
    std::stringstream s(line);
    std::string field;
    while (std::getline(s, field, ',')) fields.push_back(field);
    rows.push_back(fields);
  }
  return rows;
}

bool implemented(const std::string& name) {
  for (const Statistic s : kAllStatistics) {
    if (name == to_string(s)) return true;
  }
  return false;
}

}  // namespace

// Rate y = 1 3 2 4 0 2 (tau0 = 1 s): mean 2, so the phase is x = 0 -1 0 0 2 0 0 (N = 7).
// m = 1: first differences of y are 2 -1 2 -4 2, squares sum to 29 over N-2 = 5 terms:
//        AVAR = 29 / (2*5) = 2.9 (overlapping and non-overlapping: stride 1 is every term).
// m = 2: D2(n) = x[n+4] - 2x[n+2] + x[n] = 2, -1, -4 (N-2m = 3 terms); in rate units /m:
//        1, -0.5, -2, squares 5.25: OAVAR = 5.25 / 6 = 0.875.
//        Non-overlapping: 2-sample means 2, 3, 1; differences 1, -2 (floor(6/2)-1 = 2 terms):
//        AVAR = 5 / 4 = 1.25.
//        MVAR: V(j) = D2(j) + D2(j+1) = 1, -5 (N-3m+1 = 2 terms):
//        MVAR = (1 + 25) / (2 m^2 m^2 * 2) = 26 / 64 = 0.40625; TVAR = tau^2/3 MVAR = 0.541666...
//        HVAR: one term (N-3m = 1, and floor(6/2)-2 = 1): x6 - 3x4 + 3x2 - x0 = -6, /m = -3:
//        HVAR = 9 / 6 = 1.5.
//        TOTVAR: reflected x*[-2..8] = 0 1 | 0 -1 0 0 2 0 0 | 0 -2; terms i = 1..5 of
//        x*[i-2] - 2x*[i] + x*[i+2] = 3, 2, -1, -4, 0: TOTVAR = 30 / (2 * 2^2 * 5) = 0.75.
// m = 1 Hadamard: second differences of y are -3 3 -6 6 (N-3 = 4 terms): HVAR = 90/24 = 3.75.
TEST_CASE("each statistic matches a hand computation on a six-sample record") {
  const std::vector<double> y = {1, 3, 2, 4, 0, 2};
  const auto series = PhaseSeries::from_rate(y, 1.0);
  REQUIRE(series.size() == 7);

  CHECK(dev_at(series, Statistic::oadev, 1) == rel(std::sqrt(2.9), kHandTolerance));
  CHECK(dev_at(series, Statistic::adev, 1) == rel(std::sqrt(2.9), kHandTolerance));
  CHECK(dev_at(series, Statistic::mdev, 1) == rel(std::sqrt(2.9), kHandTolerance));
  CHECK(dev_at(series, Statistic::totdev, 1) == rel(std::sqrt(2.9), kHandTolerance));
  CHECK(dev_at(series, Statistic::hdev, 1) == rel(std::sqrt(3.75), kHandTolerance));
  CHECK(dev_at(series, Statistic::ohdev, 1) == rel(std::sqrt(3.75), kHandTolerance));

  CHECK(dev_at(series, Statistic::oadev, 2) == rel(std::sqrt(0.875), kHandTolerance));
  CHECK(dev_at(series, Statistic::adev, 2) == rel(std::sqrt(1.25), kHandTolerance));
  CHECK(dev_at(series, Statistic::mdev, 2) == rel(std::sqrt(0.40625), kHandTolerance));
  CHECK(dev_at(series, Statistic::tdev, 2) == rel(std::sqrt(0.40625 * 4.0 / 3.0), kHandTolerance));
  CHECK(dev_at(series, Statistic::hdev, 2) == rel(std::sqrt(1.5), kHandTolerance));
  CHECK(dev_at(series, Statistic::ohdev, 2) == rel(std::sqrt(1.5), kHandTolerance));
  CHECK(dev_at(series, Statistic::totdev, 2) == rel(std::sqrt(0.75), kHandTolerance));

  // Term counts from the same hand computation.
  CHECK(n_at(series, Statistic::oadev, 2) == 3);
  CHECK(n_at(series, Statistic::adev, 2) == 2);
  CHECK(n_at(series, Statistic::mdev, 2) == 2);
  CHECK(n_at(series, Statistic::hdev, 2) == 1);
  CHECK(n_at(series, Statistic::ohdev, 2) == 1);
  CHECK(n_at(series, Statistic::totdev, 2) == 5);
}

TEST_CASE("rate, increment and phase input of the same record give the same deviations") {
  // Phase in seconds = tau0 x (rate-form phase); increments = tau0 y. tau0 = 0.25 s is exact in
  // binary, so all three are the same numbers up to rounding: 1e-14.
  const double tau0 = 0.25;
  const std::vector<double> y = {1, 3, 2, 4, 0, 2, 7, -1, 3, 3, 5};
  std::vector<double> increments, phase = {1e3};  // phase offset 1e3: removed exactly
  double x = 1e3;
  for (const double v : y) {
    increments.push_back(v * tau0);
    x += v * tau0;
    phase.push_back(x);
  }
  const auto from_rate = PhaseSeries::from_rate(y, tau0);
  const auto from_increments = PhaseSeries::from_increments(increments, tau0);
  const auto from_phase = PhaseSeries::from_phase(phase, tau0);
  const std::int64_t m[] = {1, 2, 3};
  for (const Statistic s : kAllStatistics) {
    INFO(to_string(s));
    const auto a = compute_deviation(from_rate, s, m);
    const auto b = compute_deviation(from_increments, s, m);
    const auto c = compute_deviation(from_phase, s, m);
    REQUIRE(a.size() == b.size());
    REQUIRE(a.size() == c.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
      CHECK(a[i].tau_s == static_cast<double>(a[i].m) * tau0);
      CHECK(b[i].dev == rel(a[i].dev, kHandTolerance));
      CHECK(c[i].dev == rel(a[i].dev, kHandTolerance));
      CHECK(b[i].n_terms == a[i].n_terms);
      CHECK(c[i].n_terms == a[i].n_terms);
    }
  }
}

// NBS Monograph 140 / NIST SP 1065 section 12.3 (THEORY.md 1.7): 9 frequency points, tau0 = 1 s.
TEST_CASE("the NBS 9-point set reproduces the published NIST SP 1065 values") {
  const std::vector<double> y = {892, 809, 823, 798, 671, 644, 883, 903, 677};
  struct Published {
    Statistic statistic;
    double m1, m2;
  };
  const Published published[] = {
      {Statistic::adev, 91.22945, 115.8082},  {Statistic::oadev, 91.22945, 85.95287},
      {Statistic::mdev, 91.22945, 74.78849},  {Statistic::tdev, 52.67135, 86.35831},
      {Statistic::hdev, 70.80608, 116.7980},  {Statistic::ohdev, 70.80607, 85.61487},
      {Statistic::totdev, 91.22945, 93.90379},
  };
  // Published with 7 significant digits: half a unit of the 7th digit is at most 5e-7 relative.
  constexpr double kPublished = 5e-7;
  // The 10-point phase version is printed with 5 decimals (+-5e-6 on values ~100); a second
  // difference of 4 such points moves by up to 2e-5 on values >= 50: 4e-7 relative. 2e-6 covers
  // that and the 7-digit rounding of the published values.
  constexpr double kPrintedPhase = 2e-6;
  const std::vector<double> phase = {0.0,       103.11111, 123.22222, 157.33333, 166.44444,
                                     48.55555,  -96.33333, -2.22222,  111.88889, 0.0};
  const auto from_frequency = PhaseSeries::from_rate(y, 1.0);
  const auto from_phase = PhaseSeries::from_phase(phase, 1.0);
  for (const auto& p : published) {
    INFO(to_string(p.statistic));
    CHECK(dev_at(from_frequency, p.statistic, 1) == rel(p.m1, kPublished));
    CHECK(dev_at(from_frequency, p.statistic, 2) == rel(p.m2, kPublished));
    CHECK(dev_at(from_phase, p.statistic, 1) == rel(p.m1, kPrintedPhase));
    CHECK(dev_at(from_phase, p.statistic, 2) == rel(p.m2, kPrintedPhase));
  }
  if (test::has_reference_data("allantools/nbs14_10point")) {
    const auto dir = test::reference_data_dir() / "allantools/nbs14_10point";
    CHECK(read_numbers(dir / "nbs14_9point_frequency.txt") == y);
    CHECK(read_numbers(dir / "nbs14_10point_phase.txt") == phase);
  }
}

TEST_CASE("the NIST 1000-point set reproduces every published value") {
  const auto y = nist_1000_point_frequency();
  const auto series = PhaseSeries::from_rate(y, 1.0);
  REQUIRE(series.size() == 1001);
  // Published values have 7 significant digits (half a unit: <= 5e-7 relative).
  constexpr double kPublished = 5e-7;

  SUBCASE("term counts (NIST SP 1065 section 12.4 conventions)") {
    const std::int64_t m[] = {1, 10, 100};
    const std::map<Statistic, std::vector<std::int64_t>> expected = {
        {Statistic::adev, {999, 99, 9}},     {Statistic::oadev, {999, 981, 801}},
        {Statistic::mdev, {999, 972, 702}},  {Statistic::tdev, {999, 972, 702}},
        {Statistic::hdev, {998, 98, 8}},     {Statistic::ohdev, {998, 971, 701}},
        {Statistic::totdev, {999, 999, 999}}};
    for (const auto& [statistic, counts] : expected) {
      const auto points = compute_deviation(series, statistic, m);
      REQUIRE(points.size() == 3);
      for (std::size_t i = 0; i < 3; ++i) CHECK(points[i].n_terms == counts[i]);
    }
  }

  SUBCASE("sp1065_published_values.csv") {
    if (!test::has_reference_data("nist_sp1065/sp1065_published_values.csv")) return;
    const auto dir = test::reference_data_dir() / "nist_sp1065";
    // The stored 16-digit copy of the data is the generator output (REFERENCE.md: <= 1.2e-13).
    const auto stored = read_numbers(dir / "nbs_1000point_frequency.txt");
    REQUIRE(stored.size() == y.size());
    for (std::size_t i = 0; i < y.size(); ++i) CHECK(stored[i] == rel(y[i], 2e-13));
    int checked = 0;
    for (const auto& row : read_csv(dir / "sp1065_published_values.csv")) {
      // dataset,statistic,m,value,kind,recomputed,note: the plain statistics, recomputed = yes
      // (the "no" rows are other estimators: bias-corrected or end-matched variants).
      if (row.size() < 6 || row[0] != "lcg1000" || !implemented(row[1]) || row[5] != "yes") continue;
      INFO(row[1] << " m=" << row[2]);
      CHECK(dev_at(series, parse_statistic(row[1]), std::stoll(row[2])) ==
            rel(std::stod(row[3]), kPublished));
      ++checked;
    }
    CHECK(checked == 21);  // 7 statistics x m = 1, 10, 100
  }

  SUBCASE("allantools reference values, from frequency and from PHASE.DAT") {
    if (!test::has_reference_data("allantools/nbs14_1000point")) return;
    if (!test::has_reference_data("allantools/phasedat/PHASE.DAT")) return;
    const auto phase = read_numbers(test::reference_data_dir() / "allantools/phasedat/PHASE.DAT");
    REQUIRE(phase.size() == 1001);
    const auto phase_series = PhaseSeries::from_phase(phase, 1.0);
    int checked = 0;
    for (const auto& row : read_csv(test::reference_data_dir() /
                                    "allantools/nbs14_1000point/allantools_reference_values.csv")) {
      // statistic,m,value,kind,used_in_test,note
      if (row.size() < 4 || !implemented(row[0]) || row[3] != "published") continue;
      INFO(row[0] << " m=" << row[1]);
      const auto statistic = parse_statistic(row[0]);
      const auto m = std::stoll(row[1]);
      CHECK(dev_at(series, statistic, m) == rel(std::stod(row[2]), kPublished));
      // PHASE.DAT is the same data as phase (REFERENCE.md: max difference 1e-13 on values up to
      // ~10): second differences of order 0.3 move by < 1e-12 relative; the 7-digit rounding
      // dominates.
      CHECK(dev_at(phase_series, statistic, m) == rel(std::stod(row[2]), kPublished));
      ++checked;
    }
    CHECK(checked == 21);
  }
}

TEST_CASE("too few phase points give no points, never an exception") {
  SUBCASE("no samples and one sample") {
    for (const std::size_t M : {std::size_t{0}, std::size_t{1}}) {
      const std::vector<double> y(M, 1.5);
      const auto series = PhaseSeries::from_rate(y, 1.0);
      CHECK(series.size() == static_cast<std::int64_t>(M + 1));
      const std::int64_t m[] = {1, 2};
      for (const Statistic s : kAllStatistics) CHECK(compute_deviation(series, s, m).empty());
    }
  }
  SUBCASE("two samples (N = 3): only the one-term estimators at m = 1") {
    const std::vector<double> y = {1.0, 4.0};  // one difference of 3: AVAR = 9/2
    const auto series = PhaseSeries::from_rate(y, 1.0);
    const std::int64_t m[] = {1, 2};
    for (const Statistic s : {Statistic::adev, Statistic::oadev, Statistic::mdev,
                              Statistic::totdev}) {
      INFO(to_string(s));
      const auto points = compute_deviation(series, s, m);
      REQUIRE(points.size() == 1);
      CHECK(points[0].m == 1);
      CHECK(points[0].n_terms == 1);
      CHECK(points[0].dev == rel(std::sqrt(4.5), kHandTolerance));
    }
    CHECK(compute_deviation(series, Statistic::hdev, m).empty());
    CHECK(compute_deviation(series, Statistic::ohdev, m).empty());
  }
  SUBCASE("empty phase input") {
    const auto series = PhaseSeries::from_phase(std::vector<double>{}, 1.0);
    const std::int64_t m[] = {1};
    CHECK(series.size() == 0);
    for (const Statistic s : kAllStatistics) CHECK(compute_deviation(series, s, m).empty());
  }
}

TEST_CASE("factors with no terms are omitted and the order of the request is kept") {
  const auto series = PhaseSeries::from_rate(nist_1000_point_frequency(), 1.0);
  // N = 1001: OADEV needs 2m <= 1000, OHDEV 3m <= 1000, MDEV 3m <= 1001.
  const std::int64_t m[] = {500, 1, 501, 1000000, 10, 10};
  const auto oadev = compute_deviation(series, Statistic::oadev, m);
  REQUIRE(oadev.size() == 4);
  CHECK(oadev[0].m == 500);
  CHECK(oadev[0].n_terms == 1);
  CHECK(oadev[1].m == 1);
  CHECK(oadev[2].m == 10);
  CHECK(oadev[3].m == 10);
  CHECK(oadev[3].dev == oadev[2].dev);
  CHECK(compute_deviation(series, Statistic::ohdev, std::vector<std::int64_t>{333, 334}).size() == 1);
  CHECK(compute_deviation(series, Statistic::mdev, std::vector<std::int64_t>{333, 334}).size() == 1);
  CHECK(compute_deviation(series, Statistic::adev, std::vector<std::int64_t>{500, 501}).size() == 1);
  CHECK(compute_deviation(series, Statistic::hdev, std::vector<std::int64_t>{333, 334}).size() == 1);
  CHECK(compute_deviation(series, Statistic::totdev, std::vector<std::int64_t>{500, 501}).size() == 1);
  CHECK_THROWS_AS(compute_deviation(series, Statistic::oadev, std::vector<std::int64_t>{0}), Error);
  CHECK_THROWS_AS(compute_deviation(series, Statistic::oadev, std::vector<std::int64_t>{-3}), Error);
}

TEST_CASE("a constant input gives exactly zero for every statistic") {
  for (const double level : {0.0, 0.1, -7.3e-5, 1e6, 123456.789, 1e300}) {
    INFO("level " << level);
    const std::vector<double> values(1000, level);
    std::vector<std::int64_t> m;
    for (std::int64_t v = 1; v <= 333; v = v * 3 + 1) m.push_back(v);
    for (const DataKind kind : {DataKind::rate, DataKind::increment, DataKind::phase}) {
      const auto series = PhaseSeries::from_samples(values, kind, 0.01);
      for (const Statistic s : kAllStatistics) {
        for (const auto& p : compute_deviation(series, s, m)) CHECK(p.dev == 0.0);
      }
    }
  }
}

TEST_CASE("TDEV is tau / sqrt(3) times MDEV") {
  const auto y = nist_1000_point_frequency();
  for (const double tau0 : {1.0, 0.01, 42.0}) {
    const auto series = PhaseSeries::from_rate(y, tau0);
    const std::int64_t m[] = {1, 3, 10, 64, 250, 333};
    const auto mdev = compute_deviation(series, Statistic::mdev, m);
    const auto tdev = compute_deviation(series, Statistic::tdev, m);
    REQUIRE(mdev.size() == tdev.size());
    for (std::size_t i = 0; i < mdev.size(); ++i) {
      CHECK(tdev[i].n_terms == mdev[i].n_terms);
      // The same quantity rounded along two orders of about six operations: 1e-14 (~45 ulps).
      CHECK(tdev[i].dev == rel(mdev[i].tau_s / std::sqrt(3.0) * mdev[i].dev, 1e-14));
    }
  }
}

TEST_CASE("statistic names parse and print, and anything else is an Error") {
  for (const Statistic s : kAllStatistics) CHECK(parse_statistic(to_string(s)) == s);
  for (const char* bad : {"", "ADEV", "avar", "mtotdev", " oadev", "oadev ", "theo1"}) {
    CHECK_THROWS_WITH_AS(parse_statistic(bad), doctest::Contains("unknown statistic"), Error);
  }
}

TEST_CASE("tau specifications parse, and anything else is an Error naming the text") {
  CHECK(parse_tau_spec("octave").kind == TauSpec::Kind::octave);
  CHECK(parse_tau_spec("decade").kind == TauSpec::Kind::decade);
  CHECK(parse_tau_spec("all").kind == TauSpec::Kind::all);
  CHECK(parse_tau_spec("many").kind == TauSpec::Kind::many);
  CHECK(parse_tau_spec("many").per_decade == 10);
  CHECK(parse_tau_spec("many:25").per_decade == 25);
  const auto explicit_spec = parse_tau_spec("0.01, 0.1,1,2e1");
  CHECK(explicit_spec.kind == TauSpec::Kind::explicit_seconds);
  CHECK(explicit_spec.seconds == std::vector<double>{0.01, 0.1, 1.0, 20.0});
  // Times with a unit, as --duration takes them: one multiplication by the unit's factor, so
  // within an ulp or two of the seconds.
  const auto with_units = parse_tau_spec("10ms, 1 s,2min,1h,0.5");
  const std::vector<double> expected{0.01, 1.0, 120.0, 3600.0, 0.5};
  REQUIRE(with_units.seconds.size() == expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    CHECK(std::abs(with_units.seconds[i] / expected[i] - 1) < 4e-16);
  }
  for (const char* bad : {"", "octaves", "many:", "many:0", "many:-3", "many:2.5", "many:x",
                          "many:100000", "0.1,,1", "1,", "-1", "0", "nan", "inf", "1m",
                          "1deg", "-1s", "0 s", "1 s/s", "0.1;1", "fast"}) {
    INFO("spec \"" << bad << "\"");
    CHECK_THROWS_WITH_AS(parse_tau_spec(bad),
                         doctest::Contains(("\"" + std::string(bad) + "\"").c_str()), Error);
  }
}

TEST_CASE("max_averaging_factor follows Stable32's stop ratios and the term counts") {
  // N = 1001 (PHASE.DAT): (N-1)/ratio.
  CHECK(max_averaging_factor(Statistic::adev, 1001) == 200);
  CHECK(max_averaging_factor(Statistic::oadev, 1001) == 250);
  CHECK(max_averaging_factor(Statistic::mdev, 1001) == 250);
  CHECK(max_averaging_factor(Statistic::tdev, 1001) == 250);
  CHECK(max_averaging_factor(Statistic::hdev, 1001) == 200);
  CHECK(max_averaging_factor(Statistic::ohdev, 1001) == 250);
  CHECK(max_averaging_factor(Statistic::totdev, 1001) == 500);
  // Short records: never beyond the last factor with a term, but m = 1 when it has one.
  CHECK(max_averaging_factor(Statistic::oadev, 4) == 1);
  CHECK(max_averaging_factor(Statistic::ohdev, 4) == 1);
  CHECK(max_averaging_factor(Statistic::ohdev, 3) == 0);
  CHECK(max_averaging_factor(Statistic::hdev, 3) == 0);
  CHECK(max_averaging_factor(Statistic::totdev, 2) == 0);
  CHECK(max_averaging_factor(Statistic::oadev, 1) == 0);
  for (const Statistic s : kAllStatistics) {
    for (std::int64_t N = 0; N < 60; ++N) {
      const std::int64_t max_m = max_averaging_factor(s, N);
      INFO(to_string(s) << " N=" << N);
      if (max_m > 0) CHECK(term_count(s, max_m, N) >= 1);
      if (max_m == 0) CHECK(term_count(s, 1, N) == 0);
    }
  }
}

TEST_CASE("averaging factors for each tau specification") {
  const std::int64_t N = 1001;
  using V = std::vector<std::int64_t>;
  CHECK(averaging_factors(parse_tau_spec("octave"), Statistic::oadev, N, 1.0) ==
        V{1, 2, 4, 8, 16, 32, 64, 128});
  CHECK(averaging_factors(parse_tau_spec("octave"), Statistic::totdev, N, 1.0) ==
        V{1, 2, 4, 8, 16, 32, 64, 128, 256});
  CHECK(averaging_factors(parse_tau_spec("decade"), Statistic::oadev, N, 1.0) ==
        V{1, 2, 4, 10, 20, 40, 100, 200});
  CHECK(averaging_factors(parse_tau_spec("decade"), Statistic::adev, N, 1.0) ==
        V{1, 2, 4, 10, 20, 40, 100, 200});
  CHECK(averaging_factors(parse_tau_spec("many:3"), Statistic::oadev, N, 1.0) ==
        V{1, 2, 5, 10, 22, 46, 100, 215});
  // 10 per decade: 10^(k/10) rounded is 1 1 2 2 3 3 4 5 6 8 10 ...: duplicates dropped.
  CHECK(averaging_factors(parse_tau_spec("many"), Statistic::oadev, N, 1.0) ==
        V{1, 2, 3, 4, 5, 6, 8, 10, 13, 16, 20, 25, 32, 40, 50, 63, 79, 100, 126, 158, 200});
  const auto all = averaging_factors(parse_tau_spec("all"), Statistic::ohdev, N, 1.0);
  REQUIRE(all.size() == 250);
  CHECK(all.front() == 1);
  CHECK(all.back() == 250);
  // Explicit seconds at tau0 = 0.01 s: sorted and de-duplicated; a tau beyond the stop ratio
  // was asked for explicitly, so it is an error rather than a silently missing point.
  CHECK(averaging_factors(parse_tau_spec("1,0.01,0.1,0.1,2.5"), Statistic::oadev, N, 0.01) ==
        V{1, 10, 100, 250});
  CHECK_THROWS_WITH_AS(averaging_factors(parse_tau_spec("1,100"), Statistic::oadev, N, 0.01),
                       doctest::Contains("too long for oadev"), Error);
  CHECK_THROWS_WITH_AS(averaging_factors(parse_tau_spec("0.015"), Statistic::oadev, N, 0.01),
                       doctest::Contains("not a multiple"), Error);
  // Stamped logs measure tau0 from their own clock: 1 ppm (a crystal) and 300 ppm (a host clock)
  // off 100 Hz still give the m = 1, 100 points; 2000 ppm is beyond the 1e-3 tolerance (m 99.8).
  for (const double ppm : {1.0, -1.0, 300.0, -300.0}) {
    CHECK(averaging_factors(parse_tau_spec("0.01,1"), Statistic::oadev, N, 0.01 * (1 + ppm * 1e-6)) ==
          V{1, 100});
  }
  CHECK_THROWS_WITH_AS(averaging_factors(parse_tau_spec("1"), Statistic::oadev, N, 0.01 * 1.002),
                       doctest::Contains("not a multiple of the sample interval 0.01002 s"), Error);
  CHECK_THROWS_WITH_AS(averaging_factors(parse_tau_spec("0.001"), Statistic::oadev, N, 0.01),
                       doctest::Contains("shorter than the sample interval"), Error);
  CHECK(averaging_factors(parse_tau_spec("octave"), Statistic::oadev, 2, 1.0).empty());
}
