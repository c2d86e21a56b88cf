// The slime's drawn surface as it leaves the program: positions (m), area-weighted vertex normals and
// triangles, one frame of it at a simulated time.
#pragma once

#include "core/geometry/icosphere.h"
#include "core/geometry/surface_view.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace slime {

struct SurfaceMesh {
  double time = 0.0;                 // s, simulated
  std::vector<glm::dvec3> positions;  // m
  std::vector<glm::dvec3> normals;    // unit, outward
  std::vector<Triangle> triangles;    // counter-clockwise seen from outside
  // The pieces, in order: piece k is the vertices from pieceVertexStarts[k] to the next start (or the
  // end) and the triangles likewise; each piece's triangles index only its own vertices.
  std::vector<std::uint32_t> pieceVertexStarts{0};
  std::vector<std::uint32_t> pieceTriangleStarts{0};
  std::size_t pieceCount() const { return pieceVertexStarts.size(); }
};

// Normals n_v = normalize(Σ over the triangles at v of (b − a) × (c − a)): each face's normal weighted
// by twice its area, as the renderer's slime geometry computes them.
SurfaceMesh surfaceMeshOf(double time, const std::vector<glm::dvec3>& positions,
                          const std::vector<Triangle>& triangles);
// The slime's pieces (Simulation::surfaces) in one mesh, piece after piece, each piece's triangles
// offset by the vertices before it: the pieces stay separate closed surfaces in the one file.
// Throws std::invalid_argument when `surfaces` is empty.
SurfaceMesh surfaceMeshOf(double time, std::span<const SurfaceView> surfaces);

}  // namespace slime
