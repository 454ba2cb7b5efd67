// Exporters against hand-computed files (tests/data/exports, README there gives the arithmetic),
// and THEORY.md T9 (PX4 defaults <-> densities).
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <numbers>
#include <regex>
#include <sstream>

#include "sigmatau/error.hpp"
#include "sigmatau/filter_export.hpp"
#include "test_support.hpp"

using namespace sigmatau;
using sigmatau::test::test_data_dir;

namespace {

/// The hand files carry 7 significant digits (or exact values): rtol 1e-6.
constexpr double kHandDigits = 1e-6;

std::string read(const std::string& name) {
  std::ifstream in(test_data_dir() / "exports" / name);
  REQUIRE(in.good());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Splits text into numbers and other non-space runs.
std::vector<std::string> tokens(const std::string& text) {
  static const std::regex token(R"([-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?|[^\s\d.+-]+|[.+-])");
  std::vector<std::string> out;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), token);
       it != std::sregex_iterator(); ++it) {
    out.push_back(it->str());
  }
  return out;
}

bool is_number(const std::string& t) {
  return !t.empty() && (std::isdigit(static_cast<unsigned char>(t.back())) != 0);
}

/// Words must match exactly, numbers within rtol.
void check_same_text(const std::string& actual, const std::string& expected) {
  INFO("actual:\n" << actual);
  const auto a = tokens(actual), e = tokens(expected);
  REQUIRE(a.size() == e.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    INFO("token " << i << ": " << a[i] << " vs expected " << e[i]);
    if (is_number(e[i]) && is_number(a[i])) {
      const double x = std::stod(a[i]), y = std::stod(e[i]);
      CHECK(std::abs(x - y) <= kHandDigits * std::abs(y));
    } else {
      CHECK(a[i] == e[i]);
    }
  }
}

void check_same_json(const nlohmann::json& a, const nlohmann::json& e, const std::string& path) {
  INFO(path);
  if (e.is_number()) {
    REQUIRE(a.is_number());
    const double x = a.get<double>(), y = e.get<double>();
    CHECK(std::abs(x - y) <= kHandDigits * std::abs(y));
  } else if (e.is_object()) {
    REQUIRE(a.is_object());
    CHECK(a.size() == e.size());
    for (const auto& [key, value] : e.items()) {
      REQUIRE(a.contains(key));
      check_same_json(a[key], value, path + "." + key);
    }
  } else if (e.is_array()) {
    REQUIRE(a.is_array());
    REQUIRE(a.size() == e.size());
    for (std::size_t i = 0; i < e.size(); ++i) {
      check_same_json(a[i], e[i], path + "[" + std::to_string(i) + "]");
    }
  } else {
    CHECK(a == e);
  }
}

/// The input of the hand files: 200 Hz, F = 1, rw from K (tests/data/exports/README.md).
DiscreteNoise reference_noise() {
  NoiseTerms g, a;
  g.white = 2e-4;
  g.rate_random_walk = 3e-6;
  a.white = 2e-3;
  a.rate_random_walk = 4e-5;
  ConvertOptions o;
  o.rate_hz = 200;
  return convert_noise({uniform_triad(Sensor::gyro, g), uniform_triad(Sensor::accel, a)}, o,
                       "test input");
}

}  // namespace

TEST_CASE("each exporter matches its hand-computed file") {
  const DiscreteNoise noise = reference_noise();
  SUBCASE("kalibr") {
    check_same_text(export_filter_config(noise, ExportFormat::kalibr), read("kalibr.yaml"));
  }
  SUBCASE("openvins") {
    check_same_text(export_filter_config(noise, ExportFormat::openvins), read("openvins.yaml"));
  }
  SUBCASE("vins-fusion") {
    check_same_text(export_filter_config(noise, ExportFormat::vins_fusion),
                    read("vins-fusion.yaml"));
  }
  SUBCASE("gtsam") {
    check_same_text(export_filter_config(noise, ExportFormat::gtsam), read("gtsam.yaml"));
  }
  SUBCASE("px4") {
    check_same_text(export_filter_config(noise, ExportFormat::px4), read("px4.txt"));
  }
  SUBCASE("json") {
    check_same_json(nlohmann::json::parse(export_filter_config(noise, ExportFormat::json)),
                    nlohmann::json::parse(read("json.json")), "$");
  }
}

TEST_CASE("json for a Gauss-Markov bias with inflation matches its hand-computed file") {
  NoiseTerms g;
  g.bias_instability = (3.0 / 3600 * std::numbers::pi / 180) / kFlickerFloorFactor;
  ConvertOptions o;
  o.rate_hz = 100;
  o.bias_model = BiasModel::gauss_markov;
  o.tau_min_s = 100;
  o.inflate = 2;
  const DiscreteNoise noise = convert_noise({uniform_triad(Sensor::gyro, g)}, o, "test input");
  check_same_json(nlohmann::json::parse(export_filter_config(noise, ExportFormat::json)),
                  nlohmann::json::parse(read("json_gm.json")), "$");
  // The random-walk formats say that they write the equivalent random walk.
  CHECK(export_filter_config(noise, ExportFormat::kalibr).find("Gauss-Markov has no counterpart") !=
        std::string::npos);
}

TEST_CASE("T9: PX4 defaults 0.015 rad/s and 1e-3 rad/s^2 are densities 1.5e-3 and 1e-4") {
  // THEORY.md section 9 T9 / 5.5: density = EKF2 value x sqrt(0.01 s). Inverted here: the
  // densities 1.5e-3 rad/s/sqrt(Hz) and 1e-4 rad/s^2/sqrt(Hz) export as 0.015 and 0.001.
  NoiseTerms g;
  g.white = 1.5e-3;
  g.rate_random_walk = 1e-4;
  ConvertOptions o;
  o.rate_hz = 1000;  // EKF2 works at its own prediction interval: the IMU rate does not enter
  const DiscreteNoise noise = convert_noise({uniform_triad(Sensor::gyro, g)}, o, "T9");
  const std::string text = export_filter_config(noise, ExportFormat::px4);
  std::smatch m;
  REQUIRE(std::regex_search(text, m, std::regex(R"(param set EKF2_GYR_NOISE (\S+))")));
  SIGMATAU_CHECK_REL(std::stod(m[1]), 0.015, kHandDigits);  // printed with 7 digits
  REQUIRE(std::regex_search(text, m, std::regex(R"(param set EKF2_GYR_B_NOISE (\S+))")));
  SIGMATAU_CHECK_REL(std::stod(m[1]), 1e-3, kHandDigits);
  CHECK(text.find("# EKF2_ACC_NOISE: not given") != std::string::npos);
}

TEST_CASE("PX4 values outside the documented ranges are flagged") {
  NoiseTerms g;
  g.white = 0.1;  // 1 rad/s per step at dt = 0.01 s: above the 0.1 maximum
  ConvertOptions o;
  o.rate_hz = 100;
  const DiscreteNoise noise = convert_noise({uniform_triad(Sensor::gyro, g)}, o, "range");
  CHECK(export_filter_config(noise, ExportFormat::px4).find("outside the documented range") !=
        std::string::npos);
}

TEST_CASE("format names parse and an empty conversion cannot be exported") {
  CHECK(parse_export_format("vins-fusion") == ExportFormat::vins_fusion);
  CHECK(parse_export_format("px4") == ExportFormat::px4);
  CHECK_THROWS_AS(parse_export_format("rovio"), Error);
  DiscreteNoise empty;
  empty.options.rate_hz = 100;
  CHECK_THROWS_AS(export_filter_config(empty, ExportFormat::json), Error);
}

namespace {

/// A gyro triad alone at 100 Hz with white noise 2e-4 rad/s/sqrt(Hz) and the bias term that
/// `add_bias` sets, its bias stability taken as reached after `t_ref_s`.
template <class AddBias>
DiscreteNoise gyro_at_100hz(AddBias add_bias, double t_ref_s = kDefaultReferenceTime) {
  NoiseTerms g;
  g.white = 2e-4;
  add_bias(g);
  ConvertOptions o;
  o.rate_hz = 100;
  o.t_ref_s = t_ref_s;
  return convert_noise({uniform_triad(Sensor::gyro, g)}, o, "gyro at 100 Hz");
}

}  // namespace

TEST_CASE("YAML numbers always carry a decimal point (PyYAML reads 1e-05 as a string)") {
  const DiscreteNoise noise = gyro_at_100hz([](NoiseTerms& g) { g.rate_random_walk = 1e-5; });
  for (const ExportFormat f : {ExportFormat::kalibr, ExportFormat::openvins}) {
    const std::string text = export_filter_config(noise, f);
    CHECK(text.find("gyroscope_random_walk: 1.0e-05") != std::string::npos);
    // No number anywhere of the form digits, 'e', exponent without a '.' before it.
    CHECK_FALSE(std::regex_search(text, std::regex(R"((^|[^.\d])\d+e[-+]\d)")));
  }
}

TEST_CASE("files a filter cannot load say what is missing") {
  // Gyro white noise only: no accelerometer, no random walk.
  const DiscreteNoise noise = gyro_at_100hz([](NoiseTerms&) {});
  CHECK(missing_filter_keys(noise, ExportFormat::kalibr) ==
        std::vector<std::string>{"accelerometer_noise_density", "accelerometer_random_walk",
                                 "gyroscope_random_walk"});
  CHECK(missing_filter_keys(noise, ExportFormat::vins_fusion) ==
        std::vector<std::string>{"acc_n", "acc_w", "gyr_w"});
  // PX4 would keep its defaults (a flight tune) and GTSAM an identity: a mixed set either way.
  CHECK(missing_filter_keys(noise, ExportFormat::px4) ==
        std::vector<std::string>{"EKF2_ACC_NOISE", "EKF2_ACC_B_NOISE", "EKF2_GYR_B_NOISE"});
  CHECK(missing_filter_keys(noise, ExportFormat::gtsam) ==
        std::vector<std::string>{"accelerometerCovariance", "biasAccCovariance",
                                 "biasOmegaCovariance"});
  CHECK(missing_filter_keys(noise, ExportFormat::json).empty());  // absent there, never zero
  for (const ExportFormat f : {ExportFormat::kalibr, ExportFormat::openvins,
                               ExportFormat::vins_fusion, ExportFormat::gtsam, ExportFormat::px4,
                               ExportFormat::json}) {
    CHECK(missing_filter_keys(reference_noise(), f).empty());
  }
  const auto missing = missing_filter_values(noise, ExportFormat::kalibr);
  REQUIRE(missing.size() == 3);
  CHECK((missing[0].sensor == Sensor::accel && !missing[0].bias));
  CHECK((missing[2].sensor == Sensor::gyro && missing[2].bias));
  CHECK(missing_values_text(missing) == "accelerometer white noise and bias, gyroscope bias");
  CHECK(export_filter_config(noise, ExportFormat::kalibr)
            .find("# gyroscope_random_walk: not given; Kalibr needs it") != std::string::npos);
  // Each incomplete file says so in its header, with what its filter does about it.
  const std::string vins = export_filter_config(noise, ExportFormat::vins_fusion);
  CHECK(vins.find("# WARNING: incomplete: acc_n, acc_w, gyr_w not in the input; VINS-Fusion "
                  "does not refuse the file: it reads 0") != std::string::npos);
  CHECK(export_filter_config(noise, ExportFormat::px4)
            .find("# WARNING: incomplete: EKF2_ACC_NOISE, EKF2_ACC_B_NOISE, EKF2_GYR_B_NOISE not "
                  "in the input; PX4 keeps its own default") != std::string::npos);
  CHECK(export_filter_config(reference_noise(), ExportFormat::kalibr).find("incomplete") ==
        std::string::npos);
}

TEST_CASE("VINS-Fusion and OpenVINS files are what OpenCV's FileStorage reads") {
  // cv::FileStorage (OpenCV 4.6, checked by hand) refuses a YAML file whose first line is not
  // "%YAML:1.0" ("Input file is invalid"), and of two equal keys keeps the first; VINS-Fusion
  // reads 0 for a key that is missing.
  const DiscreteNoise noise = reference_noise();
  for (const ExportFormat f : {ExportFormat::vins_fusion, ExportFormat::openvins}) {
    const std::string text = export_filter_config(noise, f);
    CHECK(text.rfind("%YAML:1.0\n", 0) == 0);
    std::map<std::string, int> keys;  // top-level keys, each at most once
    std::istringstream lines(text);
    for (std::string line; std::getline(lines, line);) {
      const auto colon = line.find(':');
      if (line.empty() || line[0] == '#' || line[0] == '%' || line[0] == ' ' ||
          colon == std::string::npos) {
        continue;
      }
      CHECK(++keys[line.substr(0, colon)] == 1);
    }
  }
  const std::string vins = export_filter_config(noise, ExportFormat::vins_fusion);
  for (const char* key : {"acc_n: ", "gyr_n: ", "acc_w: ", "gyr_w: "}) {
    CHECK(vins.find(std::string("\n") + key) != std::string::npos);
  }
  // Appended to an existing config the old values would stay: the header says to replace them.
  CHECK(vins.find("replace the values of acc_n, gyr_n, acc_w and gyr_w in your config") !=
        std::string::npos);
  CHECK(vins.find("do not append these lines to the config: of two equal keys OpenCV keeps the "
                  "first") != std::string::npos);
}

TEST_CASE("PX4's prediction interval is the whole number of IMU intervals nearest EKF2_PREDICT_US") {
  // ImuDownSampler::reset: max(roundf(EKF2_PREDICT_US / IMU interval), 1) intervals.
  // Exact in binary up to the division's round-off: rtol 1e-12.
  constexpr double kRoundOff = 1e-12;
  SIGMATAU_CHECK_REL(px4_prediction_interval(0.008, 200), 0.010, kRoundOff);   // 1.6 -> 2
  SIGMATAU_CHECK_REL(px4_prediction_interval(0.005, 100), 0.010, kRoundOff);   // 0.5 -> 1
  SIGMATAU_CHECK_REL(px4_prediction_interval(0.0012, 1000), 0.001, kRoundOff);  // 1.2 -> 1
  SIGMATAU_CHECK_REL(px4_prediction_interval(0.015, 200), 0.015, kRoundOff);   // whole: kept
  SIGMATAU_CHECK_REL(px4_prediction_interval(0.0075, 200), 0.010, kRoundOff);  // 1.5 -> 2
  SIGMATAU_CHECK_REL(px4_prediction_interval(0.001, 100), 0.010, kRoundOff);   // at least one
  // PX4's documented range is 1000 to 20000 us, in whole microseconds (an int32 parameter).
  CHECK_THROWS_AS(px4_prediction_interval(0.020001, 200), Error);
  CHECK_THROWS_AS(px4_prediction_interval(0.000999, 200), Error);
  CHECK_THROWS_AS(px4_prediction_interval(0.0080005, 200), Error);
  CHECK_NOTHROW(px4_prediction_interval(0.020, 200));
  // The values follow the interval used: at 200 Hz, 8000 us gives N / sqrt(0.010 s), 12 % below
  // N / sqrt(0.008 s); at 100 Hz, 5000 us gives N / sqrt(0.010 s), 41 % below N / sqrt(0.005 s).
  for (const auto& [rate, asked_s] : {std::pair{200.0, 0.008}, std::pair{100.0, 0.005}}) {
    NoiseTerms g;
    g.white = 2e-4;
    ConvertOptions o;
    o.rate_hz = rate;
    ExportOptions e;
    e.px4_predict_interval_s = asked_s;
    const std::string text = export_filter_config(
        convert_noise({uniform_triad(Sensor::gyro, g)}, o, "px4"), ExportFormat::px4, e);
    std::smatch m;
    REQUIRE(std::regex_search(text, m, std::regex(R"(param set EKF2_GYR_NOISE (\S+))")));
    SIGMATAU_CHECK_REL(std::stod(m[1]), 2e-4 / std::sqrt(0.010), kHandDigits);
    CHECK(text.find("dt = 0.01 s") != std::string::npos);
  }
  ExportOptions too_long;
  too_long.px4_predict_interval_s = 0.025;
  CHECK_THROWS_AS(export_filter_config(reference_noise(), ExportFormat::px4, too_long), Error);
}

TEST_CASE("the PX4 file compares its values with PX4's defaults and names the inflation factor") {
  const std::string text = export_filter_config(reference_noise(), ExportFormat::px4);
  // Defaults 0.015 rad/s and 0.001 rad/s^2 against 0.002 and 3e-5 (tests/data/exports/px4.txt).
  CHECK(text.find("EKF2_GYR_NOISE 7.5x") != std::string::npos);
  CHECK(text.find("EKF2_GYR_B_NOISE 33.3x") != std::string::npos);
  CHECK(text.find("set high on purpose") != std::string::npos);
  CHECK(text.find("times the inflation factor 1: raise the factor for flight") !=
        std::string::npos);
}

TEST_CASE("a bias random walk made from a bias stability is named a rule of thumb in the file") {
  const DiscreteNoise noise =
      gyro_at_100hz([](NoiseTerms& g) { g.bias_instability = 1e-5; }, 50);
  for (const ExportFormat f : {ExportFormat::kalibr, ExportFormat::vins_fusion, ExportFormat::px4,
                               ExportFormat::gtsam}) {
    CHECK(export_filter_config(noise, f).find("rule of thumb") != std::string::npos);
    CHECK(export_filter_config(noise, f).find("T_ref = 50 s") != std::string::npos);
  }
  // From a K given as such, no such line.
  CHECK(export_filter_config(reference_noise(), ExportFormat::kalibr).find("rule of thumb") ==
        std::string::npos);
}
