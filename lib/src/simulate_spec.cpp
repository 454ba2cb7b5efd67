// The noise terms `simulate --spec` takes from a data sheet and the terms the sheet leaves out.

#include "sigmatau/simulate_spec.hpp"

#include <cmath>
#include <cstdio>

#include "sigmatau/error.hpp"

namespace sigmatau {
namespace {

std::string sensor_name(Sensor sensor) { return std::string(to_string(sensor)); }

/// The option that gives a sensor's terms by hand.
std::string model_option(Sensor sensor) {
  return sensor == Sensor::gyro ? "--model" : "--accel-model";
}

std::string model_example(Sensor sensor) {
  return sensor == Sensor::gyro ? "\"N=0.15 deg/sqrt(h), B=3 deg/h\""
                                : "\"N=60 ug/sqrt(Hz), B=0.05 mg\"";
}

/// Splits "a; b" as triad_from_data_sheet joins its bias origins.
void append_parts(std::vector<std::string>& out, const std::string& text) {
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = std::min(text.find("; ", start), text.size());
    if (end > start) out.push_back(text.substr(start, end - start));
    start = end + 2;
  }
}

std::string join(const std::vector<std::string>& items, const std::string& separator) {
  std::string s;
  for (const auto& item : items) s += (s.empty() ? "" : separator) + item;
  return s;
}

/// "angle random walk" / "velocity random walk".
std::string random_walk_name(Sensor sensor) {
  return sensor == Sensor::gyro ? "angle random walk" : "velocity random walk";
}

/// "; its RMS noise 1.8 mg (typ) is a total over the output band, not a density" when the
/// section prints one, else "". A printed RMS noise is a total over the output band: without
/// the band's noise bandwidth it gives no density, so it is named, not used.
std::string rms_remark(const SensorSheet& section) {
  if (const SpecValue* rms = section.find(SpecField::rms_noise); rms && rms->nominal())
    return "; its RMS noise " + rms->nominal()->text +
           " is a total over the output band, not a density";
  return {};
}

}  // namespace

std::string sheet_noise_gap(const DataSheet& sheet, Sensor sensor, DensityConvention convention) {
  const std::string what = sensor_name(sensor);
  const SensorSheet* section = sheet.sensor(sensor);
  if (!section) return "has no " + what + " section";
  const NoiseTerms t = triad_from_data_sheet(sheet, sensor, convention).axes[0];
  if (t.white || t.bias_instability || t.rate_random_walk) return {};
  return "prints no " + what + " noise term (no " + random_walk_name(sensor) +
         ", noise density, bias instability or rate random walk" + rms_remark(*section) + ")";
}

SheetNoise simulation_noise_from_data_sheet(const DataSheet& sheet, Sensor sensor,
                                            DensityConvention convention) {
  const std::string what = sensor_name(sensor);
  if (const std::string gap = sheet_noise_gap(sheet, sensor, convention); !gap.empty())
    throw Error(
        sheet.label() + " " + gap + ", so " + (sheet.sensor(sensor) ? "the " : "its ") + what +
        " would be simulated without noise; give the " + what + " terms with " +
        model_option(sensor) + ", e.g. " + model_example(sensor) + " (it replaces the sheet's " +
        what + " terms), or leave " + what + " out of --sensors");
  const TriadNoise triad = triad_from_data_sheet(sheet, sensor, convention);
  SheetNoise out;
  out.axes = triad.axes;
  const NoiseTerms& t = triad.axes[0];
  out.has_white = t.white.has_value();
  if (t.white) out.read.push_back(triad.white_origin);
  append_parts(out.read, triad.bias_origin);
  if (!t.white)
    out.left_out.push_back("white noise (no " + random_walk_name(sensor) + " or noise density" +
                           rms_remark(*sheet.sensor(sensor)) + ")");
  if (!t.bias_instability) out.left_out.push_back("bias instability");
  if (!t.rate_random_walk) out.left_out.push_back("rate random walk");
  return out;
}

void check_sheet_noise_scale(double scale) {
  if (std::isfinite(scale) && scale > 0) return;
  char text[48];
  std::snprintf(text, sizeof text, "%g", scale);
  throw Error(std::string("--scale must be a number > 0 (the simulated noise terms as a fraction "
                          "of the sheet's values, e.g. 0.8), got ") + text);
}

void scale_sheet_noise(SheetNoise& noise, double scale) {
  check_sheet_noise_scale(scale);
  for (NoiseTerms& axis : noise.axes) {
    for (std::optional<double>* term : {&axis.quantization, &axis.white, &axis.bias_instability,
                                        &axis.rate_random_walk, &axis.rate_ramp}) {
      if (*term) **term *= scale;
    }
  }
}

std::string sheet_noise_origin(const DataSheet& sheet, std::optional<double> scale) {
  std::string origin = "data sheet " + sheet.name;
  if (scale) {
    char text[48];
    std::snprintf(text, sizeof text, "%g", *scale);
    origin += std::string(", each term x ") + text;
  }
  return origin;
}

std::string sheet_noise_warning(const DataSheet& sheet, Sensor sensor, const SheetNoise& noise) {
  if (noise.has_white) return {};
  const std::string what = sensor_name(sensor);
  return "warning: " + sheet.label() + " prints no white noise for the " + what +
         ", so the " + what + " is simulated with " + join(noise.read, " and ") +
         " only; left out: " + join(noise.left_out, ", ") + " (give " + model_option(sensor) +
         " to supply the " + what + " terms)";
}

}  // namespace sigmatau
