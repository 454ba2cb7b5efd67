// Unit parser on hostile texts (issue 28): nesting, powers of powers and very long texts end in
// a UnitError naming the column, never in a stack overflow or an int overflow, and the message
// stays one short line.
#include <string>

#include "sigmatau/units.hpp"
#include "test_support.hpp"

using namespace sigmatau;

namespace {

struct Caught {
  bool thrown = false;
  std::string message;
  std::size_t column = 0;
};

Caught parse_error(const std::string& text) {
  try {
    parse_unit(text);
  } catch (const UnitError& e) {
    return {true, e.what(), e.column()};
  }
  return {};
}

std::string repeated(const std::string& piece, int n) {
  std::string out;
  for (int i = 0; i < n; ++i) out += piece;
  return out;
}

/// Longest message accepted [bytes]: the problem (under 100), the column and an 80-character
/// excerpt with its "..." (up to 3 bytes a character: 246) fit in 400.
constexpr std::size_t kShortMessage = 400;

}  // namespace

TEST_CASE("20000 nested parentheses are a UnitError at the 33rd, not a stack overflow") {
  const std::string text = repeated("(", 20000) + "s" + repeated(")", 20000);
  const Caught c = parse_error(text);
  REQUIRE(c.thrown);
  INFO(c.message);
  CHECK(c.message.find("more than 32 nested parentheses or roots") != std::string::npos);
  CHECK(c.column == 33);  // the level that opens past the bound
  CHECK(c.message.size() < kShortMessage);
}

TEST_CASE("nested roots in every spelling are bounded alike") {
  for (const std::string root : {"sqrt ", "√", "rt "}) {
    INFO("root: " << root);
    const Caught c = parse_error(repeated(root, 20000) + "Hz");
    REQUIRE(c.thrown);
    CHECK(c.message.find("nested parentheses or roots") != std::string::npos);
    CHECK(c.message.size() < kShortMessage);
  }
}

TEST_CASE("32 levels of nesting still parse: the bound is past any real unit") {
  const Unit u = parse_unit(repeated("(", 32) + "deg" + repeated(")", 32) + "/s");
  CHECK(u.dimension == dim::angular_rate);
  CHECK(parse_error(repeated("(", 33) + "deg" + repeated(")", 33) + "/s").thrown);
}

TEST_CASE("powers of powers stop at exponent 32 instead of overflowing the exponents") {
  // (s^16)^16 is time^256: before the bound the int exponents overflowed (undefined behaviour;
  // 16 levels printed time^-1073741824).
  const Caught c = parse_error("(s^16)^16");
  REQUIRE(c.thrown);
  INFO(c.message);
  CHECK(c.message.find("dimension exponent beyond 32") != std::string::npos);
  CHECK(parse_unit("(s^4)^4").dimension.time2 == 32);  // exponent 16: accepted
  // A long product reaches the bound too.
  CHECK(parse_error(repeated("s*", 40) + "s").message.find("dimension exponent beyond 32") !=
        std::string::npos);
}

TEST_CASE("a long unit text is quoted as an excerpt around the column at fault") {
  const std::string text = repeated("deg/deg*", 500) + "foo";
  const Caught c = parse_error(text);
  REQUIRE(c.thrown);
  INFO(c.message);
  CHECK(c.message.find("unknown unit \"foo\"") != std::string::npos);
  CHECK(c.column == 4001);
  CHECK(c.message.find("\"...") != std::string::npos);       // cut before the column
  CHECK(c.message.find("deg*foo\"") != std::string::npos);  // the excerpt ends at the text's end
  CHECK(c.message.size() < kShortMessage);
}
