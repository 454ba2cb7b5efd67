// How verdicts read (review E, A3/A5): a ratio a hair over 1 never prints as "1", a typical
// limit is flagged as not a guarantee, and the plot ranges always show two labelled ticks.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numbers>
#include <string>
#include <tuple>
#include <unistd.h>

#include "sigmatau/compliance.hpp"
#include "sigmatau/plot.hpp"
#include "sigmatau/spec.hpp"
#include "made_up_sheet.hpp"
#include "test_support.hpp"

using namespace sigmatau;

TEST_CASE("a ratio within 1 % of the limit keeps four digits and never reads as 1") {
  // ADIS16470 at its typical ARW: 1.0013 was printed "1" in a fail row.
  CHECK(format_ratio(1.0013) == "1.001");
  CHECK(format_ratio(0.9987) == "0.9987");
  CHECK(format_ratio(1.0) == "1.000");  // no trailing-zero stripping
  CHECK(format_ratio(0.5) == "0.500");
  CHECK(format_ratio(0.579) == "0.579");
  CHECK(format_ratio(12.34) == "12.3");  // no bare point from %#g
  CHECK(format_ratio(250.4) == "250");
  CHECK(format_ratio(std::nan("")) == "n/a");
  // Closer than four digits can show: more digits, until it no longer reads as 1.
  for (const double r : {1.00004, 0.99996, 1 + 1e-9}) {
    const std::string text = format_ratio(r);
    CAPTURE(text);
    CHECK(std::strtod(text.c_str(), nullptr) != 1.0);
    CHECK((std::strtod(text.c_str(), nullptr) > 1) == (r > 1));  // a fail reads as over
  }
}

TEST_CASE("an item judged against a typical value is flagged; a max is not") {
  const DataSheet sheet = parse_data_sheet(test::made_up_sheet("T-3", R"(gyro:
  angle_random_walk:
    typ: 0.2 °/√h
    source: ds
    page: 1
  bias_instability:
    max: 3 °/h
    source: ds
    page: 1
)"),
                                           "t3.yaml");
  constexpr double kArw = 0.2 * std::numbers::pi / 180.0 / 60.0;  // 0.2 deg/sqrt(h) in SI
  MeasuredParameter white{.sensor = Sensor::gyro, .quantity = MeasuredQuantity::white_noise,
                          .axis = "x", .value = kArw, .ci_low = kArw, .ci_high = kArw};
  MeasuredParameter bias{.sensor = Sensor::gyro, .quantity = MeasuredQuantity::bias_instability,
                         .axis = "x", .value = 1e-6, .ci_low = 1e-6, .ci_high = 1e-6};
  const auto both = check_compliance({white, bias}, sheet);
  REQUIRE(both.size() == 2);
  CHECK(both[0].limit_is_typical);
  CHECK_FALSE(both[1].limit_is_typical);
  CHECK(any_typical_limit(both));
  CHECK_FALSE(any_typical_limit(check_compliance({bias}, sheet)));
}

TEST_CASE("the compliance chart shows a second labelled tick when every ratio is near 1") {
  // BMI088: only white-noise rows at 0.8-0.95 of the limit gave an axis with the single label 1.
  CompliancePlot white_only;
  white_only.rows = {{"a", 0.8, 0.78, 0.82, "pass"}, {"b", 0.9, 0.88, 0.95, "pass"}};
  const auto [low, high] = compliance_x_range(white_only);
  CHECK(low <= 0.78 / 1.5);  // the data's margin is kept
  CHECK(high >= 1.5);
  CHECK((low < 0.5 || high > 2));  // 0.5 or 2, the labels nearest 1, is in view
  CHECK(low < 0.5);                 // the data lie below 1: the lower side is nearer
}

TEST_CASE("a PSD spanning less than a decade gets a y range of whole decades") {
  // BMI088 demo gyro: the PSD spanned 1.2e-3 to 4e-3 and only 10^-3 was labelled.
  SpectrumPlot psd;
  psd.curves = {{"gx", "", {1, 10, 100}, {1.2e-3, 2e-3, 4e-3}, {}, {}}};
  psd.lines = {{"level", "", {1, 100}, {2.5e-3, 2.5e-3}, {}, {}}};
  auto [low, high] = decade_y_range(psd);
  // Powers of ten from the same std::pow: 1e-3 and 1e-2 within one rounding step.
  constexpr double kPowRounding = 1e-12;
  CHECK(std::abs(low / 1e-3 - 1) < kPowRounding);
  CHECK(std::abs(high / 1e-2 - 1) < kPowRounding);
  // A constant curve at an exact power of ten still spans a decade; no point gives {0, 0}.
  SpectrumPlot flat;
  flat.curves = {{"gx", "", {1, 10}, {1e-4, 1e-4}, {}, {}}};
  std::tie(low, high) = decade_y_range(flat);
  CHECK(high / low > 9.99);
  SpectrumPlot empty;
  empty.curves = {{"gx", "", {1, 10}, {0, -1}, {}, {}}};
  CHECK(decade_y_range(empty) == std::pair<double, double>{0, 0});
  // A deviation plot takes its bands into account.
  DeviationPlot adev;
  adev.curves = {{"gx", "", {1, 10}, {0.3, 0.2}, {0.25, 0.15}, {0.35, 0.31}}};
  std::tie(low, high) = decade_y_range(adev);
  CHECK(std::abs(low / 0.1 - 1) < kPowRounding);
  CHECK(std::abs(high / 1.0 - 1) < kPowRounding);
}

TEST_CASE("the rendered PSD plot of a single decade labels its ends and its 2 and 5 steps") {
  if (!gnuplot_available()) {
    MESSAGE("gnuplot not found: rendered-plot check skipped");
    return;
  }
  SpectrumPlot psd;
  psd.title = "PSD";
  psd.y_label = "PSD";
  psd.curves = {{"gx", "", {1, 10, 100}, {1.2e-3, 2e-3, 4e-3}, {}, {}}};
  const auto file = std::filesystem::temp_directory_path() /
                    ("sigmatau_psd_ticks_" + std::to_string(::getpid()) + ".svg");
  render_spectrum_plot(psd, file, true);
  std::ifstream in(file);
  const std::string svg((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // Enhanced text writes 10^{-3} as "10" then a raised "-3": both ends are labelled, and the
  // steps between them (psd.gp) so a value can be read off.
  CHECK(svg.find(">-3<") != std::string::npos);
  CHECK(svg.find(">-2<") != std::string::npos);
  CHECK(svg.find(">2×10<") != std::string::npos);
  CHECK(svg.find(">5×10<") != std::string::npos);
  std::filesystem::remove(file);
}
