// PNG encoding is lossless and deterministic; the worker pool delivers every frame and
// reports a failing sink.

#include <catch2/catch.hpp>

#include <atomic>
#include <stdexcept>

#include <stb_image.h>

#include "render/png_writer.hpp"

using namespace fetic::render;

namespace {

Image gradient(int width, int height, int seed) {
  Image image{width, height,
              std::vector<std::uint8_t>(static_cast<std::size_t>(width * height * 4))};
  for (std::size_t i = 0; i < image.rgba.size(); ++i)
    image.rgba[i] = static_cast<std::uint8_t>((i * 7 + static_cast<std::size_t>(seed)) % 251);
  return image;
}

}  // namespace

TEST_CASE("a PNG decodes to the pixels it was made from, and the same pixels give the same bytes") {
  const Image image = gradient(37, 23, 1);
  const PngBytes png = encode_png(image);
  REQUIRE(png.size() > 8);
  int width = 0, height = 0, channels = 0;
  stbi_uc* decoded = stbi_load_from_memory(png.data(), static_cast<int>(png.size()), &width,
                                           &height, &channels, 4);
  REQUIRE(decoded != nullptr);
  CHECK(width == 37);
  CHECK(height == 23);
  CHECK(std::equal(image.rgba.begin(), image.rgba.end(), decoded));
  stbi_image_free(decoded);
  CHECK(encode_png(image) == png);
}

TEST_CASE("the encoder pool delivers every frame, on any number of threads") {
  for (int threads : {0, 1, 2, 3}) {
    std::atomic<int> delivered{0};
    PngEncoderPool pool(threads);
    for (int i = 0; i < 9; ++i)
      pool.submit(gradient(16, 16, i), [&](PngBytes png) {
        CHECK(png.size() > 8);
        ++delivered;
      });
    pool.finish();
    CHECK(delivered == 9);
  }
}

TEST_CASE("a failing sink stops the pool with its error") {
  PngEncoderPool pool(2);
  const auto failing = [](PngBytes) { throw std::runtime_error("frame_0003.png: disk full"); };
  bool thrown = false;
  try {
    for (int i = 0; i < 20; ++i)
      pool.submit(gradient(16, 16, i), failing);
    pool.finish();
  } catch (const std::runtime_error& error) {
    thrown = true;
    CHECK_THAT(error.what(), Catch::Contains("disk full"));
  }
  CHECK(thrown);
}
