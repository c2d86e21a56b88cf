// Springs on the mesh edges as flat arrays, and the seed's spring and damper forces (SPEC §3).
//   Hooke:  F_j = -k (|x_ij| - l_ij) x_ij/|x_ij|,           x_ij = p_j - p_i, F_i = -F_j
//   damper: F_j = -k_d ((v_ij · x_ij)/(x_ij · x_ij)) x_ij,  v_ij = v_j - v_i
//   series rule: a spring of length d is a chain of d/d_e elementary springs of stiffness k_e,
//   so k = k_e d_e / d (longer springs are softer).
// The damper is the relative velocity projected on the spring, times k_d in N·s/m (the unit of
// slime.damping). SPEC §3 writes a further 1/|x_ij|, which would make k_d a strain-rate coefficient
// in N·s and the skin's viscosity (k_d per spring spacing) double with every subdivision level;
// without it both the spring and the damper give a skin whose tension and viscosity do not
// depend on the level.
#pragma once

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace slime {

struct SpringSet {
  std::vector<glm::u32vec2> ends;    // vertex index pairs (i, j)
  std::vector<double> restLengths;   // l_ij, m
  std::vector<double> stiffnesses;   // k, N/m

  std::size_t size() const { return ends.size(); }
};

// k = k_e d_e / d.
double seriesStiffness(double elementaryStiffness, double elementaryLength, double length);

// Force on the second end j of one spring (the first end i feels the opposite).
glm::dvec3 springForce(const glm::dvec3& positionI, const glm::dvec3& positionJ, double restLength,
                       double stiffness);
glm::dvec3 damperForce(const glm::dvec3& positionI, const glm::dvec3& positionJ,
                       const glm::dvec3& velocityI, const glm::dvec3& velocityJ, double damping);

// Adds the Hooke and damper forces of every spring into `forces` (same length as positions).
void addSpringForces(const SpringSet& springs, const std::vector<glm::dvec3>& positions,
                     const std::vector<glm::dvec3>& velocities, double damping,
                     std::vector<glm::dvec3>& forces);

// The damper alone, integrated implicitly (operator splitting): a symmetric Gauss–Seidel sweep over
// the springs (forward, then backward), each solving its two-body damper exactly over h, so the relative velocity
// along x̂ decays as exp(-k_d (w_i + w_j) h). Never adds energy, so stable for any k_d and h;
// what symplectic_euler uses instead of the explicit damper, whose stable step shrinks 4x per level.
void dampSpringsImplicitly(const SpringSet& springs, const std::vector<glm::dvec3>& positions,
                           const std::vector<double>& inverseMasses, double damping, double h,
                           std::vector<glm::dvec3>& velocities);

// The same with each spring's factor (exp(-k_d (w_i + w_j) h/2) - 1) / (w_i + w_j) for one half
// sweep precomputed (springDampingDecays), because it only changes with h, k_d and the masses.
void springDampingDecays(const SpringSet& springs, const std::vector<double>& inverseMasses, double damping,
                         double h, std::vector<double>& decays);
void dampSpringsImplicitly(const SpringSet& springs, const std::vector<glm::dvec3>& positions,
                           const std::vector<double>& inverseMasses, const std::vector<double>& decays,
                           std::vector<glm::dvec3>& velocities);
// The same factors times (w_i, w_j): each end's share of the impulse, as the fused substep
// (damped_symplectic_euler.h) uses them.
void springDampingShares(const SpringSet& springs, const std::vector<double>& inverseMasses, double damping,
                         double h, std::vector<glm::dvec2>& shares);

// The edges reordered so that consecutive ones rarely share a vertex (greedy edge colouring, edges
// sorted by colour): sweeps that write both ends then carry no dependency from one spring to the
// next, which keeps the CPU's pipeline full. Deterministic.
std::vector<glm::u32vec2> orderedForIndependence(const std::vector<glm::u32vec2>& edges, std::size_t vertexCount);

// Where each maximal run of consecutive springs sharing no vertex starts, then springs.size(): the
// springs of one run can be swept in any order, or at once on threads, with the same result as in
// order. With orderedForIndependence each colour is (about) one run.
std::vector<std::size_t> independentSpringRuns(const std::vector<glm::u32vec2>& ends, std::size_t vertexCount);

// Springs on the unique edges of `triangles` (ordered for independence), rest lengths = current edge length / (1 + prestrain),
// stiffness by the series rule with d_e = the mean edge length.
SpringSet makeEdgeSprings(const std::vector<glm::dvec3>& positions,
                          const std::vector<glm::u32vec3>& triangles, double elementaryStiffness,
                          double prestrain);

}  // namespace slime
