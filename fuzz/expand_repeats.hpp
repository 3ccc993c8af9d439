#pragma once
// Short inputs that stand for huge ones, so that the fuzzer (inputs of at most 4 KB)
// reaches deep nesting and large counts: an input that starts with the line
//   #!repeat N
// is expanded before it is parsed: every piece between a pair of "%%" is written N times
// (N <= 200,000; the whole text at most 128 KiB, so that an input stays within
// the fuzzer's 10 s under the sanitizers), "%N" inside the piece as the number of
// the copy (0, 1, ...). Anything else is used as it is. E.g.
//   #!repeat 40000
//   model = "bar"
//   %%a.%%a = 1                       -> a dotted key 40,001 levels deep
//   %%[[strut]]\nname = "s%N" ...%%   -> struts named s0, s1, ... (500 of 200 bytes)
// Used by fuzz/fuzz_scene and the regression test of its inputs.

#include <cstddef>
#include <cstdlib>
#include <string>
#include <string_view>

namespace fetic::fuzz {

inline std::string expand_repeats(std::string_view input) {
  constexpr std::string_view kMarker = "#!repeat ";
  constexpr long kMaxCount = 200000;
  constexpr std::size_t kMaxBytes = std::size_t{128} << 10;
  if (input.substr(0, kMarker.size()) != kMarker) return std::string(input);
  const std::size_t line_end = input.find('\n');
  if (line_end == std::string_view::npos) return std::string(input);
  const std::string count_text(input.substr(kMarker.size(), line_end - kMarker.size()));
  char* end = nullptr;
  const long count = std::strtol(count_text.c_str(), &end, 10);
  if (end == count_text.c_str() || count < 0 || count > kMaxCount) return std::string(input);
  std::string text(input.substr(0, line_end + 1));  // keeps the line: a TOML comment
  std::string_view rest = input.substr(line_end + 1);
  bool inside = false;
  while (!rest.empty() && text.size() <= kMaxBytes) {
    const std::size_t marker = rest.find("%%");
    const std::string_view piece = rest.substr(0, marker);
    if (!inside) {
      text += piece;
    } else {
      for (long copy = 0; copy < count && text.size() <= kMaxBytes; ++copy) {
        for (std::size_t i = 0; i < piece.size(); ++i) {
          if (piece[i] == '%' && i + 1 < piece.size() && piece[i + 1] == 'N') {
            text += std::to_string(copy);
            ++i;
          } else {
            text += piece[i];
          }
        }
      }
    }
    if (marker == std::string_view::npos) break;
    rest.remove_prefix(marker + 2);
    inside = !inside;
  }
  if (text.size() > kMaxBytes) text.resize(kMaxBytes);
  return text;
}

}  // namespace fetic::fuzz
