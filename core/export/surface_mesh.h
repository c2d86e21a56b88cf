// The slime's drawn surface as it leaves the program: positions (m), area-weighted vertex normals and
// triangles, one frame of it at a simulated time.
#pragma once

#include "core/geometry/icosphere.h"

#include <glm/vec3.hpp>

#include <vector>

namespace slime {

struct SurfaceMesh {
  double time = 0.0;                 // s, simulated
  std::vector<glm::dvec3> positions;  // m
  std::vector<glm::dvec3> normals;    // unit, outward
  std::vector<Triangle> triangles;    // counter-clockwise seen from outside
};

// Normals n_v = normalize(Σ over the triangles at v of (b − a) × (c − a)): each face's normal weighted
// by twice its area, as the renderer's slime geometry computes them.
SurfaceMesh surfaceMeshOf(double time, const std::vector<glm::dvec3>& positions,
                          const std::vector<Triangle>& triangles);

}  // namespace slime
