// The drawn surface carried by the simulated body (as games' soft bodies carry a fine render mesh in
// a coarse tetrahedral one). Two maps from the body's nodes to each drawn vertex, both fixed linear
// combinations x = Σ φ_j x_j with Σ φ_j = 1, found once at rest:
//  - the element map: the vertex's barycentric coordinates in one tetrahedron of the body's outer
//    layer (a vertex just outside the flat outer face, where the sphere bulges past it, gets a slightly
//    negative weight, which extends the affine map). Piecewise affine: the drawn surface creases
//    wherever two elements' maps differ, i.e. along the body's element faces — facets under a pinch or
//    a press. The grab uses it to find the nodes under a drawn vertex.
//  - the smooth map, which places the drawn surface: a moving-least-squares fit (Lancaster & Šalkauskas
//    1981) of an affine map to the nodes around the vertex's rest point X, weighted by
//    W(|X_j − X| / h) = (1 − q²)³ (C², zero at q = 1), evaluated at X:
//        φ_j = W_j p(X)ᵀ M⁻¹ p(X_j),  p(Y) = (1, Y − X),  M = Σ_j W_j p(X_j) p(X_j)ᵀ.
//    It reproduces every affine motion exactly (so the rest shape, and any rigid motion, are exact) and
//    is as smooth in X as W: no creases along elements. Its support h = 2.5 body radial steps
//    (R / 2^s) holds about 30–40 nodes of the outer shells.
#pragma once

#include "core/geometry/icosphere.h"
#include "core/bulk/tet_mesh.h"

#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace slime {

struct SmoothTerm {
  double weight;       // φ_j
  std::uint32_t node;  // j
};

struct SurfaceEmbedding {
  std::vector<Tetrahedron> nodes;    // element map: per drawn vertex, the four body nodes
  std::vector<glm::dvec4> weights;   // element map: per drawn vertex, their weights (sum 1)
  // Smooth map: drawn vertex i takes terms [smoothStart[i], smoothStart[i + 1]).
  std::vector<std::uint32_t> smoothStart;
  std::vector<SmoothTerm> smoothTerms;
  // Per body surface triangle, the drawn vertices it carries (each drawn vertex in exactly one).
  std::vector<std::vector<std::uint32_t>> verticesOfSurfaceTriangle;
  // A smooth map still being fitted, a few vertices a step (a drawn surface made afresh: fitted at
  // once, it stalled the tear's frame by about 25 ms): the body's nodes it is fitted from, the drawn
  // vertices there, and the support. Until it is complete, placeEmbedded uses the element map.
  std::vector<glm::dvec3> fitNodes;
  std::vector<glm::dvec3> fitRest;
  double fitSupport = 0.0;
};

// MLS support radius in body radial steps R / 2^s (surface_embedding.h's header comment).
constexpr double kSmoothSupportSteps = 2.5;

// Barycentric coordinates of p in tetrahedron abcd.
glm::dvec4 barycentric(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                       const glm::dvec3& d);

// Embeds `drawn`, an icosphere of a level ≥ the body's shell level about the same centre and radius,
// in the body `body` at rest (its triangles descend from the body's surface triangles: triangle j of
// level L lies in surface triangle j >> 2(L − s)): the element map and the smooth map.
SurfaceEmbedding embedSurface(const TetMesh& body, const TriangleMesh& drawn, int drawnLevel);

// The element map alone of the same (nodes, weights, verticesOfSurfaceTriangle; no smooth map): for
// points the physics reads through the element map only, as the floor contact's (bulk_body.h).
SurfaceEmbedding embedByElements(const TetMesh& body, const TriangleMesh& drawn, int drawnLevel);

// The smooth map's terms for the points `rest` (at rest) over the body's nodes, support radius
// `support` (m; grown by 25 % at a time where fewer nodes than an affine fit needs surround a point).
void embedSmoothly(const TetMesh& body, const std::vector<glm::dvec3>& rest, double support,
                   SurfaceEmbedding& embedding);

// A smooth map fitted later from the nodes at `nodes` to the drawn vertices at `rest` (its terms are
// cleared; the element map must already hold every drawn vertex): continueSmoothFit fits `vertices`
// more drawn vertices and says whether the map is complete.
void beginSmoothFit(const std::vector<glm::dvec3>& nodes, const std::vector<glm::dvec3>& rest, double support,
                    SurfaceEmbedding& embedding);
bool continueSmoothFit(SurfaceEmbedding& embedding, std::size_t vertices);

// x_drawn = Σ φ_j x_body[j] for every drawn vertex, by the smooth map (by the element map when the
// smooth one is empty or still being fitted).
void placeEmbedded(const SurfaceEmbedding& embedding, const std::vector<glm::dvec3>& body,
                   std::vector<glm::dvec3>& drawn);

// The same by the element map alone (piecewise affine), for comparison.
void placeByElements(const SurfaceEmbedding& embedding, const std::vector<glm::dvec3>& body,
                     std::vector<glm::dvec3>& drawn);

}  // namespace slime
