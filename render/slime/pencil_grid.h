// The slime's triangles binned by their direction as seen from one point, the apex (the light): a
// central projection about the apex maps every line through it to a point and every triangle to a
// triangle, so a segment on such a line (a shadow ray) can cross only the triangles binned in the
// grid cell of that point. Its crossings are then found exactly, each by the brute force's
// Möller–Trumbore test (brute_tracer.h) with the same operations, 8 triangles at a time: the grid
// only chooses which triangles to test. Any segment is answered correctly (its projection is a
// short 2-D segment whose cells are all visited); one through the apex visits one cell or two.
// Built anew for each shape and light (render setup, serial); read by every tracing thread. The
// primary rays, all through the eye, use one too (nearest()).
#pragma once

#include "render/trace/ray.h"
#include "render/slime/slime_geometry.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace slime {

class PencilGrid {
 public:
  // Bins `geometry`'s triangles by direction from `apex`. False, and an empty grid, when it cannot
  // serve: the analytic sphere, no triangles or more than 32,768 (a fine drawn surface: the build
  // would cost more than the queries save), or the apex within 1.2 bounding radii of the slime's
  // bounding sphere's centre (its view of the slime would be too wide for one projection plane).
  // With `facingApexOnly`, only the triangles whose outward side faces the apex are binned: from an
  // apex outside the slime a ray's first crossing is always into it, through one of those (nearest()
  // from the eye); crossings() then finds those alone.
  bool build(const SlimeGeometry& geometry, const glm::vec3& apex, bool facingApexOnly = false);
  void clear();
  bool ready() const { return ready_; }
  const glm::vec3& apex() const { return apex_; }
  std::size_t cellCount() const { return blockBegin_.empty() ? 0 : blockBegin_.size() - 1; }
  std::size_t entryCount() const { return entries_; }  // a triangle once for each cell it is binned in

  // Every crossing of the segment [ray.tNear, ray.tFar] with the slime's surface, nearest first (a
  // triangle once, even where the segment's cells share it). More than SegmentCrossings::kCapacity
  // crossings: count = kCapacity + 1 and the hits are the first kCapacity found, unsorted.
  void crossings(const Ray& ray, SegmentCrossings& out) const;
  // The nearest crossing in [ray.tNear, ray.tFar] (a primary ray from the apex, the eye), or an invalid hit.
  SlimeHit nearest(const Ray& ray) const;

 private:
  // Eight binned triangles, by lane: a corner and its two edges (b − a, c − a) as the brute force
  // computes them; an empty lane has zero edges (a zero determinant: never a hit).
  struct alignas(32) Block {
    float corner[3][8];
    float edge1[3][8];
    float edge2[3][8];
    std::uint32_t primitive[8];
  };
  // The projection of a point with w = (p − apex)·axis > 0.
  void project(const glm::vec3& point, float& u, float& v) const;
  // The lanes of `block` whose triangle `ray` crosses within [tNear, tFar] (bit i: lane i), with
  // their t, u and v when any.
  unsigned hitLanes(const Block& block, const Ray& ray, float* ts, float* us, float* vs) const;
  // Calls visit(block) for every block of the cells the segment's projection touches, until it returns false.
  template <typename Visit>
  void visitBlocks(const Ray& ray, Visit visit) const;

  bool ready_ = false;
  glm::vec3 apex_{0.0f};
  glm::vec3 axis_{0.0f, 0.0f, -1.0f}, across_{1.0f, 0.0f, 0.0f}, up_{0.0f, 1.0f, 0.0f};  // orthonormal
  float wMin_ = 0.0f, wMax_ = 0.0f;  // the bounding sphere's extent along the axis, with slack
  float u0_ = 0.0f, v0_ = 0.0f;      // the grid's corner in the projection plane
  float inverseCell_ = 0.0f;         // cells per unit of u and v (square cells)
  int columns_ = 0, rows_ = 0;
  std::vector<std::uint32_t> blockBegin_;  // cell c holds blocks_[blockBegin_[c], blockBegin_[c + 1])
  std::vector<Block> blocks_;
  std::size_t entries_ = 0;
  // The build's scratch, kept between frames.
  std::vector<float> vertexU_, vertexV_;
  std::vector<std::uint32_t> fill_;
  std::vector<std::uint8_t> binned_;
};

}  // namespace slime
