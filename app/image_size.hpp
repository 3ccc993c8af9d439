#pragma once
// The sides of a picture or a window in pixels: --size and a view file's "size" share them.

namespace fetic::app {

inline constexpr int kMinImageSide = 16;
inline constexpr int kMaxImageSide = 8192;

}  // namespace fetic::app
