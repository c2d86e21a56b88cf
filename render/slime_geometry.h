// The slime as the renderer sees it: float vertex positions (padded for Embree), per-frame vertex
// normals, triangles, a bounding sphere for culling, and the analytic sphere of slime.shape=sphere.
// Shared by both intersection back-ends and by shading, so only the intersection differs.
#pragma once

#include "core/icosphere.h"
#include "render/ray.h"

#include <glm/vec3.hpp>

#include <vector>

namespace slime {

struct SlimeGeometry {
  std::vector<glm::vec3> positions;  // one extra zero vertex at the end: Embree reads 16 bytes past the last
  std::vector<glm::vec3> normals;    // area-weighted vertex normals of the current (deformed) mesh
  std::vector<Triangle> triangles;
  glm::vec3 boundCenter{0.0f};       // a sphere that contains every vertex
  float boundRadius = 0.0f;
  bool analyticSphere = false;       // slime.shape == sphere: the exact sphere below replaces the mesh
  glm::vec3 sphereCenter{0.0f};
  float sphereRadius = 0.0f;

  std::size_t vertexCount() const { return positions.empty() ? 0 : positions.size() - 1; }

  // Copies the physics state; recomputes normals and bounds. Returns true when the topology changed.
  bool update(const std::vector<glm::dvec3>& newPositions, const std::vector<Triangle>& newTriangles);

  // Makes the analytic sphere (centre of the vertices, `radius`) the slime, or the mesh again.
  void setAnalyticSphere(bool enabled, float radius);

  // Whether the segment [tNear, tFar] of the ray can touch the bounding sphere (slack included).
  bool mayHit(const Ray& ray) const;

  // Unit geometric normal (outward) at a hit point.
  glm::vec3 geometricNormal(const SlimeHit& hit, const glm::vec3& point) const;
  // Unit shading normal: interpolated vertex normals when smooth, else the geometric normal.
  glm::vec3 shadingNormal(const SlimeHit& hit, const glm::vec3& point, bool smooth) const;
};

}  // namespace slime
