#pragma once
// Values and numbers shown in messages, the same way in every layer: a value quoted back
// is escaped (control characters as \n, \xHH: scenes::printable) and cut to about 80
// characters, so that a message stays one readable line whatever the input held (a
// 10 MB name, a NUL byte, a BOM).

#include <cstdio>
#include <string>
#include <string_view>

#include "scenes/scene_error.hpp"

namespace fetic::scenes {

// At most this many characters of a value are shown before "...".
inline constexpr size_t kShownValueLength = 80;

// The value escaped and cut: "aaaa... (10485760 bytes)".
inline std::string shortened(std::string_view text) {
  if (text.size() <= kShownValueLength) {
    std::string whole = printable(std::string(text));
    if (whole.size() <= kShownValueLength) return whole;
  }
  // Whole characters (UTF-8), escaped, up to 60 characters shown; then how long it was.
  std::string shown;
  for (size_t at = 0; at < text.size();) {
    size_t next = at + 1;
    while (next < text.size() && (static_cast<unsigned char>(text[next]) & 0xC0) == 0x80)
      ++next;
    const std::string piece = printable(std::string(text.substr(at, next - at)));
    if (shown.size() + piece.size() > kShownValueLength - 20) break;
    shown += piece;
    at = next;
  }
  return shown + "... (" + std::to_string(text.size()) + " bytes)";
}

// The same in single quotes: 'name'.
inline std::string quoted(std::string_view text) {
  return "'" + shortened(text) + "'";
}

// Six significant digits, as %g.
inline std::string number_text(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", value);
  return buffer;
}

}  // namespace fetic::scenes
