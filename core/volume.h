// The volume enclosed by a closed, outward-wound triangle mesh and its gradient, and the pressure
// force that keeps the volume (the "pressure model" of Matyka & Ollila 2003: F_i = p ∇_i V).
//   V = Σ_t (a - o) · ((b - o) × (c - o)) / 6                 (divergence theorem, any origin o)
//   ∇_a V = Σ_{t ∋ a} (b × c) / 6                             (translation invariant on a closed mesh)
#pragma once

#include <glm/vec3.hpp>

#include <vector>

namespace slime {

double enclosedVolume(const std::vector<glm::dvec3>& positions,
                      const std::vector<glm::u32vec3>& triangles);

// Writes ∇_i V for every vertex into `gradient` (resized to positions.size()); returns V.
double volumeGradient(const std::vector<glm::dvec3>& positions,
                      const std::vector<glm::u32vec3>& triangles, std::vector<glm::dvec3>& gradient);

// Internal pressure of a nearly incompressible filling: p = restPressure + bulkModulus (1 - V/V0).
double fillPressure(double volume, double restVolume, double restPressure, double bulkModulus);

}  // namespace slime
