#pragma once
// The one pass over a scene's text that runs before toml++ sees it. toml++ 3.3 (Debian 12)
// cannot take every text safely, and fuzzing (fuzz/fuzz_scene) found three kinds it
// trips over:
// * a NUL byte (after '[' an internal assertion);
// * a non-ASCII character outside strings and comments (toml++ asks whether it is
//   whitespace, and for most code points that question reaches TOML_UNREACHABLE:
//   undefined behaviour); TOML allows such characters only in strings and comments;
// * nesting without a cap (toml++ recurses once per level of dotted keys, table headers,
//   arrays and inline tables: 40,000 levels overflow the stack).
// The guard reads TOML just far enough to find these - strings and comments as toml++
// delimits them, and the levels that keys, headers, arrays and inline tables open - and
// reports the first one with its line.

#include <string_view>

#include "scenes/scene_error.hpp"

namespace fetic::scenes {

// Deepest nesting accepted: tables (headers and dotted keys), arrays and inline tables
// together. A scene needs 4 ([[strut]] in the root, a table, an array such as `from`).
inline constexpr int kMaxNesting = 32;

// The first place where toml++ could not safely parse the text, or {0, ""}.
Problem toml_guard_problem(std::string_view text);

}  // namespace fetic::scenes
