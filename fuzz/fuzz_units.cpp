// libFuzzer harness: the unit and quantity parsers (units.hpp). Bad text must give UnitError /
// Error; a parsed unit must have a finite, positive factor.
#include <cmath>
#include <string_view>

#include "sigmatau/error.hpp"
#include "sigmatau/units.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sigmatau;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    const Unit u = parse_unit(text);
    (void)to_string(u.dimension);
  } catch (const Error&) {
  }
  try {
    (void)parse_quantity(text);
  } catch (const Error&) {
  }
  try {
    (void)parse_quantity_as(text, dim::angle_random_walk, "fuzz");
  } catch (const Error&) {
  }
  return 0;
}
