// UTF-8 checks and the Windows-1252 reading of bytes that are not UTF-8 (text_encoding.hpp).
//
// Glossary: a sequence is a lead byte and its continuation bytes (10xxxxxx); code point ranges
// per RFC 3629 section 4: 2-byte leads C2..DF, 3-byte E0..EF (E0 needs A0..BF next, ED 80..9F),
// 4-byte F0..F4 (F0 needs 90..BF next, F4 80..8F).
#include "sigmatau/text_encoding.hpp"

#include <cstdint>
#include <cstdio>

namespace sigmatau {
namespace {

/// Unicode code points of Windows-1252's bytes 0x80..0x9F (unicode.org's cp1252 mapping table,
/// MAPPINGS/VENDORS/MICSFT/WINDOWS/CP1252.TXT); 0 where the byte is undefined.
constexpr char16_t kCp1252High[32] = {
    0x20AC, 0,      0x201A, 0x0192, 0x201E, 0x2026, 0x2020, 0x2021,  // 80-87
    0x02C6, 0x2030, 0x0160, 0x2039, 0x0152, 0,      0x017D, 0,       // 88-8F
    0,      0x2018, 0x2019, 0x201C, 0x201D, 0x2022, 0x2013, 0x2014,  // 90-97
    0x02DC, 0x2122, 0x0161, 0x203A, 0x0153, 0,      0x017E, 0x0178,  // 98-9F
};
/// U+FFFD REPLACEMENT CHARACTER, for the bytes Windows-1252 does not define.
constexpr char32_t kReplacement = 0xFFFD;

/// Length of the well-formed UTF-8 sequence at text[i], 0 when there is none.
std::size_t sequence_length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char b0 = byte(i);
  if (b0 < 0x80) return 1;
  std::size_t n = 0;
  unsigned char low = 0x80, high = 0xBF;  // allowed range of the second byte
  if (b0 >= 0xC2 && b0 <= 0xDF) {
    n = 2;
  } else if (b0 >= 0xE0 && b0 <= 0xEF) {
    n = 3;
    if (b0 == 0xE0) low = 0xA0;   // no overlong forms
    if (b0 == 0xED) high = 0x9F;  // no surrogates
  } else if (b0 >= 0xF0 && b0 <= 0xF4) {
    n = 4;
    if (b0 == 0xF0) low = 0x90;   // no overlong forms
    if (b0 == 0xF4) high = 0x8F;  // nothing above U+10FFFF
  } else {
    return 0;
  }
  if (i + n > text.size()) return 0;
  if (byte(i + 1) < low || byte(i + 1) > high) return 0;
  for (std::size_t k = 2; k < n; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
  }
  return n;
}

void append_utf8(std::string& out, char32_t c) {
  if (c < 0x80) {
    out += static_cast<char>(c);
  } else if (c < 0x800) {
    out += static_cast<char>(0xC0 | (c >> 6));
    out += static_cast<char>(0x80 | (c & 0x3F));
  } else {  // the BMP is enough here: Windows-1252 maps into it
    out += static_cast<char>(0xE0 | (c >> 12));
    out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (c & 0x3F));
  }
}

}  // namespace

bool is_utf8(std::string_view text) {
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = sequence_length(text, i);
    if (n == 0) return false;
    i += n;
  }
  return true;
}

std::string utf8_from_windows1252(std::string_view text) {
  std::string out;
  out.reserve(text.size() + text.size() / 2);
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = sequence_length(text, i);
    if (n > 0) {
      out.append(text.substr(i, n));
      i += n;
      continue;
    }
    const auto b = static_cast<unsigned char>(text[i++]);
    char32_t c = b;  // 0xA0..0xFF: Latin-1, the same code point
    if (b < 0xA0) c = kCp1252High[b - 0x80] != 0 ? kCp1252High[b - 0x80] : kReplacement;
    append_utf8(out, c);
  }
  return out;
}

std::string escape_non_utf8(std::string_view text) {
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = sequence_length(text, i);
    const auto b = static_cast<unsigned char>(text[i]);
    if (n > 0 && b >= 0x20 && b != 0x7F) {
      out.append(text.substr(i, n));
      i += n;
      continue;
    }
    char hex[8];
    std::snprintf(hex, sizeof hex, "\\x%02X", static_cast<unsigned>(b));
    out += hex;
    ++i;
  }
  return out;
}

}  // namespace sigmatau
