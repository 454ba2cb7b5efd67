// `sigmatau units`: converts a data-sheet value to another unit, or shows its SI value.
#include "sigmatau/units.hpp"

#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "sigmatau/error.hpp"
#include "text_columns.hpp"
#include "verbs.hpp"

namespace sigmatau::cli {
namespace {

struct UnitsArguments {
  std::vector<std::string> words;  // "0.3 deg/sqrt(h)", or "0.3" "deg/sqrt(h)", or "deg/h"
  std::string to;
  int digits = 10;
  bool list = false;
};

/// True when the text starts (after spaces) with something a number starts with.
bool starts_with_number(const std::string& text) {
  const std::size_t i = text.find_first_not_of(" \t");
  if (i == std::string::npos) return false;
  const char c = text[i];
  return (c >= '0' && c <= '9') || c == '.' || c == '+' || c == '-' ||
         text.compare(i, 3, "\xE2\x88\x92") == 0;  // U+2212 minus sign
}

std::string format_value(double v, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
  return buffer;
}

void print_table() {
  std::cout << pad("symbol", 9) << pad("in SI", 22) << pad("prefixes", 14) << "meaning\n";
  for (const UnitSymbol& s : known_units()) {
    const std::string si = format_value(s.factor, 10) + " " + si_unit_string(s.dimension);
    std::cout << pad(s.name, 9) << pad(si, 22) << pad(s.prefixes.empty() ? "-" : s.prefixes, 14)
              << s.meaning << "\n";
  }
}

void run_units(const UnitsArguments& args) {
  if (args.list) {
    print_table();
    if (args.words.empty()) return;
  }
  if (args.words.empty()) {
    throw Error(
        "units: give a value with its unit, e.g. sigmatau units \"0.3 deg/sqrt(h)\" "
        "--to deg/s/sqrt(Hz) (or --list for the known symbols)");
  }
  if (!(args.digits >= 1 && args.digits <= 17)) throw Error("--digits must be 1..17");
  std::string text;
  for (const auto& w : args.words) text += (text.empty() ? "" : " ") + w;

  double value_si = 0;
  Dimension dimension;
  if (starts_with_number(text)) {
    const Quantity q = parse_quantity(text);
    value_si = q.value_si;
    dimension = q.dimension;
  } else {  // a unit alone means one of it
    const Unit u = parse_unit(text);
    value_si = u.factor + u.offset;
    dimension = u.dimension;
  }

  if (args.to.empty()) {
    std::cout << format_value(value_si, args.digits) << " " << si_unit_string(dimension) << "\n";
    return;
  }
  const Unit to = parse_unit(args.to);
  if (!(to.dimension == dimension)) {
    throw Error("cannot convert " + text + " (" + to_string(dimension) + ") to " + args.to + " (" +
                to_string(to.dimension) + ")");
  }
  std::cout << format_value((value_si - to.offset) / to.factor, args.digits) << " " << args.to
            << "\n";
}

}  // namespace

void add_units_command(CLI::App& app) {
  auto args = std::make_shared<UnitsArguments>();
  CLI::App* command = app.add_subcommand(
      "units",
      "Convert a value between units as data sheets print them, or show its SI value.\n"
      "  sigmatau units \"0.3 deg/sqrt(h)\" --to \"deg/s/sqrt(Hz)\"   ->  0.005 deg/s/sqrt(Hz)\n"
      "  sigmatau units 70 \"ug/sqrt(Hz)\"                        ->  0.0006864655 m/s^1.5 (SI)\n"
      "  sigmatau units deg/h                                    ->  one deg/h in SI\n"
      "Notation: products * · or a space, quotients / (left to right: deg/s/sqrt(Hz)), powers\n"
      "^2 ^-1 ^0.5 ^(1/2) ² ⁻¹ ½, roots sqrt(Hz) √Hz rtHz rt-Hz, parentheses. g is standard\n"
      "gravity 9.80665 m/s^2 (mg = milli-g, never milligram); a lone °C is absolute (25 °C =\n"
      "298.15 K), inside a compound (%/°C) it is a difference; LSB is a raw count. Quote\n"
      "arguments containing ( ) or spaces; put -- before a negative value.");
  command->add_option("QUANTITY", args->words,
                      "a number and a unit, as one argument or two; a unit alone means 1 of it");
  command->add_option("--to", args->to, "unit to convert to (default: SI)");
  command->add_option("--digits", args->digits, "significant digits printed (1..17)")
      ->capture_default_str();
  command->add_flag("--list", args->list,
                    "list the known unit symbols, their SI values and prefixes");
  command->callback([args] { run_units(*args); });
}

}  // namespace sigmatau::cli
