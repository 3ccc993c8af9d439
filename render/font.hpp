#pragma once
// Text through Dear ImGui's font machinery, on the CPU: DejaVu Sans (regular and bold)
// baked by ImGui's font atlas at the sizes the images use, and text items turned into
// glyph triangles by ImGui's ImDrawList. When the TTF files are missing, ImGui's built-in
// font is used instead and note() says so.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "render/draw_list.hpp"

namespace fetic::render {

struct TexturedVertex {
  float x = 0, y = 0;  // pixels
  float u = 0, v = 0;  // atlas coordinates
  std::uint8_t rgba[4] = {0, 0, 0, 0};
};

// Where fonts-dejavu-core puts its files.
inline constexpr const char* kDejaVuSans = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
inline constexpr const char* kDejaVuSansBold =
    "/usr/share/fonts/truetype/dejavu/DejaVuSans-Bold.ttf";

class FontAtlas {
 public:
  // Sizes up to 22 pixels are always baked; `largest` (the largest text a frame will
  // use) adds larger ones, up to 64 pixels (beyond, the nearest is scaled).
  explicit FontAtlas(float largest = 22.0f, const std::string& regular_ttf = kDejaVuSans,
                     const std::string& bold_ttf = kDejaVuSansBold);
  ~FontAtlas();
  FontAtlas(const FontAtlas&) = delete;
  FontAtlas& operator=(const FontAtlas&) = delete;

  // Empty, or why the built-in font is used (naming the missing file).
  const std::string& note() const { return note_; }
  int texture_width() const { return width_; }
  int texture_height() const { return height_; }
  const std::uint8_t* texture_rgba() const { return pixels_; }
  // Atlas coordinates of an opaque white texel: solid triangles sample it.
  float white_u() const { return white_u_; }
  float white_v() const { return white_v_; }

  // Appends the glyph triangles (3 vertices each) of `item`.
  void layout(const TextItem& item, std::vector<TexturedVertex>& out) const;
  // Width and height of a text line.
  Point measure(const std::string& text, float size, bool bold) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string note_;
  int width_ = 0, height_ = 0;
  const std::uint8_t* pixels_ = nullptr;
  float white_u_ = 0, white_v_ = 0;
};

}  // namespace fetic::render
