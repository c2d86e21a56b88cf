// The primary rays of a frame: Camera::rayDirection in float. The ray through image point (x, y) (in
// pixels from the top-left corner) points along forward + (2x/width − 1) right + (1 − 2y/height) up,
// with right and up scaled by the field of view, normalised. Every primary ray of a frame comes from
// primaryDirections8, so a pixel's ray is the same whichever packet it is traced in and whichever
// pass asks for it (the tiles, the primary visibility).
#pragma once

#include "core/geometry/camera.h"

#include <glm/vec3.hpp>

namespace slime {

struct PrimaryView {
  PrimaryView(const Camera& camera, int width, int height)
      : forward(camera.forward),
        right(camera.right * (camera.tanHalfFov * camera.aspect)),
        up(camera.up * camera.tanHalfFov),
        width(static_cast<float>(width)),
        height(static_cast<float>(height)) {}
  glm::vec3 forward, right, up;
  float width, height;
};

// The unit directions of the 8 primary rays through the points (column + i + offsetX, y), i = 0..7,
// by lane. The column is whole, so a pixel's point is float(column + i) + offsetX wherever its
// packet starts. Compiled once, in the render library (no fused multiply-adds, render/CMakeLists.txt):
// whoever asks gets the same rays.
void primaryDirections8(const PrimaryView& view, int column, float offsetX, float y, float* directionX,
                        float* directionY, float* directionZ);

}  // namespace slime
