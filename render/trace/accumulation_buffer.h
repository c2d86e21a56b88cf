// Progressive anti-aliasing: while nothing moves, each frame is traced once more with the pixel's
// sample moved to another point of it, and the frames are averaged, up to `target` samples a pixel
// (as interactive path tracers refine a still view). The points are the cells' centres of the n × n
// grid that render.spp = n² traces at once (Renderer), so 16 accumulated frames give the 16-spp
// snapshot's image up to float rounding. They come in pairs mirrored about the pixel's centre, so an
// average of an even count is centred like a one-sample frame: the image refines without shifting.
//
// The renderer traces; this buffer sums; the caller decides when to reset (the camera, the slime or
// a setting changed) and shows `average()` whenever add() says it is ready.
#pragma once

#include "render/image/image.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <vector>

namespace slime {

class AccumulationBuffer {
 public:
  // target: samples per pixel to reach, a square number (render.spp's rule); 1 turns refining off.
  explicit AccumulationBuffer(int target = 16);

  void reset() { samples_ = 0; }
  void setTarget(int target);
  int target() const { return target_; }
  int samples() const { return samples_; }
  bool converged() const { return samples_ >= target_; }

  // The point of the pixel the next frame should trace, in pixels from its top-left corner ((0.5,
  // 0.5) is its centre; Renderer::render's pixelOffset).
  glm::vec2 nextOffset() const { return offset(samples_); }
  // The k-th point of the sequence (k < target).
  glm::vec2 offset(int k) const;

  // Adds a frame traced at nextOffset(); a frame of another size restarts the sum. Returns true
  // when the mean is ready to show (an even count, or the target reached; until then the caller
  // keeps showing its one-sample frame): then `average` holds it
  // and, with `srgba`, its 8-bit sRGB bytes, 4 a pixel (as Renderer::render writes them).
  bool add(const Image& frame, Image& average, std::vector<std::uint8_t>* srgba = nullptr);

 private:
  int target_ = 16;
  int perAxis_ = 4;
  int samples_ = 0;
  int width_ = 0, height_ = 0;
  std::vector<glm::vec3> sum_;
};

}  // namespace slime
