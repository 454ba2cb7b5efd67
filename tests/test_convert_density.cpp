// A printed noise density ND read as the Allan N under either density convention: the one
// function `convert --noise-density` uses (white_from_noise_density) against THEORY.md T1 and
// against the data-sheet path (triad_from_data_sheet), which must read a sheet's ND alike.
#include <cmath>
#include <numbers>
#include <string>

#include "sigmatau/convert.hpp"
#include "sigmatau/spec.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

constexpr double kDeg = std::numbers::pi / 180;
/// Round-off of a handful of floating-point operations on exact inputs.
constexpr double kRoundOff = 1e-12;

/// A one-gyro sheet printing only a noise density of `nd_text`.
DataSheet sheet_with_density(const std::string& nd_text) {
  return parse_data_sheet("schema: 1\nmanufacturer: T\npart: P\ngrade: consumer\nsources:\n"
                          "  s: {document: D, kind: secondary}\ngyro:\n"
                          "  noise_density: {typ: " + nd_text + ", source: s}\n",
                          "inline.yaml");
}

}  // namespace

TEST_CASE("two-sided N = ND, one-sided N = ND / sqrt(2) (THEORY.md 9 T1)") {
  const double nd = 0.015 * kDeg;  // rad/s/sqrt(Hz)
  CHECK(white_from_noise_density(nd, DensityConvention::two_sided) == nd);
  const double one = white_from_noise_density(nd, DensityConvention::one_sided);
  // T1: the one-sided reading halves the white PSD, N^2 = 0.015^2 / 2 = 1.125e-4 (deg/s)^2/Hz.
  SIGMATAU_CHECK_REL(one * one / (kDeg * kDeg), 1.125e-4, kRoundOff);
  CHECK(noise_density_reading(DensityConvention::two_sided) == "read as N = ND (two-sided)");
  CHECK(noise_density_reading(DensityConvention::one_sided) ==
        "read as one-sided: N = ND / sqrt(2)");
}

TEST_CASE("a data sheet's noise density is read as the typed one is") {
  // `convert --spec` and `convert --noise-density` must give the same N and say the same: the
  // same value through both paths, exactly (the same operations on the same double).
  const DataSheet sheet = sheet_with_density("0.015 deg/s/sqrt(Hz)");
  const double nd = sheet.gyro->find(SpecField::noise_density)->nominal()->value_si;
  for (const DensityConvention c : {DensityConvention::two_sided, DensityConvention::one_sided}) {
    CAPTURE(to_string(c));
    const TriadNoise t = triad_from_data_sheet(sheet, Sensor::gyro, c);
    REQUIRE(t.axes[0].white);
    CHECK(*t.axes[0].white == white_from_noise_density(nd, c));
    const std::string reading(noise_density_reading(c));
    REQUIRE(t.white_origin.size() >= reading.size());
    CHECK(t.white_origin.substr(t.white_origin.size() - reading.size()) == reading);
  }
}
