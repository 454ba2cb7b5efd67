// Unit parser: data-sheet notations to SI, with dimensions kept in halves of exponents.
//
// Glossary:
//   factor  value_in_si = value_in_unit * factor (+ offset for a lone absolute temperature)
//   x2      2 x an exponent (Dimension stores halves so sqrt(Hz) is exact)
//   column  1-based position in characters (UTF-8 code points), as a text editor counts
//   symbol  a run of letters and unit signs (°, µ, μ, %, ...) looked up in units_table.cpp
#include "sigmatau/units.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>

#include "units_table.hpp"

namespace sigmatau {
namespace {

using units_detail::kZeroCelsius;

/// Largest |exponent| accepted after '^'. No physical unit needs more; the limit keeps the
/// dimension exponents (ints) and the factor far from overflow.
constexpr double kMaxExponent = 16;
/// An exponent times a dimension exponent must be a whole number of halves; this tolerance only
/// absorbs the rounding of decimal exponents such as ^0.3333333333 (which is still rejected).
constexpr double kHalvesTolerance = 1e-9;
/// Deepest nesting of parentheses and roots accepted ("((deg)/s)" is 2, "sqrt(sqrt(h))" 4). The
/// deepest data-sheet unit nests 2 or 3 deep; the parser recurses once per level, so without a
/// bound a text of 20000 '(' overflowed the stack (SIGSEGV).
constexpr int kMaxNesting = 32;
/// Largest |dimension exponent| in halves (Dimension): 64 is an exponent of 32, far beyond any
/// physical unit (the noise terms reach 2.5). Powers of powers ("((s^16)^16)^16") and long
/// products stop here, well before the int exponents overflow.
constexpr int kMaxDimensionHalves = 64;
/// A unit text longer than this [characters] is quoted in messages as an excerpt around the
/// column at fault, so a hostile 1 MB text gives a one-line message.
constexpr std::size_t kMaxQuotedChars = 80;

// ---- UTF-8 ----------------------------------------------------------------------------------

constexpr char32_t kInvalid = 0xFFFFFFFF;

struct CodePoint {
  char32_t value = kInvalid;
  std::size_t size = 1;
};

CodePoint decode(std::string_view s, std::size_t pos) {
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(s[i]); };
  const unsigned char b0 = byte(pos);
  if (b0 < 0x80) return {b0, 1};
  std::size_t n = 0;
  char32_t v = 0;
  if ((b0 & 0xE0) == 0xC0) {
    n = 2;
    v = b0 & 0x1F;
  } else if ((b0 & 0xF0) == 0xE0) {
    n = 3;
    v = b0 & 0x0F;
  } else if ((b0 & 0xF8) == 0xF0) {
    n = 4;
    v = b0 & 0x07;
  } else {
    return {};
  }
  if (pos + n > s.size()) return {};
  for (std::size_t i = 1; i < n; ++i) {
    if ((byte(pos + i) & 0xC0) != 0x80) return {};
    v = (v << 6) | (byte(pos + i) & 0x3F);
  }
  return {v, n};
}

std::size_t column_of(std::string_view text, std::size_t byte_pos) {
  std::size_t column = 1;
  for (std::size_t i = 0; i < byte_pos && i < text.size(); ++i)
    if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) ++column;
  return column;
}

/// Byte position of the code point `chars` characters before (negative) or after `byte_pos`,
/// clamped to the text.
std::size_t step_chars(std::string_view text, std::size_t byte_pos, long chars) {
  const auto lead = [&](std::size_t i) { return (static_cast<unsigned char>(text[i]) & 0xC0) != 0x80; };
  std::size_t p = std::min(byte_pos, text.size());
  for (; chars < 0 && p > 0; ++chars) {
    --p;
    while (p > 0 && !lead(p)) --p;
  }
  for (; chars > 0 && p < text.size(); --chars) {
    ++p;
    while (p < text.size() && !lead(p)) ++p;
  }
  return p;
}

/// `text` for a message: whole when it has at most kMaxQuotedChars characters, else the
/// kMaxQuotedChars around `byte_pos` with "..." where it is cut.
std::string excerpt(std::string_view text, std::size_t byte_pos) {
  if (column_of(text, text.size()) - 1 <= kMaxQuotedChars) return std::string(text);
  const auto half = static_cast<long>(kMaxQuotedChars / 2);
  const std::size_t begin = step_chars(text, byte_pos, -half);
  const std::size_t end = step_chars(text, begin, 2 * half);
  return (begin > 0 ? "..." : "") + std::string(text.substr(begin, end - begin)) +
         (end < text.size() ? "..." : "");
}

std::string describe(std::string_view text, std::size_t pos, const CodePoint& c) {
  char buffer[32];
  if (c.value == kInvalid) {
    std::snprintf(buffer, sizeof buffer, "byte 0x%02X (not UTF-8)",
                  static_cast<unsigned>(static_cast<unsigned char>(text[pos])));
    return buffer;
  }
  if (c.value < 0x20 || c.value == 0x7F) {
    std::snprintf(buffer, sizeof buffer, "control character U+%04X",
                  static_cast<unsigned>(c.value));
    return buffer;
  }
  std::snprintf(buffer, sizeof buffer, " (U+%04X)", static_cast<unsigned>(c.value));
  return "'" + std::string(text.substr(pos, c.size)) + "'" + (c.value < 0x80 ? "" : buffer);
}

bool is_space(char32_t c) {
  return c == ' ' || c == '\t' || c == 0xA0 || c == 0x2009 || c == 0x202F;
}
bool is_digit(char32_t c) { return c >= '0' && c <= '9'; }
bool is_minus(char32_t c) { return c == '-' || c == 0x2212; }
bool is_symbol_char(char32_t c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == 0xB0 || c == 0xBA || c == 0xB5 ||
         c == 0x3BC || c == 0x2103 || c == '%' || c == 0x2030;
}
/// Value of a superscript digit, or -1.
int superscript_digit(char32_t c) {
  if (c == 0x2070) return 0;
  if (c == 0xB9) return 1;
  if (c == 0xB2) return 2;
  if (c == 0xB3) return 3;
  if (c >= 0x2074 && c <= 0x2079) return static_cast<int>(c - 0x2070);
  return -1;
}
constexpr char32_t kSuperMinus = 0x207B;
constexpr char32_t kHalf = 0xBD;

std::string format_number(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

Unit multiply(const Unit& a, const Unit& b, int sign) {
  Unit u;
  u.factor = sign > 0 ? a.factor * b.factor : a.factor / b.factor;
  u.dimension.angle2 = a.dimension.angle2 + sign * b.dimension.angle2;
  u.dimension.length2 = a.dimension.length2 + sign * b.dimension.length2;
  u.dimension.time2 = a.dimension.time2 + sign * b.dimension.time2;
  u.dimension.temperature2 = a.dimension.temperature2 + sign * b.dimension.temperature2;
  u.dimension.counts2 = a.dimension.counts2 + sign * b.dimension.counts2;
  return u;
}

// ---- parser -----------------------------------------------------------------------------------

/// Recursive-descent parser over `text` (the whole text the caller passed, so columns and the
/// quoted text in messages are the caller's), starting at byte `start`.
class Parser {
 public:
  Parser(std::string_view text, std::size_t start) : text_(text), pos_(start) {}

  Unit parse_all() {
    skip_space();
    if (at_end()) fail("empty unit", pos_);
    Unit u = parse_product();
    if (!at_end()) fail("unbalanced ')'", pos_);  // parse_product stops only at the end or ')'
    return u;
  }

  /// Throws `PROBLEM at column N of "TEXT"HINT`.
  [[noreturn]] void fail(const std::string& problem, std::size_t byte_pos,
                         const std::string& hint = "") const {
    const std::size_t column = column_of(text_, byte_pos);
    throw UnitError(problem + " at column " + std::to_string(column) + " of \"" +
                        excerpt(text_, byte_pos) + "\"" + hint,
                    column);
  }

 private:
  bool at_end() const { return pos_ >= text_.size(); }
  CodePoint peek() const { return at_end() ? CodePoint{0, 0} : decode(text_, pos_); }
  bool peek_is(char32_t c) const { return !at_end() && peek().value == c; }
  void advance() { pos_ += peek().size; }
  bool skip_space() {
    const std::size_t start = pos_;
    while (!at_end() && is_space(peek().value)) advance();
    return pos_ != start;
  }
  std::string found_here() const {
    return at_end() ? "the end of the text" : describe(text_, pos_, peek());
  }

  /// One level of '(' or root, for the extent of a parse_factor call that recurses; throws past
  /// kMaxNesting (where the level opens).
  class Nested {
   public:
    Nested(Parser& parser, std::size_t where) : parser_(parser) {
      if (++parser_.depth_ > kMaxNesting) {
        parser_.fail("more than " + std::to_string(kMaxNesting) +
                         " nested parentheses or roots (no unit nests this deep)",
                     where);
      }
    }
    ~Nested() { --parser_.depth_; }
    Nested(const Nested&) = delete;
    Nested& operator=(const Nested&) = delete;

   private:
    Parser& parser_;
  };

  /// `u` when every dimension exponent is within kMaxDimensionHalves, else fails at `where`.
  Unit bounded(const Unit& u, std::size_t where) const {
    const Dimension& d = u.dimension;
    for (const int x2 : {d.angle2, d.length2, d.time2, d.temperature2, d.counts2}) {
      if (std::abs(x2) > kMaxDimensionHalves) {
        fail("a dimension exponent beyond " + std::to_string(kMaxDimensionHalves / 2) +
                 " (no physical unit has one)",
             where);
      }
    }
    return u;
  }

  /// factor { op factor }, stopping before ')' or at the end.
  Unit parse_product() {
    Unit u;
    bool divided = false;
    if (!peek_is('/')) u = parse_factor();  // a leading '/' means 1/...
    for (;;) {
      const bool spaced = skip_space();
      if (at_end() || peek_is(')')) return u;
      const std::size_t op = pos_;
      const char32_t c = peek().value;
      if (c == '*' || c == 0xB7 || c == 0x22C5) {
        advance();
        skip_space();
        u = bounded(multiply(u, parse_factor(), +1), op);
      } else if (c == '/') {
        advance();
        skip_space();
        u = bounded(multiply(u, parse_factor(), -1), op);
        divided = true;
      } else if (spaced) {
        const Unit next = parse_factor();  // first, so an unknown word is reported as such
        if (divided) fail("ambiguous product after '/' (write a/(b*c) or a/b*c)", op);
        u = bounded(multiply(u, next, +1), op);
      } else {
        fail("unexpected " + found_here(), op);
      }
    }
  }

  Unit parse_factor() {
    const std::size_t start = pos_;
    if (at_end()) fail("expected a unit, found the end of the text", pos_);
    const char32_t c = peek().value;
    if (c == 0x221A) {  // √
      const Nested level(*this, start);
      advance();
      skip_space();
      return power(parse_factor(), 0.5, start);
    }
    if (c == '(') {
      const Nested level(*this, start);
      advance();
      skip_space();
      const Unit inner = parse_product();
      if (at_end()) fail("unbalanced '(' (no matching ')')", start);
      advance();  // ')'
      return parse_power_suffix(inner);
    }
    if (is_digit(c)) {
      while (!at_end() && (is_digit(peek().value) || peek_is('.'))) advance();
      if (text_.substr(start, pos_ - start) != "1") {
        fail("a number inside a unit must be 1 (as in 1/s), found \"" +
                 std::string(text_.substr(start, pos_ - start)) + "\"",
             start);
      }
      return parse_power_suffix(Unit{});
    }
    if (is_symbol_char(c)) {
      while (!at_end() && is_symbol_char(peek().value)) advance();
      const std::string_view name = text_.substr(start, pos_ - start);
      if (name == "sqrt" || name == "rt") {
        const Nested level(*this, start);
        if (name == "rt" && is_minus(peek().value) && !at_end()) advance();  // rt-Hz
        skip_space();
        return power(parse_factor(), 0.5, start);
      }
      Unit u = resolve(name, start);
      if (!at_end() && is_digit(peek().value)) {  // "m/s2": digits right after a symbol
        const std::size_t digits = pos_;
        while (!at_end() && is_digit(peek().value)) advance();
        if (peek_is('.')) fail("write a fractional power with '^' (e.g. s^1.5)", digits);
        double p = 0;
        const auto [end, ec] = std::from_chars(text_.data() + digits, text_.data() + pos_, p);
        if (ec != std::errc()) fail("malformed exponent", digits);
        return power(u, p, digits);
      }
      return parse_power_suffix(u);
    }
    fail("expected a unit, found " + found_here(), pos_);
  }

  Unit resolve(std::string_view name, std::size_t start) const {
    if (auto u = units_detail::lookup_symbol(name)) return *u;
    for (std::string_view root : {"sqrt", "rt"}) {  // sqrtHz, rtHz
      if (name.size() > root.size() && name.starts_with(root)) {
        if (auto u = units_detail::lookup_symbol(name.substr(root.size())))
          return power(*u, 0.5, start);
      }
    }
    fail("unknown unit \"" + std::string(name) + "\"", start,
         units_detail::unknown_symbol_hint(name));
  }

  /// ^2, ^-1, ^0.5, ^(1/2), ^(-3/2), ^½, ², ⁻¹, ½ after a primary.
  Unit parse_power_suffix(const Unit& u) {
    const std::size_t start = pos_;
    if (peek_is('^')) {
      advance();
      double p = 0;
      if (peek_is('(')) {
        advance();
        p = parse_exponent_number(true);
        if (peek_is('/')) {
          advance();
          const std::size_t denominator_pos = pos_;
          const double q = parse_exponent_number(false);
          if (!(q > 0)) fail("zero denominator in the exponent", denominator_pos);
          p /= q;
        }
        if (!peek_is(')')) fail("unbalanced '(' in the exponent, found " + found_here(), pos_);
        advance();
      } else if (peek_is(kHalf)) {
        advance();
        p = 0.5;
      } else {
        p = parse_exponent_number(true);
      }
      return power(u, p, start);
    }
    const char32_t c = peek().value;
    if (!at_end() && (c == kSuperMinus || c == kHalf || superscript_digit(c) >= 0)) {
      double sign = 1;
      if (peek_is(kSuperMinus)) {
        advance();
        sign = -1;
      }
      double p = 0;
      if (peek_is(kHalf)) {
        advance();
        p = 0.5;
      } else {
        if (at_end() || superscript_digit(peek().value) < 0)
          fail("expected a superscript digit, found " + found_here(), pos_);
        while (!at_end() && superscript_digit(peek().value) >= 0) {
          p = 10 * p + superscript_digit(peek().value);
          advance();
        }
      }
      return power(u, sign * p, start);
    }
    return u;
  }

  /// [sign] digits [. digits]
  double parse_exponent_number(bool allow_sign) {
    const std::size_t start = pos_;
    double sign = 1;
    if (allow_sign && !at_end() && (is_minus(peek().value) || peek_is('+'))) {
      if (is_minus(peek().value)) sign = -1;
      advance();
    }
    const std::size_t digits = pos_;
    while (!at_end() && (is_digit(peek().value) || peek_is('.'))) advance();
    double v = 0;
    const char* first = text_.data() + digits;
    const char* last = text_.data() + pos_;
    const auto [end, ec] = std::from_chars(first, last, v);
    if (digits == pos_ || ec != std::errc() || end != last)
      fail("expected an exponent, found " +
               (digits == pos_ ? found_here() : "\"" + std::string(first, last) + "\""),
           start);
    return sign * v;
  }

  Unit power(const Unit& u, double p, std::size_t where) const {
    if (!(std::abs(p) <= kMaxExponent))
      fail("exponent " + format_number(p) + " is out of range (|p| <= 16)", where);
    const auto scaled = [&](int x2) {
      const double x = x2 * p;
      const double r = std::round(x);
      if (!(std::abs(x - r) <= kHalvesTolerance))
        fail("power " + format_number(p) +
                 " gives an exponent that is not a multiple of 1/2 (quarter roots are not units)",
             where);
      if (!(std::abs(r) <= kMaxDimensionHalves)) {  // before the cast: it would overflow int
        fail("a dimension exponent beyond " + std::to_string(kMaxDimensionHalves / 2) +
                 " (no physical unit has one)",
             where);
      }
      return static_cast<int>(r);
    };
    Unit out;
    out.factor = p == 0.5 ? std::sqrt(u.factor) : std::pow(u.factor, p);
    out.dimension = {scaled(u.dimension.angle2), scaled(u.dimension.length2),
                     scaled(u.dimension.time2), scaled(u.dimension.temperature2),
                     scaled(u.dimension.counts2)};
    return out;
  }

  std::string_view text_;
  std::size_t pos_;
  int depth_ = 0;  ///< levels of '(' and roots open (Nested)
};

std::string_view trim(std::string_view s) {
  std::size_t begin = 0, end = s.size();
  while (begin < end && is_space(decode(s, begin).value)) begin += decode(s, begin).size;
  while (end > begin && (s[end - 1] == ' ' || s[end - 1] == '\t')) --end;
  return s.substr(begin, end - begin);
}

/// Parses the unit in text[start..] (the whole text is quoted in errors).
Unit parse_unit_at(std::string_view text, std::size_t start) {
  Unit u = Parser(text, start).parse_all();
  if (!std::isfinite(u.factor) || !(u.factor > 0)) {
    Parser(text, start).fail("unit factor out of double range", start);
  }
  const std::string_view unit_text = trim(text.substr(start));
  if (units_detail::is_celsius(unit_text)) u.offset = kZeroCelsius;
  return u;
}

struct ParsedQuantity {
  double value = 0;  // in the written unit
  Unit unit;
  std::string_view unit_text;  // "" when dimensionless by omission
};

ParsedQuantity parse_quantity_parts(std::string_view text) {
  const Parser located(text, 0);
  std::size_t pos = 0;
  while (pos < text.size() && is_space(decode(text, pos).value)) pos += decode(text, pos).size;
  if (pos >= text.size()) located.fail("empty quantity (expected a number and a unit)", pos);
  const std::size_t number_start = pos;
  double sign = 1;
  const CodePoint first = decode(text, pos);
  if (is_minus(first.value) || first.value == '+') {
    if (is_minus(first.value)) sign = -1;
    pos += first.size;
  }
  const bool starts_numeric =
      pos < text.size() && (is_digit(static_cast<unsigned char>(text[pos])) ||
                            (text[pos] == '.' && pos + 1 < text.size() &&
                             is_digit(static_cast<unsigned char>(text[pos + 1]))));
  if (!starts_numeric)
    located.fail(
        "expected a number, found " + describe(text, number_start, decode(text, number_start)),
        number_start);
  double value = 0;
  const auto [end, ec] = std::from_chars(text.data() + pos, text.data() + text.size(), value);
  const std::string number(
      text.substr(number_start, static_cast<std::size_t>(end - text.data()) - number_start));
  if (ec == std::errc::result_out_of_range)
    located.fail("number \"" + number + "\" is out of double range", number_start);
  if (ec != std::errc()) located.fail("malformed number", number_start);
  pos = static_cast<std::size_t>(end - text.data());

  ParsedQuantity q;
  q.value = sign * value;
  std::size_t unit_start = pos;
  while (unit_start < text.size() && is_space(decode(text, unit_start).value))
    unit_start += decode(text, unit_start).size;
  if (unit_start < text.size()) {
    q.unit = parse_unit_at(text, pos);
    q.unit_text = trim(text.substr(pos));
  }
  const double si = q.value * q.unit.factor + q.unit.offset;
  if (!std::isfinite(si))
    located.fail("value \"" + excerpt(text, number_start) + "\" overflows in SI", number_start);
  return q;
}

std::string dimension_text(const Dimension& d, const std::array<std::string_view, 5>& names,
                           std::string_view none) {
  const int x2[5] = {d.counts2, d.angle2, d.length2, d.temperature2, d.time2};
  const auto term = [&](int i, int e2) {
    const std::string name(names[static_cast<std::size_t>(i)]);
    if (e2 == 2) return name;
    if (e2 == 1) return "sqrt(" + name + ")";
    if (e2 % 2 == 0) return name + "^" + std::to_string(e2 / 2);
    return name + "^" + std::to_string(e2 / 2) + ".5";
  };
  std::string numerator, denominator;
  for (int i = 0; i < 5; ++i) {
    if (x2[i] > 0) numerator += (numerator.empty() ? "" : "*") + term(i, x2[i]);
    if (x2[i] < 0) denominator += "/" + term(i, -x2[i]);
  }
  if (numerator.empty() && denominator.empty()) return std::string(none);
  return (numerator.empty() ? "1" : numerator) + denominator;
}

}  // namespace

std::string to_string(const Dimension& dimension) {
  return dimension_text(dimension, {"counts", "angle", "length", "temperature", "time"},
                        "dimensionless");
}

std::string si_unit_string(const Dimension& dimension) {
  return dimension_text(dimension, {"LSB", "rad", "m", "K", "s"}, "1");
}

Unit parse_unit(std::string_view text) { return parse_unit_at(text, 0); }

Unit parse_unit_as(std::string_view text, const Dimension& expected, std::string_view what) {
  const std::string prefix = std::string(what) + ": ";
  Unit u;
  try {
    u = parse_unit(text);
  } catch (const UnitError& e) {
    throw UnitError(prefix + e.what(), e.column());
  }
  if (!(u.dimension == expected)) {
    throw UnitError(prefix + "expected " + to_string(expected) + " (e.g. " +
                        si_unit_string(expected) + "), found " + to_string(u.dimension) + " (" +
                        excerpt(trim(text), 0) + ")",
                    0);
  }
  return u;
}

Quantity parse_quantity(std::string_view text) {
  const ParsedQuantity q = parse_quantity_parts(text);
  return {q.value * q.unit.factor + q.unit.offset, q.unit.dimension};
}

double convert(double value, std::string_view from, std::string_view to) {
  const Unit a = parse_unit(from);
  const Unit b = parse_unit(to);
  if (!(a.dimension == b.dimension)) {
    throw UnitError("cannot convert " + excerpt(trim(from), 0) + " (" + to_string(a.dimension) +
                        ") to " + excerpt(trim(to), 0) + " (" + to_string(b.dimension) + ")",
                    0);
  }
  return (value * a.factor + a.offset - b.offset) / b.factor;
}

double parse_quantity_as(std::string_view text, const Dimension& expected, std::string_view field) {
  const std::string prefix = std::string(field) + ": ";
  ParsedQuantity q;
  try {
    q = parse_quantity_parts(text);
  } catch (const UnitError& e) {
    throw UnitError(prefix + e.what(), e.column());
  }
  if (!(q.unit.dimension == expected)) {
    const std::string written = q.unit_text.empty() ? "no unit" : std::string(q.unit_text);
    throw UnitError(prefix + "expected " + to_string(expected) + " (e.g. " +
                        si_unit_string(expected) + "), found " + to_string(q.unit.dimension) +
                        " (" + excerpt(written, 0) + ") in \"" + excerpt(text, 0) + "\"",
                    0);
  }
  return q.value * q.unit.factor + q.unit.offset;
}

}  // namespace sigmatau
