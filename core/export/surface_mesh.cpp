#include "core/export/surface_mesh.h"

#include <glm/geometric.hpp>

#include <stdexcept>

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

SurfaceMesh surfaceMeshOf(double time, std::span<const SurfaceView> surfaces) {
  if (surfaces.empty()) throw std::invalid_argument("surfaceMeshOf: no surface; the slime has at least one piece");
  std::vector<glm::dvec3> positions;
  std::vector<Triangle> triangles;
  std::vector<std::uint32_t> vertexStarts, triangleStarts;
  for (const SurfaceView& surface : surfaces) {
    const Triangle offset(static_cast<std::uint32_t>(positions.size()));
    vertexStarts.push_back(static_cast<std::uint32_t>(positions.size()));
    triangleStarts.push_back(static_cast<std::uint32_t>(triangles.size()));
    positions.insert(positions.end(), surface.positions.begin(), surface.positions.end());
    for (const Triangle& t : surface.triangles) triangles.push_back(t + offset);
  }
  SurfaceMesh mesh = surfaceMeshOf(time, positions, triangles);
  mesh.pieceVertexStarts = std::move(vertexStarts);
  mesh.pieceTriangleStarts = std::move(triangleStarts);
  return mesh;
}

}  // namespace slime
