// `simulate --spec --scale` and `demo --scale`: a data sheet's noise terms as a fraction of its
// values, scaled and checked by one function for both verbs (simulate_spec.hpp).
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "sigmatau/error.hpp"
#include "sigmatau/simulate_spec.hpp"

using namespace sigmatau;

namespace {

const std::filesystem::path kSpecsDir = std::filesystem::path(SIGMATAU_SOURCE_DIR) / "specs";

/// Every term a sheet can give (Q, N, B, K, R, distinct values per axis) and a Gauss-Markov
/// term, which no sheet gives.
SheetNoise every_term() {
  SheetNoise noise;
  for (int a = 0; a < 3; ++a) {
    NoiseTerms& t = noise.axes[static_cast<std::size_t>(a)];
    t.quantization = 1e-6 * (a + 1);
    t.white = 4e-5 * (a + 1);
    t.bias_instability = 3e-6 * (a + 1);
    t.rate_random_walk = 2e-7 * (a + 1);
    t.rate_ramp = 1e-9 * (a + 1);
    t.gauss_markov = {GaussMarkov{5e-6, 100.0}};
  }
  noise.read = {"noise density read as N"};
  noise.left_out = {"rate random walk"};
  return noise;
}

}  // namespace

TEST_CASE("scale_sheet_noise multiplies every sheet term on every axis by the factor") {
  const SheetNoise before = every_term();
  SheetNoise after = before;
  const double scale = 0.8;
  scale_sheet_noise(after, scale);
  for (std::size_t a = 0; a < 3; ++a) {
    CAPTURE(a);
    const NoiseTerms& b = before.axes[a];
    const NoiseTerms& s = after.axes[a];
    // One multiplication each: the very product, so exact equality holds.
    CHECK(*s.quantization == *b.quantization * scale);
    CHECK(*s.white == *b.white * scale);
    CHECK(*s.bias_instability == *b.bias_instability * scale);
    CHECK(*s.rate_random_walk == *b.rate_random_walk * scale);
    CHECK(*s.rate_ramp == *b.rate_ramp * scale);
    // Not a sheet term: left as it is.
    CHECK(s.gauss_markov.at(0).sigma == b.gauss_markov.at(0).sigma);
  }
  // What the sheet prints and leaves out does not change with the factor.
  CHECK(after.read == before.read);
  CHECK(after.left_out == before.left_out);
}

TEST_CASE("scale_sheet_noise leaves absent terms absent") {
  SheetNoise noise;
  noise.axes[0].white = 1e-4;
  scale_sheet_noise(noise, 2.0);
  CHECK_FALSE(noise.axes[0].bias_instability.has_value());
  CHECK_FALSE(noise.axes[1].white.has_value());
  CHECK(*noise.axes[0].white == 2e-4);  // 1e-4 x 2: exact (a power of two)
}

TEST_CASE("a scale that is not a finite number > 0 is refused, with the option and the value") {
  for (const double bad : {0.0, -0.8, std::numeric_limits<double>::infinity(),
                           std::numeric_limits<double>::quiet_NaN()}) {
    CAPTURE(bad);
    CHECK_THROWS_AS(check_sheet_noise_scale(bad), Error);
    SheetNoise noise = every_term();
    CHECK_THROWS_WITH_AS(scale_sheet_noise(noise, bad),
                         doctest::Contains("--scale must be a number > 0"), Error);
    CHECK(noise.axes[0].white == every_term().axes[0].white);  // untouched when refused
  }
  CHECK_NOTHROW(check_sheet_noise_scale(1e-3));
  CHECK_NOTHROW(check_sheet_noise_scale(5.0));
}

TEST_CASE("the sidecar's origin names the factor only when one is given") {
  const DataSheet sheet = load_data_sheet(kSpecsDir / "safran_stim300.yaml");
  CHECK(sheet_noise_origin(sheet, std::nullopt) == "data sheet safran_stim300");
  CHECK(sheet_noise_origin(sheet, 0.8) == "data sheet safran_stim300, each term x 0.8");
  CHECK(sheet_noise_origin(sheet, 1.0) == "data sheet safran_stim300, each term x 1");
}
