#include "core/export/surface_mesh.h"

#include <glm/geometric.hpp>

namespace slime {

SurfaceMesh surfaceMeshOf(double time, const std::vector<glm::dvec3>& positions,
                          const std::vector<Triangle>& triangles) {
  SurfaceMesh mesh{time, positions, std::vector<glm::dvec3>(positions.size(), glm::dvec3(0.0)), triangles};
  for (const Triangle& t : triangles) {
    const glm::dvec3 weighted = glm::cross(positions[t.y] - positions[t.x], positions[t.z] - positions[t.x]);
    for (int corner = 0; corner < 3; ++corner) mesh.normals[t[corner]] += weighted;
  }
  for (glm::dvec3& n : mesh.normals) {
    const double length = glm::length(n);
    n = length > 0.0 ? n / length : glm::dvec3(0.0, 0.0, 1.0);  // a vertex on no triangle: up
  }
  return mesh;
}

}  // namespace slime
