// Every Stable32 result table for ADEV, OADEV, MDEV, TDEV, HDEV, OHDEV and TOTDEV in the reference
// data (shared/data/allantools/* and shared/data/allantoolkit/{Sr87, phasedat_stable32_1.61}),
// row by row: the term count exactly, tau = AF * tau0, the deviation within the printed digits.
// Input conventions (phase or frequency, tau0, scaling) are those of each directory's
// REFERENCE.md. Confidence-interval columns are not checked here (see the confidence tests).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "sigmatau/allan.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/phase_series.hpp"
#include "sigmatau/taus.hpp"
#include "test_support.hpp"

using namespace sigmatau;
namespace fs = std::filesystem;

namespace {

/// How close a deviation must be to Stable32's printed value.
struct Tolerance {
  /// true: our value, rounded to the 5 significant digits Stable32 prints, must give the printed
  /// value, i.e. lie within half a unit of the 5th digit (<= 5e-5 relative), plus a slack of
  /// 1e-7 relative: Stable32's own arithmetic is not exact, and 6 of the ~11000 rows lie within
  /// 2e-8 relative of a rounding boundary and were rounded the other way (measured here, e.g.
  /// PHASE.DAT TDEV AF 47: exact 0.78835501, printed 0.78835).
  bool printed_digits = true;
  /// Otherwise: |ours / printed - 1| <= relative.
  double relative = 0.0;
};
constexpr double kStable32Arithmetic = 1e-7;
constexpr Tolerance kPrintedDigits{true, 0.0};
/// ocxo/*_octave.txt: Stable32 read a different copy of the record (normalised f/f0,
/// "ocxo_frequency.001", ocxo/REFERENCE.md) and these rows differ from the exact statistic of the
/// stored record by up to 5e-4 at short tau and 1.8e-3 (OHDEV, AF 4096, measured here); the
/// all-tau tables, run on an exact copy, agree to every printed digit. allantools allows 2e-3 for
/// the same rows.
constexpr Tolerance kOcxoNormalisedCopy{false, 2e-3};

bool agrees(double ours, double printed, Tolerance tolerance) {
  if (!tolerance.printed_digits) return std::abs(ours / printed - 1.0) <= tolerance.relative;
  const double half_unit = 0.5 * std::pow(10.0, std::floor(std::log10(std::abs(printed))) - 4);
  return std::abs(ours - printed) <= half_unit + kStable32Arithmetic * std::abs(printed);
}

/// TOTVAR bias B = TOTVAR / AVAR = 1 - a (tau / T), T the record length, with
/// a = 0 (white FM), 1 / (3 ln 2) (flicker FM), 3/4 (random-walk FM) (NIST SP 1065 section
/// 5.2.11). Stable32 1.60 and later divide TOTVAR by B, with its own noise estimate (the Alpha
/// column), in runs that identify the noise; this module does not (no bias correction), so for
/// those tables the test multiplies Stable32's value back by sqrt(B). Taken as 0 for PM noise
/// (alpha 1, 2), which the PM-dominated tables confirm. Stable32 takes T as its number of data
/// points times tau0: M tau0 for frequency input but N tau0 for phase input (found by matching
/// its frequency and phase runs of Sr87, which differ by exactly that at large tau).
double record_points(const PhaseSeries& series) {
  return static_cast<double>(series.kind() == DataKind::phase ? series.size() : series.size() - 1);
}

double totvar_bias(int alpha, double tau_over_T) {
  double a = 0.0;
  if (alpha == -1) a = 1.0 / (3.0 * std::log(2.0));
  if (alpha <= -2) a = 0.75;
  return 1.0 - a * tau_over_T;
}

struct Row {
  std::int64_t af = 0;
  double tau = 0;
  std::int64_t n = 0;
  int alpha = 0;
  double sigma = 0;
  bool commented = false;  // a genuine Stable32 row that the source's tests left out ("# 2426 ...")
};

/// Splits a line into whitespace-separated tokens.
std::vector<std::string> tokens(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> t;
  for (std::string s; in >> s;) t.push_back(s);
  return t;
}

bool is_integer(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

/// Data rows of a Stable32 table: `AF Tau # Alpha Min Sigma Max`, header lines either start with
/// '#' (allantools copies) or precede the column titles (allantoolkit copies).
std::vector<Row> read_table(const fs::path& path) {
  std::ifstream in(path);
  REQUIRE(in.good());
  std::vector<Row> rows;
  for (std::string line; std::getline(in, line);) {
    bool commented = false;
    std::string body = line;
    if (!body.empty() && body[0] == '#') {
      body = body.substr(1);
      commented = true;
    }
    const auto t = tokens(body);
    if (t.size() != 7 || !is_integer(t[0]) || !is_integer(t[2])) continue;
    rows.push_back({std::stoll(t[0]), std::stod(t[1]), std::stoll(t[2]), std::stoi(t[3]),
                    std::stod(t[5]), commented});
  }
  return rows;
}

/// The statistic named by the table's "Sigma Type:" header line; false when there is none.
bool sigma_type(const fs::path& path, Statistic& statistic) {
  std::ifstream in(path);
  const std::string key = "Sigma Type:";
  for (std::string line; std::getline(in, line);) {
    const auto at = line.find(key);
    if (at == std::string::npos) continue;
    std::string type = line.substr(at + key.size());
    type.erase(0, type.find_first_not_of(' '));
    type.erase(type.find_last_not_of(" \r") + 1);
    const std::pair<const char*, Statistic> names[] = {
        {"Allan", Statistic::adev},       {"Overlapping Allan", Statistic::oadev},
        {"Modified Allan", Statistic::mdev}, {"Time", Statistic::tdev},
        {"Hadamard", Statistic::hdev},    {"Overlapping Hadamard", Statistic::ohdev},
        {"Total", Statistic::totdev}};
    for (const auto& [name, s] : names) {
      if (type == name) {
        statistic = s;
        return true;
      }
    }
    return false;
  }
  return false;
}

/// The last number of every non-comment line (Sr87 frequency files carry a time stamp first).
std::vector<double> parse_numbers(std::istream& in) {
  std::vector<double> v;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    const auto t = tokens(line);
    if (t.empty()) continue;
    v.push_back(std::stod(t.back()));
  }
  return v;
}

std::vector<double> read_numbers(const fs::path& path) {
  if (path.extension() == ".gz") {
    // gzip is part of every Debian base system; the library's zlib is private to it.
    const std::string command = "gzip -dc '" + path.string() + "'";
    std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
    REQUIRE(pipe != nullptr);
    std::string text;
    char buffer[1 << 16];
    for (std::size_t got; (got = std::fread(buffer, 1, sizeof buffer, pipe.get())) > 0;) {
      text.append(buffer, got);
    }
    std::istringstream in(text);
    return parse_numbers(in);
  }
  std::ifstream in(path);
  REQUIRE(in.good());
  return parse_numbers(in);
}

/// The statistic a table holds, from the file name's tokens (adev, OADEV, ... between '_' and
/// '.'); false for tables of statistics this module does not implement (mtotdev, theo1, ...).
bool statistic_of(const fs::path& file, Statistic& statistic) {
  std::string stem = file.stem().string();
  std::transform(stem.begin(), stem.end(), stem.begin(), [](unsigned char c) { return std::tolower(c); });
  std::replace(stem.begin(), stem.end(), '.', '_');
  std::istringstream in(stem);
  for (std::string token; std::getline(in, token, '_');) {
    try {
      statistic = parse_statistic(token);
      return true;
    } catch (const Error&) {
    }
  }
  return false;
}

struct Totals {
  int tables = 0;
  int rows = 0;
  int commented_rows = 0;
  int bias_corrected_tables = 0;
  int relabelled_tables = 0;
  double worst = 0.0;  // largest |dev / expected - 1| seen
};

/// Checks every row of `table` against `series`.
void check_table(const PhaseSeries& series, const fs::path& table, Statistic statistic,
                 Tolerance tolerance, Totals& totals) {
  const auto rows = read_table(table);
  INFO("table " << table.string());
  REQUIRE(!rows.empty());
  std::vector<std::int64_t> factors;
  for (const auto& r : rows) factors.push_back(r.af);
  const auto points = compute_deviation(series, statistic, factors);
  REQUIRE(points.size() == rows.size());
  // TOTDEV tables are either plain (older Stable32, all-tau runs) or bias-corrected with the
  // Alpha column (see totvar_bias); a table must match one convention in every row.
  bool bias_corrected = false;
  if (statistic == Statistic::totdev) {
    int plain = 0, corrected = 0;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const double tau_over_T = static_cast<double>(rows[i].af) / record_points(series);
      const double dev = points[i].dev;
      if (agrees(dev, rows[i].sigma, tolerance)) ++plain;
      if (agrees(dev / std::sqrt(totvar_bias(rows[i].alpha, tau_over_T)), rows[i].sigma, tolerance)) {
        ++corrected;
      }
    }
    bias_corrected = corrected > plain;
    if (bias_corrected) ++totals.bias_corrected_tables;
  }
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Row& r = rows[i];
    const DeviationPoint& p = points[i];
    INFO("AF " << r.af << std::string(r.commented ? " (commented-out row)" : "")
               << std::string(bias_corrected ? " (bias-corrected table)" : ""));
    CHECK(p.m == r.af);
    CHECK(p.n_terms == r.n);
    CHECK(p.tau_s == static_cast<double>(r.af) * series.tau0_s());
    // The printed tau has 5 significant digits: within half a unit of the 5th.
    CHECK(p.tau_s == test::rel(r.tau, 5e-5));
    // Our value in Stable32's convention (bias-corrected TOTDEV tables: divided by sqrt(B)).
    double ours = p.dev;
    if (bias_corrected) {
      ours /= std::sqrt(totvar_bias(r.alpha, static_cast<double>(r.af) / record_points(series)));
    }
    INFO("ours " << std::setprecision(10) << ours << ", printed " << r.sigma);
    CHECK(agrees(ours, r.sigma, tolerance));
    totals.worst = std::max(totals.worst, std::abs(ours / r.sigma - 1.0));
    ++totals.rows;
    if (r.commented) ++totals.commented_rows;
  }
  ++totals.tables;
}

/// Checks every table of one statistic we implement in `dir` whose name passes `select`.
Totals check_directory(const PhaseSeries& series, const fs::path& dir,
                       const std::function<Tolerance(const std::string&)>& tolerance_for,
                       const std::function<bool(const std::string&)>& select = {}) {
  Totals totals;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir)) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const auto& file : files) {
    const std::string name = file.filename().string();
    if (file.extension() != ".txt" || (select && !select(name))) continue;
    Statistic by_name = Statistic::oadev;
    if (!statistic_of(file, by_name)) continue;
    // The header is what Stable32 computed; one Sr87 file (phase/octave/mdev.txt) holds OADEV.
    Statistic statistic = by_name;
    if (sigma_type(file, statistic) && statistic != by_name) {
      MESSAGE(file.string() << " holds " << to_string(statistic) << " (Sigma Type header), not "
                            << to_string(by_name) << " as its name says: checked as "
                            << to_string(statistic));
      ++totals.relabelled_tables;
    }
    check_table(series, file, statistic, tolerance_for(name), totals);
  }
  MESSAGE(dir.string() << ": " << totals.tables << " tables, " << totals.rows << " rows ("
                       << totals.commented_rows << " commented-out rows, "
                       << totals.bias_corrected_tables << " bias-corrected TOTDEV tables), "
                       << "largest relative difference " << totals.worst);
  return totals;
}

Tolerance default_tolerance(const std::string&) { return kPrintedDigits; }

}  // namespace

TEST_CASE("PHASE.DAT: Stable32 1.53, 1.60 and 1.61 tables") {
  if (!test::has_reference_data("allantools/phasedat")) return;
  const auto dir = test::reference_data_dir() / "allantools/phasedat";
  const auto series = PhaseSeries::from_phase(read_numbers(dir / "PHASE.DAT"), 1.0);
  REQUIRE(series.size() == 1001);
  // phase_dat_{adev,...,totdev}.txt and the seven *_octave.txt.
  CHECK(check_directory(series, dir, default_tolerance).tables == 14);
  if (!test::has_reference_data("allantoolkit/phasedat_stable32_1.61")) return;
  const auto dir161 = test::reference_data_dir() / "allantoolkit/phasedat_stable32_1.61";
  const auto series161 = PhaseSeries::from_phase(read_numbers(dir161 / "PHASE.DAT"), 1.0);
  CHECK(check_directory(series161, dir161, default_tolerance).tables == 7);
}

TEST_CASE("Cs 5071A vs H-maser, 556990 phase points: decade and all-tau tables") {
  if (!test::has_reference_data("allantools/Cs5071A")) return;
  const auto dir = test::reference_data_dir() / "allantools/Cs5071A";
  const auto series = PhaseSeries::from_phase(read_numbers(dir / "5071A_phase.txt.gz"), 1.0);
  REQUIRE(series.size() == 556990);
  CHECK(check_directory(series, dir, default_tolerance).tables == 14);
}

TEST_CASE("Keysight 53230A noise floor, 55688 phase points") {
  if (!test::has_reference_data("allantools/Keysight53230A_ti_noise_floor")) return;
  const auto dir = test::reference_data_dir() / "allantools/Keysight53230A_ti_noise_floor";
  const auto series = PhaseSeries::from_phase(read_numbers(dir / "tic_phase.txt"), 1.0);
  REQUIRE(series.size() == 55688);
  CHECK(check_directory(series, dir, default_tolerance).tables == 7);
}

TEST_CASE("GPS 1PPS vs H-maser, 241218 phase points") {
  if (!test::has_reference_data("allantools/gps_1pps")) return;
  const auto dir = test::reference_data_dir() / "allantools/gps_1pps";
  const auto series =
      PhaseSeries::from_phase(read_numbers(dir / "gps_1pps_phase_data.txt.gz"), 1.0);
  REQUIRE(series.size() == 241218);
  CHECK(check_directory(series, dir, default_tolerance).tables == 7);
}

TEST_CASE("OCXO frequency record, converted to fractional frequency (f - 1e7) / 1e7") {
  if (!test::has_reference_data("allantools/ocxo")) return;
  const auto dir = test::reference_data_dir() / "allantools/ocxo";
  auto y = read_numbers(dir / "ocxo_frequency.txt");
  REQUIRE(y.size() == 19982);
  for (auto& v : y) v = (v - 1e7) / 1e7;
  const auto series = PhaseSeries::from_rate(y, 1.0);
  const auto tolerance = [](const std::string& name) {
    return name.rfind("stable32_", 0) == 0 ? kPrintedDigits : kOcxoNormalisedCopy;
  };
  CHECK(check_directory(series, dir, tolerance).tables == 14);
}

TEST_CASE("simulated flicker-FM record, 10000 fractional-frequency points") {
  if (!test::has_reference_data("allantools/pink_frequency")) return;
  const auto dir = test::reference_data_dir() / "allantools/pink_frequency";
  const auto y = read_numbers(dir / "pink_frequency.txt");
  REQUIRE(y.size() == 10000);
  // The main tables were run with tau0 = 42 s, s32_oadev_octave.txt with tau0 = 1 s.
  const auto series42 = PhaseSeries::from_rate(y, 42.0);
  const auto series1 = PhaseSeries::from_rate(y, 1.0);
  const auto is_octave = [](const std::string& name) { return name.rfind("s32_", 0) == 0; };
  CHECK(check_directory(series42, dir, default_tolerance,
                        [&](const std::string& n) { return !is_octave(n); })
            .tables == 7);
  CHECK(check_directory(series1, dir, default_tolerance, is_octave).tables == 1);
}

TEST_CASE("Sr87 optical clock: frequency, phase and normalised phase; octave, decade, many tau") {
  if (!test::has_reference_data("allantoolkit/Sr87")) return;
  const auto dir = test::reference_data_dir() / "allantoolkit/Sr87";
  const double tau0 = 2.5;  // Stable32 header "Tau: 2.500000e+00"; the time stamps are ignored
  const auto freq = PhaseSeries::from_rate(read_numbers(dir / "freq/freq_data.txt"), tau0);
  const auto phase = PhaseSeries::from_phase(read_numbers(dir / "phase/phase_data.txt"), tau0);
  const auto phase0 = PhaseSeries::from_phase(read_numbers(dir / "phase0/phase0_data.txt"), tau0);
  REQUIRE(freq.size() == 1253);
  REQUIRE(phase.size() == 1253);
  REQUIRE(phase0.size() == 1253);
  int tables = 0;
  for (const char* grid : {"octave", "decade", "many"}) {
    tables += check_directory(freq, dir / "freq" / grid, default_tolerance).tables;
    tables += check_directory(phase, dir / "phase" / grid, default_tolerance).tables;
    tables += check_directory(phase0, dir / "phase0" / grid, default_tolerance).tables;
  }
  CHECK(tables == 3 * 3 * 7);
}

namespace {

/// TOTVAR by its definition (NIST SP 1065 eq. 25 with the reflections of sec. 5.2.11), in long
/// double, from the raw phase x[0..N): 1/(2 tau^2 (N-2)) sum_{i=1}^{N-2} (x*[i-m] - 2x[i] +
/// x*[i+m])^2, x*[-j] = 2x[0] - x[j], x*[N-1+j] = 2x[N-1] - x[N-1-j].
double brute_force_totdev(const std::vector<double>& x, std::int64_t m, double tau0_s) {
  const auto N = static_cast<std::int64_t>(x.size());
  const auto at = [&](std::int64_t k) -> long double {
    if (k < 0) return 2.0L * x[0] - x[static_cast<std::size_t>(-k)];
    if (k > N - 1) return 2.0L * x[static_cast<std::size_t>(N - 1)] -
                          x[static_cast<std::size_t>(2 * (N - 1) - k)];
    return x[static_cast<std::size_t>(k)];
  };
  long double sum = 0;
  for (std::int64_t i = 1; i <= N - 2; ++i) {
    const long double d = at(i - m) - 2 * at(i) + at(i + m);
    sum += d * d;
  }
  const long double tau = static_cast<long double>(m) * tau0_s;
  return static_cast<double>(std::sqrt(sum / (2 * tau * tau * static_cast<long double>(N - 2))));
}

}  // namespace

TEST_CASE("Stable32's stop ratios count data points: N phase points reach N/4 and N/2") {
  // Stable32 (and allantoolkit's tau_generator) stop a run at (data points) / ratio, the data
  // points being what was given: N phase points, or M = N - 1 frequency values. An 8192-point
  // phase record therefore reaches OADEV/MDEV/TDEV/OHDEV at m = 2048, ADEV/HDEV at 1638 and
  // TOTDEV at 4096; 8192 frequency values (8193 phase points) the same m.
  const std::int64_t N = 8192;
  using V = std::vector<std::int64_t>;
  const TauSpec octave = parse_tau_spec("octave");
  for (const DataKind kind : {DataKind::phase, DataKind::rate, DataKind::increment}) {
    const std::int64_t points = kind == DataKind::phase ? N : N + 1;
    INFO(to_string(kind) << " input, " << points << " phase points");
    for (const Statistic s : {Statistic::oadev, Statistic::mdev, Statistic::tdev,
                              Statistic::ohdev}) {
      CHECK(max_averaging_factor(s, points, kind) == 2048);
      CHECK(averaging_factors(octave, s, points, 1.0, kind).back() == 2048);
    }
    CHECK(max_averaging_factor(Statistic::adev, points, kind) == 1638);
    CHECK(max_averaging_factor(Statistic::hdev, points, kind) == 1638);
    CHECK(max_averaging_factor(Statistic::totdev, points, kind) == 4096);
    CHECK(averaging_factors(octave, Statistic::totdev, points, 1.0, kind).back() == 4096);
    CHECK(averaging_factors(parse_tau_spec("2048"), Statistic::oadev, points, 1.0, kind) ==
          V{2048});
    CHECK(averaging_factors(parse_tau_spec("4096"), Statistic::totdev, points, 1.0, kind) ==
          V{4096});
    CHECK_THROWS_WITH_AS(averaging_factors(parse_tau_spec("2049"), Statistic::oadev, points, 1.0,
                                           kind),
                         doctest::Contains("the longest is 2048 s"), Error);
  }
  // Every limit has terms, for every length and kind (the term counts are the estimators').
  for (const DataKind kind : {DataKind::phase, DataKind::rate}) {
    for (const Statistic s : {Statistic::adev, Statistic::oadev, Statistic::mdev,
                              Statistic::tdev, Statistic::hdev, Statistic::ohdev,
                              Statistic::totdev}) {
      for (std::int64_t n = 0; n < 70; ++n) {
        const std::int64_t max_m = max_averaging_factor(s, n, kind);
        INFO(to_string(s) << " " << to_string(kind) << " N=" << n);
        if (max_m > 0) CHECK(term_count(s, max_m, n) >= 1);
        if (max_m == 0) CHECK(term_count(s, 1, n) == 0);
      }
    }
  }
  // The last octave is computed: OADEV at N/4 and TOTDEV at N/2 (all of whose terms reach past
  // an end) equal their definitions.
  std::vector<double> x(static_cast<std::size_t>(N));
  std::uint64_t state = 12345;
  double walk = 0;
  for (auto& v : x) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    walk += static_cast<double>(state >> 11) * 0x1.0p-53 - 0.5;  // white FM: a random walk
    v = walk;
  }
  const auto series = PhaseSeries::from_phase(x, 1.0);
  const auto totdev = compute_deviation(
      series, Statistic::totdev,
      averaging_factors(octave, Statistic::totdev, N, 1.0, DataKind::phase));
  REQUIRE(!totdev.empty());
  CHECK(totdev.back().m == 4096);
  CHECK(totdev.back().n_terms == N - 2);
  for (const std::int64_t m : {std::int64_t{1}, std::int64_t{1000}, std::int64_t{4095},
                               std::int64_t{4096}}) {
    INFO("TOTDEV m = " << m);
    const auto p = compute_deviation(series, Statistic::totdev, std::vector<std::int64_t>{m});
    REQUIRE(p.size() == 1);
    // Double-double sums against long double: agreement to 1e-12 (a loss of precision in the
    // reflected terms would show at 1e-8 or worse).
    CHECK(p[0].dev == test::rel(brute_force_totdev(x, m, 1.0), 1e-12));
  }
  const auto oadev = compute_deviation(
      series, Statistic::oadev, averaging_factors(octave, Statistic::oadev, N, 1.0, DataKind::phase));
  CHECK(oadev.back().m == 2048);
  CHECK(oadev.back().n_terms == N - 2 * 2048);
}
