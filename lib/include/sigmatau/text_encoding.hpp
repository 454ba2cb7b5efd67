#pragma once
/// \file text_encoding.hpp
/// Names are user data and arrive in whatever encoding the tool that wrote them used: a CSV
/// header written by a Windows program holds "°" as the single byte 0xB0 (Windows-1252), which
/// is not UTF-8. Every name sigmatau writes out (JSON, Markdown, HTML, SVG, filter files) must be
/// UTF-8, so names are made UTF-8 once, where they enter.

#include <string>
#include <string_view>

namespace sigmatau {

/// Whether `text` is well-formed UTF-8 (RFC 3629: no overlong forms, no surrogates, nothing
/// above U+10FFFF).
bool is_utf8(std::string_view text);

/// `text` as UTF-8: its well-formed UTF-8 sequences are kept, and every other byte is read as
/// Windows-1252 (which is Latin-1, ISO 8859-1, from 0xA0 up, and prints 0x80-0x9F as the
/// typographic signs Windows tools write there: €, ’, “, ...): 0xB0 becomes "°" (U+00B0). The
/// five bytes Windows-1252 leaves undefined (0x81, 0x8D, 0x8F, 0x90, 0x9D) become U+FFFD.
/// Well-formed UTF-8 comes back unchanged.
std::string utf8_from_windows1252(std::string_view text);

/// `text` for a message: printable ASCII and well-formed UTF-8 kept, every other byte written
/// as \xHH (so "gyro \xB0/s" shows the byte the file holds). The result is always UTF-8.
std::string escape_non_utf8(std::string_view text);

}  // namespace sigmatau
