// `sigmatau check --spec SHEET RESULT.json`: pass / marginal / fail against a data sheet, and
// inconclusive for a term the fit did not detect whose upper bound exceeds the limit.
// Exit status 0 when nothing failed, 1 when any check failed (so it can gate a production line);
// an inconclusive item is not a failure.
#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <sstream>

#include "sigmatau/compliance.hpp"
#include "sigmatau/error.hpp"
#include "sigmatau/output_file.hpp"
#include "sigmatau/resources.hpp"
#include "sigmatau/units.hpp"
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

/// A value in the printed unit when it converts, else in SI.
std::string in_printed_unit(double value_si, const std::string& unit) {
  char buffer[64];
  if (!unit.empty()) {
    try {
      const Unit u = parse_unit(unit);
      std::snprintf(buffer, sizeof buffer, "%.4g %s", value_si / u.factor, unit.c_str());
      return buffer;
    } catch (const Error&) {
    }
  }
  std::snprintf(buffer, sizeof buffer, "%.4g SI", value_si);
  return buffer;
}

std::string label(const ComplianceItem& item) {
  return std::string(to_string(item.measured.sensor)) + " " +
         std::string(to_string(item.measured.quantity)) + " " + item.measured.axis;
}

void run_check(const CheckArguments& args) {
  if (args.format != "table" && args.format != "json") {
    throw Error("--format must be table or json, got \"" + args.format + "\"");
  }
  if (!args.output.empty()) check_can_write(args.output, args.force);
  const DataSheet sheet = load_data_sheet(find_data_sheet(args.spec, resource_dir("specs")));
  const auto measured = measured_parameters_from_json(read_text_file(args.result), args.result);
  ComplianceOptions options;
  options.convention = parse_density_convention(args.convention);
  const auto items = check_compliance(measured, sheet, options);

  std::ostringstream out;
  if (args.format == "json") {
    nlohmann::json doc = nlohmann::json::parse(compliance_json(items, sheet, options));
    doc["tool"] = "sigmatau";
    doc["version"] = SIGMATAU_VERSION;
    out << doc.dump(1) << "\n";
  } else {
    out << "# " << sheet.manufacturer << " " << sheet.part << " (" << sheet.name << ") against "
        << args.result << "; pass: upper bound within the limit, marginal: estimate within but "
        << "bound not, fail: estimate beyond, inconclusive: not detected and its upper bound "
        << "beyond (a longer log is needed)\n";
    char line[512];
    std::snprintf(line, sizeof line, "%-36s %-12s %-22s %-22s %-22s %8s %8s\n", "parameter",
                  "verdict", "measured", "upper bound", "limit", "margin", "upper");
    out << line;
    for (const auto& item : items) {
      if (item.verdict == Verdict::not_specified) {
        std::snprintf(line, sizeof line, "%-36s %-12s\n", label(item).c_str(), "not specified");
      } else if (!item.measured.detected) {
        // Only a bound: no estimate and no estimate margin to show.
        std::snprintf(line, sizeof line, "%-36s %-12s %-22s %-22s %-22s %8s %8.3f\n",
                      label(item).c_str(), std::string(to_string(item.verdict)).c_str(),
                      "not detected",
                      ("< " + in_printed_unit(item.compared_upper, item.limit_unit)).c_str(),
                      (item.limit_text + (item.limit_is_typical ? " (typ)" : "")).c_str(), "-",
                      item.margin_upper);
      } else {
        std::snprintf(line, sizeof line, "%-36s %-12s %-22s %-22s %-22s %8.3f %8.3f%s\n",
                      label(item).c_str(), std::string(to_string(item.verdict)).c_str(),
                      in_printed_unit(item.compared, item.limit_unit).c_str(),
                      in_printed_unit(item.compared_upper, item.limit_unit).c_str(),
                      (item.limit_text + (item.limit_is_typical ? " (typ)" : "")).c_str(),
                      item.margin, item.margin_upper, "");
      }
      out << line;
    }
    int inconclusive = 0;
    for (const auto& item : items) inconclusive += item.verdict == Verdict::inconclusive;
    if (any_failed(items)) {
      out << "RESULT: FAIL\n";
    } else if (inconclusive > 0) {
      out << "RESULT: no check failed; " << inconclusive
          << " inconclusive (terms not detected whose upper bound exceeds the limit: a longer log "
             "is needed to decide them)\n";
    } else {
      out << "RESULT: no check failed\n";
    }
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
               "exceeds the limit); exit 1 when any check fails");
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
