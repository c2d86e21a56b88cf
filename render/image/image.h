// A linear-RGB float image, row-major, top row first: what the renderer writes and image_io reads.
#pragma once

#include <glm/vec3.hpp>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace slime {

// The pixels [x0, x1) × [y0, y1) of an image or a framebuffer, the top row 0; empty when either side
// has no pixels.
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  // The smallest rectangle holding both (an empty one adds nothing).
  PixelRect unitedWith(const PixelRect& other) const {
    if (other.empty()) return *this;
    if (empty()) return other;
    return {std::min(x0, other.x0), std::min(y0, other.y0), std::max(x1, other.x1), std::max(y1, other.y1)};
  }
  PixelRect intersectedWith(const PixelRect& other) const {
    const PixelRect common{std::max(x0, other.x0), std::max(y0, other.y0), std::min(x1, other.x1), std::min(y1, other.y1)};
    return common.empty() ? PixelRect{} : common;
  }
  bool operator==(const PixelRect&) const = default;
};

struct Image {
  int width = 0;
  int height = 0;
  std::vector<glm::vec3> pixels;
  void resize(int w, int h) {
    width = w > 0 ? w : 0;
    height = h > 0 ? h : 0;
    pixels.resize(static_cast<std::size_t>(width) * height);
  }
  glm::vec3& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
  const glm::vec3& at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * width + x]; }
};

}  // namespace slime
