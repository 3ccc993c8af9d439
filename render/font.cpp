#include "render/font.hpp"

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <utility>
#include <vector>

#include <imgui.h>
#include <imgui_internal.h>

namespace fetic::render {
namespace {

// The characters the images use: Latin-1, Greek (lambda), dashes, the double bar of
// norms, superscripts (powers of ten), subscripts (x₁), arrows, minus and comparison signs.
constexpr ImWchar kGlyphRanges[] = {0x0020, 0x00FF, 0x0391, 0x03C9, 0x2013, 0x2016,
                                    0x2080, 0x2089, 0x2070, 0x207F, 0x2190, 0x2193,
                                    0x2212, 0x2212, 0x2264, 0x2265, 0};
constexpr float kRegularSizes[] = {9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 20, 22};
constexpr float kBoldSizes[] = {10, 11, 12, 13, 14, 15, 16, 18, 20, 22};

bool readable(const std::string& path) {
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (!file) return false;
  std::fclose(file);
  return true;
}

}  // namespace

struct FontAtlas::Impl {
  ImFontAtlas atlas;
  std::vector<std::pair<float, ImFont*>> regular, bold;
  ImDrawListSharedData shared;
  mutable ImDrawList scratch{&shared};

  ImFont* nearest(float size, bool want_bold) const {
    const auto& fonts = want_bold && !bold.empty() ? bold : regular;
    ImFont* best = fonts.front().second;
    float best_distance = FLT_MAX;
    for (const auto& [baked, font] : fonts)
      if (std::abs(baked - size) < best_distance) {
        best_distance = std::abs(baked - size);
        best = font;
      }
    return best;
  }
};

FontAtlas::FontAtlas(float largest, const std::string& regular_ttf, const std::string& bold_ttf)
    : impl_(std::make_unique<Impl>()) {
  // Larger sizes for large frames, a fifth apart, only as far as they will be used.
  std::vector<float> regular_sizes(std::begin(kRegularSizes), std::end(kRegularSizes));
  std::vector<float> bold_sizes(std::begin(kBoldSizes), std::end(kBoldSizes));
  for (float size = 26.0f; size <= std::min(largest, 64.0f) * 1.1f;
       size = std::round(size * 1.25f)) {
    regular_sizes.push_back(size);
    bold_sizes.push_back(size);
  }
  ImFontAtlas& atlas = impl_->atlas;
  atlas.TexDesiredWidth = 2048;
  ImFontConfig config;
  config.OversampleH = 2;
  config.OversampleV = 1;
  if (readable(regular_ttf)) {
    for (float size : regular_sizes)
      impl_->regular.emplace_back(
          size, atlas.AddFontFromFileTTF(regular_ttf.c_str(), size, &config, kGlyphRanges));
    if (readable(bold_ttf))
      for (float size : bold_sizes)
        impl_->bold.emplace_back(
            size, atlas.AddFontFromFileTTF(bold_ttf.c_str(), size, &config, kGlyphRanges));
    else
      note_ = bold_ttf + ": font not found; bold text uses the regular font";
  } else {
    // ImGui's built-in bitmap font (ProggyClean, 13 px): readable, no Greek or superscripts.
    ImFontConfig builtin;
    builtin.SizePixels = 13.0f;
    impl_->regular.emplace_back(13.0f, atlas.AddFontDefault(&builtin));
    note_ =
        regular_ttf + ": font not found (install fonts-dejavu-core); using ImGui's built-in font";
  }
  unsigned char* pixels = nullptr;
  atlas.GetTexDataAsRGBA32(&pixels, &width_, &height_);
  pixels_ = pixels;
  white_u_ = (atlas.TexUvWhitePixel.x);
  white_v_ = (atlas.TexUvWhitePixel.y);
}

FontAtlas::~FontAtlas() = default;

Point FontAtlas::measure(const std::string& text, float size, bool bold) const {
  const ImVec2 extent =
      impl_->nearest(size, bold)->CalcTextSizeA(size, FLT_MAX, 0.0f, text.c_str());
  return {extent.x, extent.y};
}

void FontAtlas::layout(const TextItem& item, std::vector<TexturedVertex>& out) const {
  if (item.text.empty() || item.color.a == 0) return;
  ImFont* font = impl_->nearest(item.size, item.bold);
  const Point extent = measure(item.text, item.size, item.bold);
  float dx = 0.0f, dy = 0.0f;
  if (item.h_align == HAlign::Center) dx = -0.5f * extent.x;
  if (item.h_align == HAlign::Right) dx = -extent.x;
  if (item.v_align == VAlign::Middle) dy = -0.5f * extent.y;
  if (item.v_align == VAlign::Bottom) dy = -extent.y;
  // Whole pixels keep glyphs crisp. A vertical label is laid out at the origin and turned.
  const ImVec2 origin =
      item.vertical ? ImVec2(std::round(dx), std::round(dy))
                    : ImVec2(std::round(item.anchor.x + dx), std::round(item.anchor.y + dy));
  ImDrawList& list = impl_->scratch;
  list._ResetForNewFrame();
  list.PushClipRect(ImVec2(-1e6f, -1e6f), ImVec2(1e6f, 1e6f));
  const ImU32 color = IM_COL32(item.color.r, item.color.g, item.color.b, item.color.a);
  list.AddText(font, item.size, origin, color, item.text.c_str());
  const float ax = std::round(item.anchor.x), ay = std::round(item.anchor.y);
  for (int i = 0; i < list.IdxBuffer.Size; ++i) {
    const ImDrawVert& v = list.VtxBuffer[list.IdxBuffer[i]];
    TexturedVertex out_vertex;
    out_vertex.x = item.vertical ? ax + v.pos.y : v.pos.x;
    out_vertex.y = item.vertical ? ay - v.pos.x : v.pos.y;
    out_vertex.u = v.uv.x;
    out_vertex.v = v.uv.y;
    out_vertex.rgba[0] = static_cast<std::uint8_t>(v.col >> IM_COL32_R_SHIFT);
    out_vertex.rgba[1] = static_cast<std::uint8_t>(v.col >> IM_COL32_G_SHIFT);
    out_vertex.rgba[2] = static_cast<std::uint8_t>(v.col >> IM_COL32_B_SHIFT);
    out_vertex.rgba[3] = static_cast<std::uint8_t>(v.col >> IM_COL32_A_SHIFT);
    out.push_back(out_vertex);
  }
}

}  // namespace fetic::render
