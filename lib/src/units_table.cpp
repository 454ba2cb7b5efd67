// Units module, part 2: the symbol table (what each data-sheet symbol means in SI) and its
// look-up with SI prefixes. The grammar that combines symbols is in units.cpp.
#include "units_table.hpp"

#include <array>
#include <numbers>
#include <vector>

namespace sigmatau {
namespace units_detail {
namespace {

constexpr double kDegree = kRadiansPerDegree;       // [rad], exact definition of the degree
constexpr double kMinute = 60;                      // [s]
constexpr double kHour = 3600;                      // [s]
constexpr double kFoot = 0.3048;                    // [m], international foot (1959)
constexpr std::string_view kSmall = "n u µ μ m";    // prefixes of small units
constexpr std::string_view kCelsiusMeaning =
    "degree Celsius (absolute alone, a difference in a compound)";

/// Function-local so that known_units() works during other files' static initialisation.
const std::vector<UnitSymbol>& symbols() {
  static const std::vector<UnitSymbol> table = {
      // angle
      {"rad", 1, dim::angle, kSmall, "radian"},
      {"deg", kDegree, dim::angle, "u µ μ m", "degree"},
      {"degree", kDegree, dim::angle, "", "degree"},
      {"degrees", kDegree, dim::angle, "", "degree"},
      {"°", kDegree, dim::angle, "", "degree"},
      {"º", kDegree, dim::angle, "", "degree (ordinal sign º, printed for ° by some data sheets)"},
      {"arcmin", kDegree / 60, dim::angle, "", "arc minute"},
      {"arcsec", kDegree / 3600, dim::angle, "", "arc second"},
      // time
      {"s", 1, dim::time, kSmall, "second"},
      {"sec", 1, dim::time, kSmall, "second"},
      {"min", kMinute, dim::time, "", "minute (never milli-inch)"},
      {"h", kHour, dim::time, "", "hour"},
      {"hr", kHour, dim::time, "", "hour"},
      {"hrs", kHour, dim::time, "", "hour"},
      {"hour", kHour, dim::time, "", "hour"},
      {"hours", kHour, dim::time, "", "hour"},
      // frequency
      {"Hz", 1, dim::frequency, "m k M", "hertz"},
      {"SPS", 1, dim::frequency, "k", "samples per second"},
      {"sps", 1, dim::frequency, "k", "samples per second"},
      // angular rate
      {"dps", kDegree, dim::angular_rate, "u µ μ m", "degree per second"},
      {"dph", kDegree / kHour, dim::angular_rate, "", "degree per hour"},
      {"rpm", 2 * std::numbers::pi / kMinute, dim::angular_rate, "", "revolution per minute"},
      // acceleration
      {"g", kStandardGravity, dim::acceleration, kSmall,
       "standard gravity, 9.80665 m/s^2 (never gram: mg is milli-g)"},
      // length
      {"m", 1, dim::length, "n u µ μ m c k", "metre"},
      {"ft", kFoot, dim::length, "", "international foot, 0.3048 m"},
      // ratios
      {"%", 1e-2, dim::dimensionless, "", "percent"},
      {"‰", 1e-3, dim::dimensionless, "", "per mille"},
      {"ppm", 1e-6, dim::dimensionless, "", "part per million"},
      {"ppb", 1e-9, dim::dimensionless, "", "part per billion (1e-9)"},
      // temperature
      {"K", 1, dim::temperature, "m", "kelvin"},
      {"°C", 1, dim::temperature, "", kCelsiusMeaning},
      {"ºC", 1, dim::temperature, "", kCelsiusMeaning},
      {"degC", 1, dim::temperature, "", kCelsiusMeaning},
      {"℃", 1, dim::temperature, "", kCelsiusMeaning},
      // raw counts
      {"LSB", 1, dim::counts, "", "least significant bit, one raw count"},
      {"lsb", 1, dim::counts, "", "least significant bit, one raw count"},
      {"count", 1, dim::counts, "", "raw count"},
      {"counts", 1, dim::counts, "", "raw count"},
  };
  return table;
}

constexpr std::array<std::string_view, 4> kCelsiusNames = {"°C", "ºC", "degC", "℃"};

struct Prefix {
  std::string_view symbol;
  double factor;
};
constexpr std::array<Prefix, 8> kPrefixes = {{{"n", 1e-9},
                                              {"u", 1e-6},
                                              {"µ", 1e-6},
                                              {"μ", 1e-6},
                                              {"m", 1e-3},
                                              {"c", 1e-2},
                                              {"k", 1e3},
                                              {"M", 1e6}}};

bool takes_prefix(std::string_view list, std::string_view prefix) {
  std::size_t start = 0;
  while (start < list.size()) {
    const std::size_t end = std::min(list.find(' ', start), list.size());
    if (list.substr(start, end - start) == prefix) return true;
    start = end + 1;
  }
  return false;
}

const UnitSymbol* find_exact(std::string_view name) {
  for (const auto& s : symbols())
    if (s.name == name) return &s;
  return nullptr;
}

}  // namespace

std::optional<Unit> lookup_symbol(std::string_view name) {
  if (const UnitSymbol* s = find_exact(name)) return Unit{s->factor, s->dimension};
  for (const auto& p : kPrefixes) {
    if (name.size() <= p.symbol.size() || !name.starts_with(p.symbol)) continue;
    const UnitSymbol* s = find_exact(name.substr(p.symbol.size()));
    if (s && takes_prefix(s->prefixes, p.symbol)) return Unit{p.factor * s->factor, s->dimension};
  }
  return std::nullopt;
}

namespace {

std::string ascii_lower(std::string_view s) {
  std::string out(s);
  for (char& c : out)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return out;
}

}  // namespace

std::string unknown_symbol_hint(std::string_view name) {
  if (name == "kg" || name == "gram" || name == "grams")
    return "; g is standard gravity here and mass units are not supported";
  if (name == "C") return "; write °C or degC for a temperature";
  if (name == "rms" || name == "RMS") return "; rms is not a unit, leave it out";
  const std::string lower = ascii_lower(name);
  for (const auto& s : symbols()) {
    if (ascii_lower(s.name) == lower) return "; did you mean \"" + std::string(s.name) + "\"?";
    for (const auto& p : kPrefixes) {
      if (!takes_prefix(s.prefixes, p.symbol)) continue;
      const std::string prefixed = std::string(p.symbol) + std::string(s.name);
      if (ascii_lower(prefixed) == lower) return "; did you mean \"" + prefixed + "\"?";
    }
  }
  return "";
}

bool is_celsius(std::string_view name) {
  for (std::string_view c : kCelsiusNames)
    if (name == c) return true;
  return false;
}

}  // namespace units_detail

const std::vector<UnitSymbol>& known_units() { return units_detail::symbols(); }

}  // namespace sigmatau
