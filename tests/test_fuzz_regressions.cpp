// Inputs the fuzzers (fuzz/, scripts/fuzz.sh) found crashing, kept in tests/data/fuzz/: each must
// now parse or fail with sigmatau::Error, never with a foreign exception.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "sigmatau/error.hpp"
#include "sigmatau/spec.hpp"
#include "test_support.hpp"

using namespace sigmatau;
namespace fs = std::filesystem;

namespace {

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// "error" when `f` throws sigmatau::Error, "ok" when it returns, else the foreign exception.
template <class F>
std::string outcome(F f) {
  try {
    f();
    return "ok";
  } catch (const Error&) {
    return "error";
  } catch (const std::exception& e) {
    return std::string("foreign exception: ") + e.what();
  }
}

}  // namespace

TEST_CASE("spec inputs found by fuzz_spec parse or throw sigmatau::Error") {
  int files = 0;
  for (const auto& entry : fs::directory_iterator(test::test_data_dir() / "fuzz" / "spec")) {
    CAPTURE(entry.path().string());
    const std::string text = slurp(entry.path());
    const std::string r = outcome([&] { parse_data_sheet(text, entry.path().string()); });
    INFO(r);
    CHECK((r == "ok" || r == "error"));
    ++files;
  }
  CHECK(files >= 1);
}
