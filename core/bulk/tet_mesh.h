// The slime's body as a tetrahedral mesh of a ball, made by our own generator (no TetGen, no CGAL:
// their licences would decide the product's). K/2 + 1 concentric icosphere shells of one level s
// (K = 2^s) evenly spaced from R down to r_in = 0.5 / 0.5 / 0.64 / 0.64 R at resolutions 1 to 4 (until
// issue 27's branch mesh3 at R·k/K down to R/2, whose innermost triangles, of half the outer edge, set
// the explicit step limit; tet_mesh.cpp), joined by
// prisms over each shell triangle, each prism cut into three tetrahedra by the global vertex order (so
// neighbouring prisms cut their shared quad along the same diagonal and the mesh is conforming), and a
// centre point coned to the innermost shell. The shells fill the outer part of the radius, where the
// n = 2 modes, the floor and the hand deform the ball; the cone keeps the core's elements few and its
// highest frequency low. Refining s halves every spacing of the shells.
// Resolution 1: 85 nodes, 320 tetrahedra; 2: 487, 2,240; 3: 3,211, 16,640; 4: 23,059, 128,000.
//
// Node order: the outer shell first, in the icosphere's own vertex order (so node i < N_s is vertex i
// of every finer icosphere, which keeps those vertices), then the inner shells outwards-in, then the
// centre.
#pragma once

#include "core/geometry/icosphere.h"

#include <glm/ext/vector_uint4_sized.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace slime {

using Tetrahedron = glm::u32vec4;  // four node indices, positively oriented (det[b-a, c-a, d-a] > 0)

constexpr int kMinBodyResolution = 1;
constexpr int kMaxBodyResolution = 4;

struct TetMesh {
  std::vector<glm::dvec3> positions;
  std::vector<Tetrahedron> tetrahedra;
  std::vector<Triangle> surface;          // the outer shell's triangles, counter-clockwise from outside
  std::vector<std::uint32_t> outerPrism;  // per surface triangle, the first of its outermost tetrahedra
  int outerPrismSize = 3;                 // tetrahedra under each surface triangle in the outer layer
  int shellLevel = 1;                     // icosphere level s of every shell
  int shells = 1;                         // how many shells
  std::size_t surfaceNodes = 0;           // N_s: nodes 0..N_s-1 are the outer shell
};

// The ball of `radius` about `center` at resolution s in [kMinBodyResolution, kMaxBodyResolution].
TetMesh makeBallTetMesh(int resolution, double radius, const glm::dvec3& center);

// Signed volume of the tetrahedron abcd, det[b-a, c-a, d-a] / 6.
double tetrahedronVolume(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec3& d);

// Each undirected edge of the tetrahedra once, as (smaller index, larger index), sorted.
std::vector<glm::u32vec2> tetrahedronEdges(const std::vector<Tetrahedron>& tetrahedra);

}  // namespace slime
