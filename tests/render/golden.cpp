#include "tests/render/golden.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <stb_image.h>

#include "render/egl_context.hpp"
#include "render/png_writer.hpp"

namespace fetic::testing {
namespace {

void write_png(const std::string& path, const render::Image& image) {
  const render::PngBytes png = render::encode_png(image);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  if (!out) throw std::runtime_error(path + ": cannot write");
}

}  // namespace

Comparison compare(const render::Image& actual, const render::Image& expected) {
  Comparison result;
  result.same_size = actual.width == expected.width && actual.height == expected.height &&
                     actual.rgba.size() == expected.rgba.size() && !actual.rgba.empty();
  if (!result.same_size) return result;
  const std::size_t pixels = actual.rgba.size() / 4;
  for (std::size_t p = 0; p < pixels; ++p) {
    int largest = 0;
    for (std::size_t c = 0; c < 4; ++c)
      largest = std::max(largest, std::abs(actual.rgba[4 * p + c] - expected.rgba[4 * p + c]));
    result.largest = std::max(result.largest, largest);
    if (largest > kChannelThreshold) ++result.differing;
  }
  result.fraction = static_cast<double>(result.differing) / static_cast<double>(pixels);
  return result;
}

render::Image amplified_difference(const render::Image& actual, const render::Image& expected) {
  render::Image diff = actual;
  if (actual.width != expected.width || actual.height != expected.height) return diff;
  for (std::size_t p = 0; p < actual.rgba.size(); p += 4) {
    int largest = 0, grey = 0;
    for (std::size_t c = 0; c < 3; ++c) {
      largest = std::max(largest, std::abs(actual.rgba[p + c] - expected.rgba[p + c]));
      grey += expected.rgba[p + c];
    }
    const auto faint = static_cast<std::uint8_t>(200 + grey / 3 / 5);  // the golden, dimmed
    const auto red = static_cast<std::uint8_t>(std::min(255, 8 * largest));
    diff.rgba[p] = largest > 0 ? 255 : faint;
    diff.rgba[p + 1] = largest > 0 ? static_cast<std::uint8_t>(255 - red) : faint;
    diff.rgba[p + 2] = largest > 0 ? static_cast<std::uint8_t>(255 - red) : faint;
    diff.rgba[p + 3] = 255;
  }
  return diff;
}

render::Image read_png(const std::string& path) {
  render::Image image;
  int channels = 0;
  stbi_uc* pixels = stbi_load(path.c_str(), &image.width, &image.height, &channels, 4);
  if (!pixels) return {};
  image.rgba.assign(pixels, pixels + static_cast<std::size_t>(image.width * image.height * 4));
  stbi_image_free(pixels);
  return image;
}

std::string check_golden(const std::string& name, const render::Image& actual) {
  const std::string golden = std::string(FETIC_GOLDEN_DIR) + "/" + name + ".png";
  const char* update = std::getenv("FETIC_UPDATE_GOLDENS");
  if (update && std::string(update) == "1") {
    write_png(golden, actual);
    return {};
  }
  const render::Image expected = read_png(golden);
  const Comparison comparison = compare(actual, expected);
  if (comparison.matches()) return {};
  const std::filesystem::path out = FETIC_GOLDEN_OUTPUT_DIR;
  std::filesystem::create_directories(out);
  write_png((out / (name + ".actual.png")).string(), actual);
  if (comparison.same_size)
    write_png((out / (name + ".diff.png")).string(), amplified_difference(actual, expected));
  if (expected.rgba.empty())
    return golden + ": missing or unreadable; the actual image is in " + out.string() +
           " (regenerate: scripts/update-goldens.sh)";
  if (!comparison.same_size)
    return golden + ": size " + std::to_string(expected.width) + "x" +
           std::to_string(expected.height) + " but the render is " + std::to_string(actual.width) +
           "x" + std::to_string(actual.height);
  return golden + ": " + std::to_string(comparison.differing) + " pixels (" +
         std::to_string(100.0 * comparison.fraction) + "%, allowed " +
         std::to_string(100.0 * kMaxDifferingFraction) + "%) differ by more than " +
         std::to_string(kChannelThreshold) + " levels (largest " +
         std::to_string(comparison.largest) + "); actual and 8x difference images in " +
         out.string();
}

render::GlRenderer& test_renderer() {
  static std::unique_ptr<render::GlContext> context = render::make_egl_context();
  static render::FontAtlas font;
  static render::GlRenderer renderer(*context, font);
  return renderer;
}

}  // namespace fetic::testing
