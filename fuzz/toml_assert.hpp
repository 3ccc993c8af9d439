#pragma once
// Force-included into the fuzz build (header-only toml++ with assertions on). Two
// precondition assertions of toml++ 3.3 fire on malformed input although the code right
// after them reports that input as an ordinary parse error:
//   - parse_table_header() calls parse_key() on a character that cannot start a key ('['
//     followed by a newline, a third '[', ...); parse_key() asserts a key start, then
//     reports "expected bare key starting character" (upstream fix: marzer/tomlplusplus
//     PR #301);
//   - parse_array() calls parse_value() on '}' ("a = [}"); parse_value() asserts it is no
//     value terminator, then reports "could not determine value type".
// Debian's libtomlplusplus.so is built without assertions, so fetic reports those errors
// (tests/scenes/fuzz_regressions checks it with the real library). Only these two known
// assertions are let through here; every other toml++ assertion still aborts the fuzzer.

#include <cstdio>
#include <cstdlib>
#include <cstring>

inline void fetic_fuzz_toml_assert(bool ok, const char* expression, const char* file, int line) {
  if (ok) return;
  if (std::strcmp(expression, "is_bare_key_character(*cp) || is_string_delimiter(*cp)") == 0 ||
      std::strcmp(expression, "!is_value_terminator(*cp)") == 0)
    return;
  std::fprintf(stderr, "%s:%d: toml++ assertion failed: %s\n", file, line, expression);
  std::abort();
}

#define TOML_ASSERT(expr) fetic_fuzz_toml_assert(static_cast<bool>(expr), #expr, __FILE__, __LINE__)
