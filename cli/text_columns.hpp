// Text table columns for the CLI's tables (specs, units, check): widths in displayed characters,
// so units such as °/√h line up with plain ASCII.
#pragma once

#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>

namespace sigmatau::cli {

/// Displayed width of UTF-8 text: its code points (every byte but continuation bytes 10xxxxxx).
inline std::size_t display_width(std::string_view text) {
  return static_cast<std::size_t>(std::count_if(text.begin(), text.end(), [](char c) {
    return (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  }));
}

/// `text` padded with spaces to `columns` displayed characters, left-aligned or right-aligned
/// (a longer text is returned as it is).
inline std::string pad(std::string_view text, std::size_t columns, bool right = false) {
  const std::size_t w = display_width(text);
  const std::string fill(w < columns ? columns - w : 0, ' ');
  return right ? fill + std::string(text) : std::string(text) + fill;
}

}  // namespace sigmatau::cli
