#include "app/viewer/screenshot.h"

#include "app/viewer/gl.h"

#include <stb_image_write.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace slime {

void writeFramebufferPng(glm::ivec2 size, const std::string& path) {
  if (size.x <= 0 || size.y <= 0) throw std::runtime_error("cannot write " + path + ": the window is 0x0");
  const std::size_t rowBytes = static_cast<std::size_t>(size.x) * 3;
  std::vector<std::uint8_t> pixels(rowBytes * size.y);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, size.x, size.y, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
  // GL's first row is the bottom one; PNG's is the top one.
  std::vector<std::uint8_t> flipped(pixels.size());
  for (int row = 0; row < size.y; ++row)
    std::copy_n(pixels.begin() + static_cast<std::ptrdiff_t>(rowBytes * (size.y - 1 - row)), rowBytes,
                flipped.begin() + static_cast<std::ptrdiff_t>(rowBytes * row));
  if (!stbi_write_png(path.c_str(), size.x, size.y, 3, flipped.data(), static_cast<int>(rowBytes)))
    throw std::runtime_error("cannot write " + path);
}

}  // namespace slime
