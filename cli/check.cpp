// `sigmatau check --spec SHEET RESULT.json`: pass / marginal / fail against a data sheet, and
// inconclusive for a term the fit did not detect whose upper bound exceeds the limit.
// Exit status 0 when nothing failed, 1 when any check failed (so it can gate a production line);
// an inconclusive item is not a failure; 2 on bad input, including a sheet that prints none of
// the measured items (nothing was checked, so no pass can be given).
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <sstream>

#include "json_text.hpp"
#include "sigmatau/compliance.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/output_file.hpp"
#include "sigmatau/resources.hpp"
#include "sigmatau/units.hpp"
#include "text_columns.hpp"
#include "verbs.hpp"

namespace sigmatau::cli {
namespace {

struct CheckArguments {
  std::string spec;
  std::string result;
  std::string convention = "two-sided";
  std::string format = "table";
  std::string output;
  bool force = false;
};

/// A value in `unit` when it converts, else in SI; `sign` false prints |value| (as compared).
std::string in_unit(double value_si, const std::string& unit, bool sign = true) {
  char buffer[64];
  if (!unit.empty()) {
    try {
      const Unit u = parse_unit(unit);
      std::snprintf(buffer, sizeof buffer, sign ? "%+.4g %s" : "%.4g %s", value_si / u.factor,
                    unit.c_str());
      return buffer;
    } catch (const Error&) {
    }
  }
  std::snprintf(buffer, sizeof buffer, sign ? "%+.4g SI" : "%.4g SI", value_si);
  return buffer;
}

/// The unit a value the sheet does not print is shown in (the usual data-sheet one).
std::string display_unit(const MeasuredParameter& p) {
  const bool gyro = p.sensor == Sensor::gyro;
  switch (p.quantity) {
    case MeasuredQuantity::white_noise: return gyro ? "°/√h" : "m/s/√h";
    case MeasuredQuantity::bias_instability: return gyro ? "°/h" : "mg";
    case MeasuredQuantity::rate_random_walk: return gyro ? "°/h/√h" : "m/s/h/√h";
    case MeasuredQuantity::bias: return gyro ? "°/h" : "mg";
    case MeasuredQuantity::scale_factor_error: return "ppm";
    case MeasuredQuantity::bias_temperature_coefficient: return gyro ? "°/h/K" : "mg/K";
    case MeasuredQuantity::cross_axis:
    case MeasuredQuantity::non_orthogonality:
    case MeasuredQuantity::frame_rotation: return "mrad";
  }
  return "";
}

/// The measured estimate as shown: signed, and inside |...| when the magnitude is what is
/// compared (a negative bias stays visibly negative; the margin is of |b|).
std::string measured_cell(const ComplianceItem& item, const std::string& unit) {
  const MeasuredParameter& p = item.measured;
  if (!p.detected) return "not detected";
  if (compared_by_magnitude(p.quantity)) return "|" + in_unit(p.value, unit) + "|";
  // B is compared as its ADEV floor, the figure the sheet prints: shown so, labelled.
  if (p.quantity == MeasuredQuantity::bias_instability) {
    return "0.664 B = " + in_unit(item.compared, unit, false);
  }
  return in_unit(item.compared, unit, false);
}

/// The interval as compared, "[low, high]" in the unit of the measured cell; for a term not
/// detected its one-sided bound ("< 1.044 °/h", "0.664 B < 1.044 °/h").
std::string interval_cell(const ComplianceItem& item, const std::string& unit) {
  if (!item.measured.detected) {
    return std::string(item.measured.quantity == MeasuredQuantity::bias_instability ? "0.664 B " : "") +
           "< " + in_unit(item.compared_upper, unit, false);
  }
  std::string low = in_unit(item.compared_low, unit, false);
  std::string high = in_unit(item.compared_upper, unit, false);
  low = low.substr(0, low.find(' '));  // the unit once, after the upper end
  return "[" + low + ", " + high + "]";
}

/// measured / limit with its interval: "[0.998, 1.002]".
std::string ratio_interval(const ComplianceItem& item) {
  if (!item.measured.detected) return "< " + format_ratio(item.margin_upper);
  return "[" + format_ratio(item.margin_low) + ", " + format_ratio(item.margin_upper) + "]";
}

/// The limit actually compared with, and the printed value when it was scaled (one-sided
/// density: printed / √2; per-axis misalignment against a pair: 2 × printed).
std::string limit_cell(const ComplianceItem& item) {
  std::string cell = item.limit_factor_text.empty()
                         ? item.limit_text
                         : in_unit(item.limit_si, item.limit_unit, false) + " (" +
                               item.limit_text + " " + item.limit_factor_text + ")";
  return cell + (item.limit_is_typical ? " (typ)" : " (max)");
}

std::string label(const ComplianceItem& item) {
  return std::string(to_string(item.measured.sensor)) + " " +
         std::string(to_string(item.measured.quantity)) + " " + item.measured.axis;
}

/// measured / limit as shown: never "1" for a ratio that is not 1 (format_ratio).
std::string ratio(double value) { return format_ratio(value); }

/// One table row; `cells` are parameter, verdict, measured, interval, limit, margin, margin
/// interval, note.
std::string row(const std::vector<std::string>& cells) {
  static const std::size_t kWidths[] = {36, 13, 24, 28, 40, 8, 18, 0};
  std::string line;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    if (i > 0) line += ' ';
    line += pad(cells[i], kWidths[i], i == 5);
  }
  while (!line.empty() && line.back() == ' ') line.pop_back();
  return line + "\n";
}

std::string table(const std::vector<ComplianceItem>& items, const DataSheet& sheet,
                  const std::string& result, double confidence) {
  std::ostringstream out;
  out << "# " << sheet.manufacturer << " " << sheet.part << " (" << sheet.name << ") against "
      << result << "; pass: upper bound within the limit, marginal: estimate within but "
      << "bound not, fail: estimate beyond, inconclusive: not detected and its upper bound "
      << "beyond (a longer log is needed); |x|: compared by magnitude; bias instability as its "
      << "ADEV floor 0.664 B, the figure sheets print\n";
  // How strong a pass on a noise term is (fit's default intervals are 68.3 %); a calibration's
  // terms have their own default level and are always detected.
  const bool noise_terms = std::any_of(items.begin(), items.end(), [](const ComplianceItem& i) {
    return i.measured.quantity == MeasuredQuantity::white_noise ||
           i.measured.quantity == MeasuredQuantity::bias_instability ||
           i.measured.quantity == MeasuredQuantity::rate_random_walk;
  });
  if (const std::string note = gate_confidence_note(confidence); noise_terms && !note.empty()) {
    out << "# " << note << "\n";
  }
  out << row({"parameter", "verdict", "measured", "interval", "limit", "margin", "margin interval",
              "note"});
  std::vector<const ComplianceItem*> informational;
  for (const auto& item : items) {
    if (item.measured.quantity == MeasuredQuantity::frame_rotation) {
      informational.push_back(&item);
      continue;
    }
    const std::string verdict(to_string(item.verdict));
    if (item.verdict == Verdict::not_specified) {
      out << row({label(item), verdict, measured_cell(item, display_unit(item.measured))});
    } else {
      // A term not detected has only a bound: no estimate and no estimate margin ("-").
      const std::string note =
          verdict_qualifiers(fail_within_uncertainty(item), item.measured.fit_p_value,
                             item.measured.from_curve_readings);
      out << row({label(item), verdict, measured_cell(item, item.limit_unit),
                  interval_cell(item, item.limit_unit), limit_cell(item),
                  item.measured.detected ? ratio(item.margin) : "-", ratio_interval(item), note});
    }
  }
  if (!informational.empty()) {
    out << "# gyro-to-accelerometer rotation (informational, not a verdict: no data sheet prints "
           "it): rotation vector carrying the accelerometer axes onto the gyro axes, in the "
           "accelerometer frame, with its interval\n";
    for (const ComplianceItem* item : informational) {
      const MeasuredParameter& p = item->measured;
      out << row({label(*item), "info", in_unit(p.value, "mrad"),
                  "[" + in_unit(p.ci_low, "mrad") + ", " + in_unit(p.ci_high, "mrad") + "]"});
    }
  }
  const int checked = items_checked(items);
  const int unspecified = static_cast<int>(items.size() - informational.size()) - checked;
  int inconclusive = 0;
  for (const auto& item : items) inconclusive += item.verdict == Verdict::inconclusive;
  const std::string counted = std::to_string(checked) + " of " +
                              std::to_string(checked + unspecified) + " items checked";
  // Beside the verdict (RESULT stays the last line): a typ limit is not a guarantee; what the
  // notes mean when a row has one.
  if (std::any_of(items.begin(), items.end(), fail_within_uncertainty)) {
    out << "# note: " << kWithinUncertaintyNote << "\n";
  }
  if (std::any_of(items.begin(), items.end(),
                  [](const ComplianceItem& i) { return fit_rejected(i.measured); })) {
    out << "# note: " << kFitRejectedNote << "\n";
  }
  if (std::any_of(items.begin(), items.end(),
                  [](const ComplianceItem& i) { return i.measured.from_curve_readings; })) {
    out << "# note: " << kCurveReadingNote << "\n";
  }
  if (any_typical_limit(items)) out << "# note: " << kTypicalLimitNote << "\n";
  if (any_failed(items)) {
    out << "RESULT: FAIL (" << counted << ")\n";
  } else if (inconclusive > 0) {
    out << "RESULT: no check failed (" << counted << "); " << inconclusive
        << " inconclusive (terms not detected whose upper bound exceeds the limit: a longer log "
           "is needed to decide them)\n";
  } else {
    out << "RESULT: no check failed (" << counted << ")\n";
  }
  return out.str();
}

void run_check(const CheckArguments& args) {
  if (args.format != "table" && args.format != "json") {
    throw Error("--format must be table or json, got \"" + args.format + "\"");
  }
  if (!args.output.empty()) check_can_write(args.output, args.force);
  const DataSheet sheet = load_data_sheet(find_data_sheet(args.spec, resource_dir("specs")));
  const std::string result_text = read_text_file(args.result);
  const auto measured = measured_parameters_from_json(result_text, args.result);
  // The intervals' level, as fit and analyze write it (68.3 % when absent).
  double confidence = 0.683;
  if (const auto doc = nlohmann::json::parse(result_text, nullptr, false);
      doc.is_object() && doc.contains("confidence") && doc["confidence"].is_number()) {
    confidence = doc["confidence"].get<double>();
  }
  ComplianceOptions options;
  options.convention = parse_density_convention(args.convention);
  const auto items = check_compliance(measured, sheet, options);
  if (items_checked(items) == 0) {
    // A pass with zero checks would let any part through a production gate: this is an input
    // that cannot give a verdict (the wrong sheet for this result, or the wrong result).
    throw Error("nothing to check: " + sheet.name + " (" + sheet.part + ") prints none of the " +
                std::to_string(measured.size()) + " items measured in " + args.result +
                " (use the sheet of this part, or a result that measures what the sheet prints)");
  }

  std::ostringstream out;
  if (args.format == "json") {
    nlohmann::json doc = nlohmann::json::parse(compliance_json(items, sheet, options));
    doc["tool"] = "sigmatau";
    doc["version"] = SIGMATAU_VERSION;
    out << json_text(doc, 1) << "\n";
  } else {
    out << table(items, sheet, args.result, confidence);
  }
  if (args.output.empty()) {
    std::cout << out.str();
  } else {
    write_file_atomically(args.output, out.str(), args.force);
  }
  if (any_failed(items)) throw ExitStatus{1};
}

}  // namespace

void add_check_command(CLI::App& app) {
  auto args = std::make_shared<CheckArguments>();
  CLI::App* command = app.add_subcommand(
      "check", "Compare measured parameters (fit, calibrate or analyze result) with a data sheet: "
               "pass / marginal / fail (inconclusive: a term not detected whose upper bound "
               "exceeds the limit); exit 1 when any check fails, 2 when the sheet prints "
               "none of the measured items");
  command->add_option("--spec", args->spec, "data sheet: a YAML file or a name from `sigmatau specs list`")
      ->required();
  command->add_option("RESULT", args->result, "a sigmatau fit / calibrate / analyze JSON result")
      ->required();
  command->add_option("--density-convention", args->convention,
                      "how a printed noise density is read: two-sided (N = ND) or one-sided "
                      "(N = ND/sqrt(2))")
      ->capture_default_str();
  command->add_option("--format", args->format, "table | json")->capture_default_str();
  command->add_option("-o,--output", args->output, "write to FILE (atomically) instead of stdout");
  command->add_flag("--force", args->force, "overwrite an existing output file");
  command->callback([args] { run_check(*args); });
}

}  // namespace sigmatau::cli
