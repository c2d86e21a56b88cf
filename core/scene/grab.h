// Grabbing the slime: find the surface point nearest to where the user points, take the mass points
// within a radius of it, and drive them kinematically (inverse mass 0) towards a moving target,
// like the seed ("move the grabbed points to where the mouse points") but rate-limited so a jump of
// the mouse never injects an absurd velocity. Release restores their masses.
#pragma once

#include "core/scene/icosphere.h"
#include "core/settings/settings.h"

#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

namespace slime {

// The fastest the grabbed points follow the grab target, m/s: a target that jumps (a mouse flick, a
// scenario's 1 m drag in 10 ms) is followed at this speed, never faster. Tests that drag quickly
// state their physical limit with it.
constexpr double kGrabSpeed = 1.5;

// Closest point to p on triangle abc (Ericson, Real-Time Collision Detection, 2005, §5.1.5).
glm::dvec3 closestPointOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                  const glm::dvec3& c);

// The point of the mesh surface nearest to `point` (brute force over the triangles).
glm::dvec3 nearestSurfacePoint(const std::vector<glm::dvec3>& positions,
                               const std::vector<Triangle>& triangles, const glm::dvec3& point);

// Indices (ascending) of the positions within `radius` of `center`.
std::vector<std::uint32_t> pointsWithinRadius(const std::vector<glm::dvec3>& positions,
                                              const glm::dvec3& center, double radius);

// The bulk slime's grab and press: a mouse spring, a compliant constraint with the force limit of a
// hand. Each grabbed node i is pulled towards target + offset_i by its share of the stiffness, with a
// damper on its velocity relative to the target's; the sum of these forces is scaled down to at most
// maxForce, the setting sim.handForce (one source: its default, SimSettings and assets/default.json;
// 16 N). A slow pull lets the material flow into a neck; a fast one takes the body along.
constexpr double kMouseStiffness = 400.0;  // N/m, the whole pinch
constexpr double kMouseDampingRatio = 0.7; // of the pinch's critical damping 2√(k m)

struct MouseSpring {
  std::vector<std::uint32_t> nodes;
  std::vector<glm::dvec3> offsets;  // node − grab point at the grab
  std::vector<double> shares;       // of the stiffness and damping, sum 1
  glm::dvec3 target{0.0};
  glm::dvec3 targetVelocity{0.0};
  double stiffness = kMouseStiffness;
  double damping = 0.0;             // N·s/m
  double maxForce = SimSettings{}.handForce;  // N; Simulation::grab sets the run's sim.handForce
};

// Adds the mouse spring's forces to `forces`; returns the total force the hand exerts, N.
glm::dvec3 addMouseSpringForces(const MouseSpring& spring, const std::vector<glm::dvec3>& positions,
                                const std::vector<glm::dvec3>& velocities, std::vector<glm::dvec3>& forces);

// The mouse spring by backward Euler node by node, m (v' − v)/h = s_k (k (t_k − x − h v') + c (v_t − v')),
// the whole hand's force limited to maxForce; changes the velocities of the held nodes with w > 0.
// Returns the hand's force, N. (The projective solver applies one hand so; this is the second hand's.)
glm::dvec3 applyMouseSpringImplicitly(const MouseSpring& spring, const std::vector<glm::dvec3>& positions,
                                      const std::vector<double>& inverseMasses, double h,
                                      std::vector<glm::dvec3>& velocities);

// Moves `anchor` towards `target` by at most maxStep (m).
glm::dvec3 stepTowards(const glm::dvec3& anchor, const glm::dvec3& target, double maxStep);

}  // namespace slime
