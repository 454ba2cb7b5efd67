// The dynamic Allan deviation's windows (issue 28): windows asked that cannot be formed are said
// in the warnings, with why and how many would fit, by the in-memory and the bounded-memory
// analysis alike; windows that can be formed are unchanged.
#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <random>
#include <string>

#include "sigmatau/analysis.hpp"
#include "temp_dir.hpp"
#include "test_support.hpp"

using namespace sigmatau;
using nlohmann::json;

namespace {

/// A 100 Hz gyro log "t,gx" of `rows` rows of white noise.
void write_log(const std::string& path, std::int64_t rows) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::ofstream out(path);
  out << "t,gx\n";
  char line[128];
  for (std::int64_t i = 0; i < rows; ++i) {
    std::snprintf(line, sizeof line, "%.17g,%.17g\n", static_cast<double>(i) / 100.0, noise(rng));
    out << line;
  }
}

AnalysisOptions options_with(int windows) {
  AnalysisOptions o;
  o.trim = TrimMode::none;
  o.dynamic_windows = windows;
  o.threads = 1;
  o.created_utc = "2026-01-01T00:00:00Z";
  return o;
}

json in_memory(const std::string& path, const AnalysisOptions& options) {
  LogOptions log;
  log.path = path;
  log.time_column = "t";
  Log read = read_log(log);
  AnalysisInput input;
  input.path = path;
  input.rate_hz = read.timing.rate_hz;
  AnalysisChannel channel;
  channel.name = "gx";
  channel.role = classify_channel("gx");
  channel.values = read.channels[0];
  input.channels.push_back(std::move(channel));
  input.input_units.push_back("rad/s");
  return json::parse(run_analysis(std::move(input), options).results_json);
}

json bounded(const std::string& path, const AnalysisOptions& options, const std::string& dir) {
  BoundedAnalysisSource source;
  source.log.path = path;
  source.log.time_column = "t";
  source.channels = [](const std::vector<std::string>& names) {
    std::vector<BoundedChannel> out(1);
    out[0].column = 0;
    out[0].name = names[0];
    out[0].role = classify_channel(names[0]);
    out[0].input_unit = "rad/s";
    return out;
  };
  source.rate_hz = [](const TimingReport& timing) { return timing.rate_hz; };
  source.storage.directory = dir;
  AnalysisInput input;
  input.path = path;
  return json::parse(run_analysis_bounded(source, std::move(input), options).results_json);
}

/// The warnings of results.json that speak of the dynamic Allan deviation.
std::vector<std::string> dynamic_warnings(const json& results) {
  std::vector<std::string> out;
  for (const auto& w : results.at("warnings")) {
    const std::string text = w.get<std::string>();
    if (text.find("dynamic Allan") != std::string::npos) out.push_back(text);
  }
  return out;
}

}  // namespace

TEST_CASE("1500 windows of 3000 samples are said to be too short, with how many fit") {
  test::TempDir dir("sigmatau_test_dynamic_windows");
  const std::string path = dir.file("log.csv").string();
  write_log(path, 3000);
  // 2 x 3000 / 1501 = 3 samples a window; 16 needed: at most 2 x 3000 / 16 - 1 = 374 windows.
  for (const json& results : std::vector<json>{in_memory(path, options_with(1500)),
                              bounded(path, options_with(1500), dir.file("").string())}) {
    CHECK(results["channels"][0]["dynamic"]["windows"].empty());
    const auto said = dynamic_warnings(results);
    REQUIRE(said.size() == 1);
    INFO(said[0]);
    CHECK(said[0].find("none of the 1500 windows asked was formed") != std::string::npos);
    CHECK(said[0].find("each would hold 3 samples, fewer than the 16") != std::string::npos);
    CHECK(said[0].find("at most 374 windows fit") != std::string::npos);
  }
}

TEST_CASE("374 windows of 3000 samples are formed, 375 are not") {
  test::TempDir dir("sigmatau_test_dynamic_windows");
  const std::string path = dir.file("log.csv").string();
  write_log(path, 3000);
  const json fits = in_memory(path, options_with(374));
  CHECK(fits["channels"][0]["dynamic"]["windows"].size() == 374);
  CHECK(dynamic_warnings(fits).empty());
  const json too_many = in_memory(path, options_with(375));
  CHECK(too_many["channels"][0]["dynamic"]["windows"].empty());
  CHECK(dynamic_warnings(too_many).size() == 1);
}

TEST_CASE("the most windows an int holds do not overflow the window length") {
  test::TempDir dir("sigmatau_test_dynamic_windows");
  const std::string path = dir.file("log.csv").string();
  write_log(path, 3000);
  // K + 1 overflowed an int at K = 2^31 - 1 (undefined behaviour) before the length was 64-bit.
  const json results = in_memory(path, options_with(2147483647));
  CHECK(results["channels"][0]["dynamic"]["windows"].empty());
  REQUIRE(dynamic_warnings(results).size() == 1);
  CHECK(dynamic_warnings(results)[0].find("each would hold 0 samples") != std::string::npos);
}
