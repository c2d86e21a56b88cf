// The triangle each primary ray meets first, found in object order before the tiles: every triangle
// that faces the eye is projected on the image, and each pixel whose sample point its box covers is
// tested with that pixel's own ray (render/trace/primary_view.h), eight pixels of a row against the
// triangle at once, by the brute force's Möller–Trumbore test in its order of operations (as the
// eye's grid tests eight triangles against one ray); the nearest hit is kept, at equal distances the
// lower triangle index (the eye's grid's order). A packet's primary hits are then read, not queried:
// a triangle is tested only against the few pixels it may cover, where a ray tested the triangles of
// its grid cell. From outside the slime a ray's first crossing is always into it, through a triangle
// that faces the eye, so those alone are tested (as the eye's grid bins them).
// It serves one sample per pixel at a known offset, with the eye well outside the slime (as the
// eye's grid: 1.2 bounding radii from its centre) and the whole slime in front of the camera; the
// eye's grid answers otherwise.
#pragma once

#include "core/geometry/camera.h"
#include "render/trace/primary_view.h"
#include "render/trace/ray.h"
#include "render/slime/slime_geometry.h"

#include <glm/vec2.hpp>

#include <cstdint>
#include <vector>

namespace slime {

class PrimaryVisibility {
 public:
  // The first hits of the primary rays through (column + offset.x, row + offset.y) of a width ×
  // height image; false (and nothing kept) where it cannot serve.
  bool build(const SlimeGeometry& geometry, const Camera& camera, int width, int height, glm::vec2 offset);
  void clear() { ready_ = false; }
  bool ready() const { return ready_; }

  // The first hits of the primary rays of pixels (column + i, row), i < count, that active[i] asks
  // for; an invalid hit where the ray meets no triangle.
  void hits8(int column, int row, int count, const bool* active, SlimeHit* hits) const;

  // Pixels in the region kept (where the slime's vertices project, with a margin) and their tests.
  std::size_t regionPixels() const { return t_.size(); }
  std::uint64_t pixelTests() const { return pixelTests_; }

 private:
  bool ready_ = false;
  int left_ = 0, top_ = 0, columns_ = 0, rows_ = 0;  // the region, in pixels of the image
  std::vector<float> t_, u_, v_;                      // per pixel of the region: the first hit
  std::vector<std::uint32_t> primitive_;              // its triangle, or kNoPrimitive
  std::vector<glm::vec2> projected_;                  // per vertex: its image point (column, row)
  std::vector<float> directions_[3];                  // the region's rays, by row (stride_ a row)
  int stride_ = 0;
  std::uint64_t pixelTests_ = 0;
};

}  // namespace slime
