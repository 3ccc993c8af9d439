#pragma once
// An RGBA image in memory, rows top to bottom, 8 bits per channel.

#include <cstdint>
#include <vector>

namespace fetic::render {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4

  const std::uint8_t* pixel(int x, int y) const {
    return rgba.data() + (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                          static_cast<std::size_t>(x)) *
                             4;
  }
};

}  // namespace fetic::render
