// The volume enclosed by a closed, outward-wound triangle mesh and its gradient, and the pressure
// force that keeps the volume (the "pressure model" of Matyka & Ollila 2003: F_i = p ∇_i V).
//   V = Σ_t (a - o) · ((b - o) × (c - o)) / 6                 (divergence theorem, any origin o)
//   ∇_a V = Σ_{t ∋ a} (b × c) / 6                             (translation invariant on a closed mesh)
// The same gradient per edge: the edge (i, j) of the triangles (i, j, k) and (j, i, l) gives
// (p_i × p_j)/6 to ∇_k V and its opposite to ∇_l V, so one cross product per edge instead of three
// per triangle, and V = Σ_i p_i · ∇_i V / 3 (Euler's theorem: V is homogeneous of degree 3).
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <vector>

namespace slime {

double enclosedVolume(const std::vector<glm::dvec3>& positions,
                      const std::vector<glm::u32vec3>& triangles);

// Writes 6∇_i V for the first `count` vertices into `gradient` (resized to count; the triangles may
// use no other vertex); returns 6V. The sums about the first vertex, no division: the bulk body's
// volume projection takes them as they are.
double sixTimesVolumeGradient(const std::vector<glm::dvec3>& positions, const std::vector<glm::u32vec3>& triangles,
                              std::size_t count, std::vector<glm::dvec3>& gradient);

// Writes ∇_i V for every vertex into `gradient` (resized to positions.size()); returns V.
double volumeGradient(const std::vector<glm::dvec3>& positions,
                      const std::vector<glm::u32vec3>& triangles, std::vector<glm::dvec3>& gradient);

// For each edge (i, j) of `edges`, the third vertices (k, l) of its triangles (i, j, k) and (j, i, l)
// (in the triangles' winding). Throws std::invalid_argument unless every edge has exactly those two.
std::vector<glm::u32vec2> edgeOpposites(const std::vector<glm::u32vec2>& edges,
                                        const std::vector<glm::u32vec3>& triangles);

// Internal pressure of a nearly incompressible filling: p = restPressure + bulkModulus (1 - V/V0).
double fillPressure(double volume, double restVolume, double restPressure, double bulkModulus);

}  // namespace slime
