// The YAML of a made-up data sheet for tests: the preamble every test sheet shares (schema,
// maker, part, grade, one primary source "ds") followed by the test's own sensor sections.
#pragma once

#include <string>
#include <string_view>

namespace sigmatau::test {

/// `sections` holds the sensor sections ("gyro:\n  noise_density:\n ..."), each item citing
/// source ds.
inline std::string made_up_sheet(std::string_view part, std::string_view sections) {
  return "schema: 1\nmanufacturer: Test\npart: " + std::string(part) +
         "\ngrade: industrial\nsources:\n  ds:\n    document: test sheet\n    revision: \"1\"\n"
         "    kind: primary\n" +
         std::string(sections);
}

}  // namespace sigmatau::test
