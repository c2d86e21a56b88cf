// The drawn surface carried by the simulated body (as games' soft bodies carry a fine render mesh in
// a coarse tetrahedral one): each vertex of the drawn icosphere is a fixed affine combination of the
// four nodes of one tetrahedron of the body's outer layer, x = Σ w_j x_j with Σ w_j = 1. The weights
// are the vertex's barycentric coordinates in that tetrahedron at rest; a vertex just outside the flat
// outer face (the sphere bulges past it) gets a slightly negative weight, which extends the affine map.
// A drawn vertex on a shared face has the same position in both neighbours, so the surface stays whole.
#pragma once

#include "core/scene/icosphere.h"
#include "core/bulk/tet_mesh.h"

#include <glm/vec4.hpp>

#include <vector>

namespace slime {

struct SurfaceEmbedding {
  std::vector<Tetrahedron> nodes;    // per drawn vertex, the four body nodes
  std::vector<glm::dvec4> weights;   // per drawn vertex, their weights (sum 1)
  // Per body surface triangle, the drawn vertices it carries (each drawn vertex in exactly one).
  std::vector<std::vector<std::uint32_t>> verticesOfSurfaceTriangle;
};

// Barycentric coordinates of p in tetrahedron abcd.
glm::dvec4 barycentric(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                       const glm::dvec3& d);

// Embeds `drawn`, an icosphere of a level ≥ the body's shell level about the same centre and radius,
// in the body `body` at rest (its triangles descend from the body's surface triangles: triangle j of
// level L lies in surface triangle j >> 2(L − s)).
SurfaceEmbedding embedSurface(const TetMesh& body, const TriangleMesh& drawn, int drawnLevel);

// x_drawn = Σ w_j x_body[j] for every drawn vertex.
void placeEmbedded(const SurfaceEmbedding& embedding, const std::vector<glm::dvec3>& body,
                   std::vector<glm::dvec3>& drawn);

}  // namespace slime
