// The seed's intersection algorithm, kept as the oracle: a ray is tested against the slime's bounding
// sphere, then against every triangle with Möller–Trumbore. Single-threaded use only (the renderer
// runs it serially); the analytic sphere of slime.shape=sphere is intersected exactly.
#pragma once

#include "render/trace/ray.h"
#include "render/slime/slime_geometry.h"

#include <cstdint>
#include <vector>

namespace slime {

class BruteTracer final : public SlimeIntersector {
 public:
  explicit BruteTracer(const SlimeGeometry& geometry) : geometry_(geometry) {}
  SlimeHit intersect(const Ray& ray) const override;
  void intersectNonSupporting8(const Ray* rays, const bool* active, SlimeHit* hits) const override;

 private:
  // The closest hit among `triangles`, named by their index or by primitives[index].
  SlimeHit closestTriangleHit(const Ray& ray, const std::vector<Triangle>& triangles,
                              const std::vector<std::uint32_t>* primitives) const;

  const SlimeGeometry& geometry_;
};

// Möller–Trumbore (1997): solves o + t d = (1−u−v) a + u b + v c by Cramer's rule. Both windings hit.
// Returns t (or +∞ on a miss) and writes the barycentrics u, v.
float intersectTriangle(const Ray& ray, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, float& u, float& v);

// The two roots of |o + t d − c|² = r² with t in [tNear, tFar], nearest first; +∞ on a miss.
float intersectSphere(const Ray& ray, const glm::vec3& center, float radius);

}  // namespace slime
