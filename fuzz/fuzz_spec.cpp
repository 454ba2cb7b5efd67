// libFuzzer harness: the data-sheet (YAML spec) parser. Bad text must give sigmatau::Error
// (yaml-cpp exceptions included, which the parser must translate).
#include <string_view>

#include "sigmatau/error.hpp"
#include "sigmatau/spec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace sigmatau;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    (void)parse_data_sheet(text, "fuzz.yaml");
  } catch (const Error&) {
  }
  return 0;
}
