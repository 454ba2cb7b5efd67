// Compliance verdicts: measured parameters against data-sheet limits (see compliance.hpp).
#include "sigmatau/compliance.hpp"

#include "json_text.hpp"
#include "sigmatau/fit.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace sigmatau {
namespace {

struct Candidate {
  SpecField field;
  double limit_factor;  // limit_si = printed value_si * limit_factor
  std::string rule;
  std::string factor_text = "";  // how the printed value is scaled, for showing the limit used
};

/// Said of a non-orthogonality in every rule: what it is and why it is the one compared.
constexpr const char* kDeltaRule =
    "|delta| = |90 deg - angle between the two sensing axes| (frame-free, from A A^T; ~ "
    "|m_ij + m_ji|; the cross-axis terms m_ij themselves depend on the calibration frame) ";

/// The data-sheet fields a measured quantity is compared with, in order of preference.
std::vector<Candidate> candidates(MeasuredQuantity q, DensityConvention convention) {
  const bool one_sided = convention == DensityConvention::one_sided;
  switch (q) {
    case MeasuredQuantity::white_noise:
      return {{SpecField::random_walk, 1.0, "measured N against the printed random walk (ARW/VRW)"},
              {SpecField::noise_density, white_from_noise_density(1.0, convention),
               one_sided ? "measured N against printed noise density / sqrt(2) (one-sided convention)"
                         : "measured N against printed noise density (two-sided convention: N = ND)",
               one_sided ? "/√2" : ""}};
    case MeasuredQuantity::bias_instability:
      return {{SpecField::bias_instability, 1.0,
               "ADEV floor 0.664 B against the printed in-run bias stability"}};
    case MeasuredQuantity::rate_random_walk:
      return {{SpecField::rate_random_walk, 1.0, "measured K against the printed rate random walk"}};
    case MeasuredQuantity::bias:
      return {{SpecField::initial_bias, 1.0, "|b| against the printed initial bias / zero offset"}};
    case MeasuredQuantity::scale_factor_error:
      return {{SpecField::sensitivity_error, 1.0, "|s| against the printed sensitivity tolerance"}};
    case MeasuredQuantity::cross_axis:
      return {{SpecField::cross_axis_sensitivity, 1.0, "|m| against the printed cross-axis sensitivity"},
              {SpecField::misalignment, 1.0,
               "|m| against the printed misalignment angle (small-angle: rad = ratio)"}};
    case MeasuredQuantity::non_orthogonality:
      // A printed "axis-to-axis" misalignment is delta itself: see axis_to_axis() below.
      return {{SpecField::misalignment, 2.0,
               std::string(kDeltaRule) +
                   "against 2 x the printed misalignment c (read as each axis against the package, "
               "which keeps a pair within 2c of 90 deg; the tilt against the package is not "
               "measured)",
               "×2"},
              {SpecField::cross_axis_sensitivity, 2.0,
               std::string(kDeltaRule) +
                   "against 2 x the printed cross-axis sensitivity c (each axis within c of its "
               "package axis keeps a pair within 2c of 90 deg; small angles: rad = ratio; the "
               "tilt against the package is not measured)",
               "×2"}};
    case MeasuredQuantity::bias_temperature_coefficient:
      return {{SpecField::bias_temperature_coefficient, 1.0,
               "|db/dT| against the printed bias temperature coefficient"}};
    case MeasuredQuantity::frame_rotation:
      return {};  // informational: no data sheet prints it
  }
  return {};
}

/// A printed misalignment between the axes of a triad (rather than against the package) bounds
/// the non-orthogonality itself.
Candidate axis_to_axis(const Candidate& c, const SpecValue& value) {
  std::string condition = value.condition;
  for (char& ch : condition) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (condition.find("axis-to-axis") == std::string::npos &&
      condition.find("axis to axis") == std::string::npos) {
    return c;
  }
  return {c.field, 1.0, std::string(kDeltaRule) + "against the printed axis-to-axis misalignment",
          ""};
}

/// The interval's lower bound as compared with the limit (see ComplianceItem::compared_low).
double lower_as_compared(const MeasuredParameter& p) {
  if (!p.detected) return std::numeric_limits<double>::quiet_NaN();
  if (p.quantity == MeasuredQuantity::bias_instability) return kFlickerFloorFactor * p.ci_low;
  if (compared_by_magnitude(p.quantity)) {
    if (p.ci_low <= 0 && p.ci_high >= 0) return 0;  // the interval holds 0
    return std::min(std::abs(p.ci_low), std::abs(p.ci_high));
  }
  return p.ci_low;
}

/// The estimate and its upper bound as compared with the limit. A term not detected has no
/// estimate (NaN) and its one-sided upper bound in place of the interval's upper end.
std::pair<double, double> as_compared(const MeasuredParameter& p) {
  if (!p.detected) {
    const double bound = std::abs(p.upper_bound);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (p.quantity == MeasuredQuantity::bias_instability) return {nan, kFlickerFloorFactor * bound};
    return {nan, bound};
  }
  switch (p.quantity) {
    case MeasuredQuantity::bias_instability:
      return {kFlickerFloorFactor * p.value, kFlickerFloorFactor * p.ci_high};
    case MeasuredQuantity::bias:
    case MeasuredQuantity::scale_factor_error:
    case MeasuredQuantity::cross_axis:
    case MeasuredQuantity::non_orthogonality:
    case MeasuredQuantity::bias_temperature_coefficient:
      return {std::abs(p.value), std::max(std::abs(p.ci_low), std::abs(p.ci_high))};
    default:
      return {p.value, p.ci_high};
  }
}

std::string_view field_key(Sensor sensor, SpecField field) {
  const SpecFieldInfo* info = spec_field_info(sensor, field);
  return info ? info->key : std::string_view("?");
}

}  // namespace

std::string_view to_string(MeasuredQuantity quantity) {
  switch (quantity) {
    case MeasuredQuantity::white_noise: return "white_noise";
    case MeasuredQuantity::bias_instability: return "bias_instability";
    case MeasuredQuantity::rate_random_walk: return "rate_random_walk";
    case MeasuredQuantity::bias: return "bias";
    case MeasuredQuantity::scale_factor_error: return "scale_factor_error";
    case MeasuredQuantity::cross_axis: return "cross_axis";
    case MeasuredQuantity::bias_temperature_coefficient: return "bias_temperature_coefficient";
    case MeasuredQuantity::non_orthogonality: return "non_orthogonality";
    case MeasuredQuantity::frame_rotation: return "frame_rotation";
  }
  return "?";
}

bool compared_by_magnitude(MeasuredQuantity quantity) {
  switch (quantity) {
    case MeasuredQuantity::bias:
    case MeasuredQuantity::scale_factor_error:
    case MeasuredQuantity::cross_axis:
    case MeasuredQuantity::non_orthogonality:
    case MeasuredQuantity::bias_temperature_coefficient:
      return true;
    default:
      return false;
  }
}

std::string_view to_string(Verdict verdict) {
  switch (verdict) {
    case Verdict::pass: return "pass";
    case Verdict::marginal: return "marginal";
    case Verdict::fail: return "fail";
    case Verdict::inconclusive: return "inconclusive";
    case Verdict::not_specified: return "not specified";
  }
  return "?";
}

std::vector<ComplianceItem> check_compliance(const std::vector<MeasuredParameter>& measured,
                                             const DataSheet& sheet,
                                             const ComplianceOptions& options) {
  std::vector<ComplianceItem> items;
  for (const auto& p : measured) {
    const SensorSheet* section = sheet.sensor(p.sensor);
    bool found = false;
    if (section) {
      for (const auto& listed : candidates(p.quantity, options.convention)) {
        const SpecValue* entry = section->find(listed.field);
        if (!entry) continue;
        const SpecValue axis_entry = entry->for_axis(p.axis);  // a value printed for this axis
        const SpecValue* value = &axis_entry;
        if (!value->limit()) continue;
        const Candidate candidate = p.quantity == MeasuredQuantity::non_orthogonality
                                        ? axis_to_axis(listed, *value)
                                        : listed;
        const PrintedValue& limit = *value->limit();
        ComplianceItem item;
        item.measured = p;
        item.spec_field = std::string(field_key(p.sensor, candidate.field));
        item.limit_text = limit.text;
        item.limit_unit = limit.unit;
        item.limit_is_typical = value->limit_is_typical();
        item.limit_si = std::abs(limit.value_si) * candidate.limit_factor;
        item.limit_factor = candidate.limit_factor;
        item.limit_factor_text = candidate.factor_text;
        std::tie(item.compared, item.compared_upper) = as_compared(p);
        item.compared_low = lower_as_compared(p);
        item.rule = candidate.rule;
        if (item.limit_is_typical) item.rule += " (no max printed: typical value used)";
        if (!(item.limit_si > 0)) continue;  // a zero limit cannot be a ratio
        item.margin = item.compared / item.limit_si;
        item.margin_upper = item.compared_upper / item.limit_si;
        item.margin_low = item.compared_low / item.limit_si;
        if (!p.detected) {
          // Only a bound: within the limit it shows the term is small enough; beyond it the log
          // cannot tell (a longer one would), which is not evidence of a failure. A NaN bound
          // is inconclusive too.
          item.rule += "; not detected by the fit: its one-sided upper bound against the limit";
          item.verdict = item.compared_upper <= item.limit_si ? Verdict::pass : Verdict::inconclusive;
        } else if (!(item.compared <= item.limit_si)) {
          item.verdict = Verdict::fail;  // NaN estimates fail too
        } else if (item.compared_upper <= item.limit_si) {
          item.verdict = Verdict::pass;
        } else {
          item.verdict = Verdict::marginal;
        }
        items.push_back(std::move(item));
        found = true;
        break;  // the preferred field decides; a sheet printing both ARW and ND uses ARW
      }
    }
    // A term neither printed on the sheet nor detected in the log says nothing: no row.
    if (!found && p.detected) {
      ComplianceItem item;
      item.measured = p;
      item.verdict = Verdict::not_specified;
      std::tie(item.compared, item.compared_upper) = as_compared(p);
      item.compared_low = lower_as_compared(p);
      if (p.quantity == MeasuredQuantity::frame_rotation) {
        item.rule =
            "informational: rotation vector carrying the accelerometer triad's axes onto the "
            "gyro triad's (nearest rotations to each A), in the accelerometer frame; no data "
            "sheet prints it";
      }
      items.push_back(std::move(item));
    }
  }
  return items;
}

bool fit_rejected(const MeasuredParameter& p) { return p.fit_p_value < kMisfitPValue; }

bool fail_within_uncertainty(const ComplianceItem& item) {
  return item.verdict == Verdict::fail && item.measured.detected &&
         item.compared_low <= item.limit_si;
}

bool any_failed(const std::vector<ComplianceItem>& items) {
  return std::any_of(items.begin(), items.end(),
                     [](const ComplianceItem& i) { return i.verdict == Verdict::fail; });
}

int items_checked(const std::vector<ComplianceItem>& items) {
  return static_cast<int>(std::count_if(items.begin(), items.end(), [](const ComplianceItem& i) {
    return i.verdict != Verdict::not_specified;
  }));
}

std::string overall_verdict(const std::vector<ComplianceItem>& items) {
  int pass = 0, marginal = 0, fail = 0, inconclusive = 0;
  for (const auto& item : items) {
    pass += item.verdict == Verdict::pass;
    marginal += item.verdict == Verdict::marginal;
    fail += item.verdict == Verdict::fail;
    inconclusive += item.verdict == Verdict::inconclusive;
  }
  if (fail > 0) return "fail";
  if (marginal > 0) return "marginal";
  if (inconclusive > 0) return "inconclusive";
  return pass > 0 ? "all pass" : "nothing to check";
}

std::string compliance_json(const std::vector<ComplianceItem>& items, const DataSheet& sheet,
                            const ComplianceOptions& options) {
  nlohmann::json list = nlohmann::json::array();
  for (const auto& item : items) {
    nlohmann::json j = {{"sensor", std::string(to_string(item.measured.sensor))},
                        {"quantity", std::string(to_string(item.measured.quantity))},
                        {"axis", item.measured.axis},
                        {"detected", item.measured.detected}};
    // The measured side as a fit result gives it: an interval, or only an upper bound.
    if (item.measured.detected) {
      j["value"] = item.measured.value;
      j["ci_low"] = item.measured.ci_low;
      j["ci_high"] = item.measured.ci_high;
    } else {
      j["upper_bound"] = item.measured.upper_bound;
    }
    j["verdict"] = std::string(to_string(item.verdict));
    if (item.measured.from_curve_readings) j["from_curve_readings"] = true;
    if (std::isfinite(item.measured.fit_p_value)) {
      j["fit_p_value"] = item.measured.fit_p_value;
      j["fit_rejected"] = fit_rejected(item.measured);
    }
    if (item.verdict != Verdict::not_specified) {
      j["spec_field"] = item.spec_field;
      j["limit_text"] = item.limit_text;
      j["limit_unit"] = item.limit_unit;
      j["limit_is_typical"] = item.limit_is_typical;
      j["limit_si"] = item.limit_si;
      if (item.measured.detected) j["compared"] = item.compared;
      j["compared_upper"] = item.compared_upper;
      if (item.measured.detected) {
        j["margin"] = item.margin;
        j["compared_low"] = item.compared_low;
        j["margin_low"] = item.margin_low;
        j["within_uncertainty"] = fail_within_uncertainty(item);
      }
      j["margin_upper"] = item.margin_upper;
      j["limit_factor"] = item.limit_factor;
      if (!item.limit_factor_text.empty()) j["limit_factor_text"] = item.limit_factor_text;
      j["rule"] = item.rule;
    } else if (!item.rule.empty()) {
      j["rule"] = item.rule;
    }
    list.push_back(j);
  }
  const nlohmann::json doc = {
      {"spec", {{"name", sheet.name}, {"part", sheet.part}, {"manufacturer", sheet.manufacturer}}},
      {"density_convention", std::string(to_string(options.convention))},
      {"verdict", overall_verdict(items)},
      {"failed", any_failed(items)},
      {"items", list}};
  return detail::json_text(doc, 1);
}

}  // namespace sigmatau
