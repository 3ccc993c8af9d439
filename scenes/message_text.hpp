#pragma once
// Values and numbers shown in messages, the same way in every layer: a value quoted back
// is escaped (control characters as \n, \xHH: scenes::printable) and cut to about 80
// characters, so that a message stays one readable line whatever the input held (a
// 10 MB name, a NUL byte, a BOM).

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include "scenes/scene_error.hpp"

namespace fetic::scenes {

// At most this many characters of a value are shown before "...".
inline constexpr size_t kShownValueLength = 80;

// The value escaped and cut: "aaaa... (10485760 bytes)"; at most `limit` characters
// (kShownValueLength unless a message has room for more).
inline std::string shortened(std::string_view text, size_t limit = kShownValueLength) {
  if (text.size() <= limit) {
    std::string whole = printable(std::string(text));
    if (whole.size() <= limit) return whole;
  }
  // Whole characters (UTF-8), escaped, up to limit - 20 characters shown; then how long
  // it was.
  std::string shown;
  for (size_t at = 0; at < text.size();) {
    size_t next = at + 1;
    while (next < text.size() && (static_cast<unsigned char>(text[next]) & 0xC0) == 0x80)
      ++next;
    const std::string piece = printable(std::string(text.substr(at, next - at)));
    if (shown.size() + piece.size() + 20 > limit) break;
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

enum class LetterCase { Exact, Ignored };

// Levenshtein distance, for "did you mean" suggestions (scene keys ignore case, command
// line options do not).
inline size_t edit_distance(std::string_view a, std::string_view b, LetterCase letter_case) {
  const auto same = [letter_case](char x, char y) {
    if (letter_case == LetterCase::Exact) return x == y;
    return std::tolower(static_cast<unsigned char>(x)) ==
           std::tolower(static_cast<unsigned char>(y));
  };
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j)
    row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] =
          std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same(a[i - 1], b[j - 1]) ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

}  // namespace fetic::scenes
