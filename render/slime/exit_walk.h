// Where rays inside the slime leave it through a supporting triangle, found without a query. Such a
// crossing is the ray's only crossing with a supporting triangle (after it the ray is above that
// triangle's plane, and the whole slime below: see SlimeGeometry::supporting), so a supporting
// triangle the ray is seen to cross ahead of its origin is the one the reversed query would find.
// The walk guesses it from a map of the surface seen from the centre of the mesh's bounds (the
// triangle in the direction where the ray leaves the bounding sphere, then the one in the direction
// where the ray meets the guess's plane), then steps over the triangles' edges towards the ray, each step one
// Möller–Trumbore test (the brute force's): it crosses the edge whose barycentric coordinate of the
// ray's crossing with the triangle's plane is the most negative, as a walk through a planar
// triangulation locates a point. It gives up (the caller then asks the intersector) after
// kMaxSteps, at a triangle that does not support the slime, or at a crossing outside the segment.
// Sixteen rays walk side by side (eight at a time with AVX2); each lane's result depends on its own
// ray alone.
#pragma once

#include "core/geometry/icosphere.h"
#include "render/trace/ray.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace slime {

struct SlimeGeometry;

class ExitWalk {
 public:
  static constexpr int kMaxSteps = 6;

  // The triangle across each edge of each triangle, for a new topology (none across an open or a
  // non-manifold edge).
  void connect(const std::vector<Triangle>& triangles);
  // This frame's shape: the triangles as the test reads them, and the map of directions.
  void map(const SlimeGeometry& geometry);

  // For each of kBatch rays that is active (origin inside the slime), its crossing with a supporting
  // triangle in [tNear, tFar], or an invalid hit where the walk gives up. `exitPoints[i]`: where ray
  // i leaves the bounding sphere (the first guess).
  static constexpr int kBatch = SlimeIntersector::kExitRays;  // 16 lanes with AVX-512, twice 8 with AVX2
  void supportingExits(const SlimeGeometry& geometry, const Ray* rays, const glm::vec3* exitPoints, const bool* active,
                       SlimeHit* hits) const;
  // The same for 8 rays, one after another whatever the build (the lanes' oracle in the tests).
  void supportingExits8OneByOne(const SlimeGeometry& geometry, const Ray* rays, const glm::vec3* exitPoints,
                                const bool* active, SlimeHit* hits) const {
    walkOneByOne(geometry, rays, exitPoints, active, hits);
  }

 private:
  // The cube map's cell in direction `direction` from the centre (any length, not zero).
  std::size_t cell(const glm::vec3& direction) const;
  // Connected and mapped for `geometry`'s triangles (else the walk finds nothing).
  bool ready(const SlimeGeometry& geometry) const;
  // 8 rays of supportingExits one after another (no AVX2), and N in lanes (8 with AVX2, 16 with
  // AVX-512): the same operations in the same order, so the same hits bit for bit.
  void walkOneByOne(const SlimeGeometry& geometry, const Ray* rays, const glm::vec3* exitPoints, const bool* active,
                    SlimeHit* hits) const;
  template <int N>
  void walkInLanes(const SlimeGeometry& geometry, const Ray* rays, const glm::vec3* exitPoints, const bool* active,
                   SlimeHit* hits) const;

  // Per triangle, this frame: a corner, its two edges (b − a, c − a), its unit normal.
  struct Corner {
    glm::vec3 a, edge1, edge2, normal;  // 12 floats: the lanes gather them by offset
  };
  std::vector<Corner> corners_;
  std::vector<std::uint32_t> neighbours_;  // 3 per triangle: across edge (b, c), (c, a), (a, b)
  std::vector<std::uint32_t> cells_;       // 6 faces × side² cells: a triangle, or kNoPrimitive
  int side_ = 0;
  glm::vec3 center_{0.0f};
};

}  // namespace slime
