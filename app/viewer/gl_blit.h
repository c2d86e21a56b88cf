// Shows the ray tracer's image: uploads it, already sRGB-encoded to 8 bits (render/image/image_io.h, the
// bytes the PNG writer writes), to a GL texture and draws it over the whole viewport. Encoding on the
// CPU, not per fragment: under software GL (llvmpipe) the float texture with a pow per fragment
// cost 5.4 ms a frame at 734×564. The texture is reallocated only when the image size changes, so a
// steady frame allocates nothing.
#pragma once

#include "render/image/image.h"  // PixelRect

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace slime {

// The colour behind the image and the panels (where nothing is drawn yet, and under the column).
inline constexpr float kViewerBackground[4] = {0.08f, 0.08f, 0.09f, 1.0f};

class GlBlit {
 public:
  GlBlit();  // needs a current GL 3.3 core context; throws std::runtime_error if a shader fails
  ~GlBlit();
  GlBlit(const GlBlit&) = delete;
  GlBlit& operator=(const GlBlit&) = delete;

  // Copies the pixels `changed` (image pixels, top row first) of a width × height sRGB image, 4 bytes
  // a pixel (RGBA, top row first), into the texture; all of them when the size is new. Returns the
  // pixels copied.
  PixelRect upload(const std::vector<std::uint8_t>& rgba, int width, int height, PixelRect changed);

  // Draws, within `rect` of the framebuffer (pixels, top row 0), the background left of `left`
  // pixels and the texture over the rest: texel for pixel when the sizes agree, stretched bilinearly
  // when the image is smaller (the background everywhere before the first upload).
  void draw(glm::ivec2 framebufferSize, int left, PixelRect rect) const;

  // The framebuffer pixels that show the image pixels `changed` when drawn right of `left` (with the
  // bilinear stretch, every pixel a changed texel reaches).
  PixelRect framebufferPixels(PixelRect changed, glm::ivec2 framebufferSize, int left) const;

 private:
  unsigned program_ = 0;
  unsigned vertexArray_ = 0;
  unsigned texture_ = 0;
  glm::ivec2 textureSize_{0, 0};
};

}  // namespace slime
