// Shows the ray tracer's linear float image: uploads it to a GL texture and draws it over the whole
// viewport, converting linear RGB to sRGB in the fragment shader. The texture is reallocated only when
// the image size changes, so a steady frame allocates nothing.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <vector>

namespace slime {

class GlBlit {
 public:
  GlBlit();  // needs a current GL 3.3 core context; throws std::runtime_error if a shader fails
  ~GlBlit();
  GlBlit(const GlBlit&) = delete;
  GlBlit& operator=(const GlBlit&) = delete;

  // Copies width × height linear RGB pixels (top row first) into the texture.
  void upload(const std::vector<glm::vec3>& pixels, int width, int height);

  // Draws the texture stretched over a viewport of the given size (bilinear when it is smaller).
  void draw(glm::ivec2 viewportSize) const;

 private:
  unsigned program_ = 0;
  unsigned vertexArray_ = 0;
  unsigned texture_ = 0;
  glm::ivec2 textureSize_{0, 0};
};

}  // namespace slime
