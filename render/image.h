// A linear-RGB float image, row-major, top row first: what the renderer writes and image_io reads.
#pragma once

#include <glm/vec3.hpp>

#include <cstddef>
#include <vector>

namespace slime {

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
