#pragma once
// Internal to the units module: the symbol table and its look-up (units_table.cpp); the parser
// (units.cpp) combines what these return.
#include <optional>
#include <string>
#include <string_view>

#include "sigmatau/units.hpp"

namespace sigmatau::units_detail {

/// The unit a symbol stands for: an exact table entry ("min", "mg", "°"), else an SI prefix on
/// an entry that takes it ("mdps", "µrad", "kHz"); nothing when neither.
std::optional<Unit> lookup_symbol(std::string_view name);

/// Text appended to an "unknown unit" message ("; did you mean \"Hz\"?"), or "".
std::string unknown_symbol_hint(std::string_view name);

/// True for the spellings of degree Celsius, which are absolute when they are the whole unit.
bool is_celsius(std::string_view name);

/// Offset of an absolute °C reading [K].
inline constexpr double kZeroCelsius = 273.15;

}  // namespace sigmatau::units_detail
