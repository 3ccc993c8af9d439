// A screenshot of the whole window - panels, tooltips and the "Picked" window included -
// read from the default frame buffer after ImGui has drawn, before the swap (key W,
// script action `screenshot-window [FILE]`). `S` saves the picture alone.

#include <cstdio>
#include <filesystem>
#include <tuple>
#include <utility>

#define GL_GLEXT_PROTOTYPES
#include <GL/glcorearb.h>

#include "app/gui/app.hpp"
#include "app/render_output.hpp"

namespace fetic::app::gui {

void App::capture_window(int width, int height) {
  if (!window_shot_requested_) return;
  window_shot_requested_ = false;
  std::string path = pending_window_shot_;
  int number = -1;
  if (path.empty()) {
    std::tie(path, number) = numbered_name("fetic_window_%04d.png", window_shots_);
    window_shots_ = number + 1;
  } else if (std::filesystem::path(path).is_relative()) {
    path = (std::filesystem::path(args_.screenshot_dir) / path).string();
  }
  if (!output_folder_ready(path)) {
    if (number >= 0) give_back(window_shots_, number);
    return;
  }
  render::Image image;
  image.width = width;
  image.height = height;
  image.rgba.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, image.rgba.data());
  const std::size_t row = static_cast<std::size_t>(width) * 4;
  for (int top = 0, bottom = height - 1; top < bottom; ++top, --bottom)
    std::swap_ranges(image.rgba.begin() + static_cast<std::ptrdiff_t>(top * row),
                     image.rgba.begin() + static_cast<std::ptrdiff_t>((top + 1) * row),
                     image.rgba.begin() + static_cast<std::ptrdiff_t>(bottom * row));
  if (!screenshot_pool_) screenshot_pool_ = std::make_unique<render::PngEncoderPool>(1, 4);
  say("window screenshot " + path);
  screenshot_pool_->submit(std::move(image), [this, path, number](render::PngBytes png) {
    try {
      write_png_atomically(path, png);
      log_.write({{"event", "screenshot"}, {"path", path}, {"window", true}});
    } catch (const std::exception& error) {
      if (number >= 0) give_back(window_shots_, number);
      log_.output_lost(error.what());
    }
  });
}

}  // namespace fetic::app::gui
