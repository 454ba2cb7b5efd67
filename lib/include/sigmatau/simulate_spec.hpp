#pragma once
/// \file simulate_spec.hpp
/// The noise terms `simulate --spec` takes from a data sheet, with what the sheet leaves out.
///
/// A sheet prints some of the terms the simulator knows (white noise as a random walk or a noise
/// density, bias instability, rate random walk) and not others. A term the sheet does not print
/// would be simulated as zero, so the caller is told: a sensor with no noise term at all is an
/// Error (its log would be noise-free or constant), and the terms left out are listed so that a
/// sensor simulated without white noise can be warned about and recorded in the sidecar.

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "sigmatau/convert.hpp"
#include "sigmatau/noise_model.hpp"
#include "sigmatau/spec.hpp"

namespace sigmatau {

/// One sensor's noise as a data sheet gives it to the simulator.
struct SheetNoise {
  std::array<NoiseTerms, 3> axes;  ///< the same terms on x, y, z [SI, as NoiseTerms]
  /// How each simulated term was read, e.g. "noise density 2.8 mdps/√Hz (typ) read as N = ND
  /// (two-sided)"; one entry per term taken from the sheet.
  std::vector<std::string> read;
  /// The terms the sheet does not print, simulated as zero, e.g. "white noise (no angle random
  /// walk or noise density)"; a printed RMS noise that gives no density is named here too.
  std::vector<std::string> left_out;
  bool has_white = false;  ///< the sheet gives white noise (the term most logs are made of)
};

/// The nominal (typ, else max) noise terms of `sensor` on `sheet` (triad_from_data_sheet, with
/// the density `convention`) and the terms it leaves out. Throws Error naming the sheet, the
/// sensor and the options that give the terms (--model / --accel-model) when the sheet has no
/// section for the sensor or prints none of its noise terms.
SheetNoise simulation_noise_from_data_sheet(const DataSheet& sheet, Sensor sensor,
                                            DensityConvention convention);

/// What `sheet` lacks for `sensor` to be simulated with any noise, as a phrase that follows the
/// sheet's name: "has no accel section", or "prints no accel noise term (no velocity random
/// walk, noise density, bias instability or rate random walk)" (a printed RMS noise is named as
/// giving no density). Empty when the sheet gives the sensor at least one noise term, i.e. when
/// simulation_noise_from_data_sheet does not throw. For callers that leave such a sensor out
/// (the demo) instead of refusing it.
std::string sheet_noise_gap(const DataSheet& sheet, Sensor sensor, DensityConvention convention);

/// Throws Error "--scale must be a number > 0 ..." unless `scale` (a fraction of the sheet's
/// values, dimensionless) is finite and > 0. The check of `simulate --scale` and `demo --scale`.
void check_sheet_noise_scale(double scale);

/// Every noise term of `noise` on every axis (Q, N, B, K, R: those a sheet can give) times
/// `scale`: a unit `scale` times as noisy as the sheet's nominal one, e.g. 0.8 for one a little
/// better than nominal. `read` and `left_out` are kept (they say what the sheet prints); the
/// sidecar records the factor through sheet_noise_origin. Throws as check_sheet_noise_scale.
void scale_sheet_noise(SheetNoise& noise, double scale);

/// The sidecar's noise_source origin of terms taken from `sheet`: "data sheet NAME", and with a
/// `scale`, "data sheet NAME, each term x 0.8" (the factor as %g).
std::string sheet_noise_origin(const DataSheet& sheet, std::optional<double> scale);

/// One line for stderr when `noise` has no white noise: names the sheet, the sensor, every term
/// left out and the option that supplies them; empty when white noise is given.
std::string sheet_noise_warning(const DataSheet& sheet, Sensor sensor, const SheetNoise& noise);

}  // namespace sigmatau
