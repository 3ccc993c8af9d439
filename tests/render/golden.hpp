#pragma once
// Golden-image comparison for the GL tests. A pixel differs when any channel differs by
// more than kChannelThreshold; an image matches when at most kMaxDifferingFraction of its
// pixels differ (docs/RENDERING.md: llvmpipe output is byte-identical run to run, the
// tolerance absorbs Mesa/LLVM versions re-rasterizing anti-aliased edges and glyphs).
// With FETIC_UPDATE_GOLDENS=1 the goldens are rewritten instead of compared. On failure
// the actual image and an amplified difference image go to FETIC_GOLDEN_OUTPUT_DIR.

#include <memory>
#include <string>

#include "render/gl_renderer.hpp"
#include "render/image.hpp"

namespace fetic::testing {

inline constexpr int kChannelThreshold = 24;
inline constexpr double kMaxDifferingFraction = 0.001;

struct Comparison {
  bool same_size = false;
  long differing = 0;     // pixels over the threshold
  double fraction = 1.0;  // differing / all
  int largest = 0;        // largest channel difference
  bool matches() const { return same_size && fraction <= kMaxDifferingFraction; }
};

Comparison compare(const render::Image& actual, const render::Image& expected);
// The golden dimmed to grey, differing pixels in red with 8x their difference.
render::Image amplified_difference(const render::Image& actual, const render::Image& expected);
render::Image read_png(const std::string& path);  // empty image when unreadable

// Compares with tests/golden/NAME.png (or rewrites it); returns a message on mismatch,
// empty when it matches.
std::string check_golden(const std::string& name, const render::Image& actual);

// One headless renderer per test process (EGL; fails the test when there is none).
render::GlRenderer& test_renderer();

}  // namespace fetic::testing
