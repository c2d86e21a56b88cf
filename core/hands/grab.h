// Grabbing the slime: find the surface point nearest to where the user points, take the mass points
// within a radius of it, and drive them kinematically (inverse mass 0) towards a moving target,
// like the seed ("move the grabbed points to where the mouse points") but rate-limited so a jump of
// the mouse never injects an absurd velocity. Release restores their masses.
#pragma once

#include "core/geometry/icosphere.h"
#include "core/settings/settings.h"

#include <glm/vec3.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace slime {

// The fastest the grabbed points follow the grab target, m/s: a target that jumps (a mouse flick, a
// scenario's 1 m drag in 10 ms) is followed at this speed, never faster. Tests that drag quickly
// state their physical limit with it.
constexpr double kGrabSpeed = 1.5;

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

// How a hand holds what it grabs. A pinch (the default) shares kMouseStiffness among the nodes it takes:
// each of a big wad's nodes is held loosely (200 nodes, 2 N/m each), so the held material draws out with a
// strand pulled from it. A fist holds every node it takes by kFistNodeStiffness, ten times a resolution-2
// element's own stiffness (E L ≈ 3 · 1,200 Pa · 1.1 cm ≈ 40 N/m): the wad goes with the hand as one
// piece, its shape kept, and only the material outside it draws out (docs/physics.md, "The shape, drawn
// out"). Both pull with at most sim.handForce in all.
enum class Grip { Pinch, Fist };
constexpr double kFistNodeStiffness = 400.0;  // N/m, each held node

// A hand pressing the slime onto the floor squeezes the material under its fingertip out sideways, and
// the film left under it resists the more the thinner it gets (Stefan's squeeze film, F = 3π η R⁴ ḣ / 2h³:
// the Maxwell branch's η1 = μ1 τ = 430 Pa·s under a 1.5 cm pinch pushed at 0.23 m/s by 16 N leaves
// h ≈ 1.1 cm, 0.19 of the 5.8 cm body). The tetrahedra cannot squeeze out a film: driven flat onto
// the floor, the grabbed nodes slid over the nodes under them, which left the body folded for good
// (docs/physics.md, known limits; press_top_to_the_floor left it folded with a stop at 0.05, and at 0.10 on
// resolution 3, and came back from 0.15 up at resolutions 2 and 3: 0.25 keeps a margin above that).
// So each grabbed node is driven no lower than this fraction of the material under it at the grab (its
// height above the body's lowest node) above the floor.
constexpr double kPressStopFraction = 0.25;

struct MouseSpring {
  std::vector<std::uint32_t> nodes;
  std::vector<glm::dvec3> offsets;  // node − grab point at the grab
  std::vector<double> shares;       // of the stiffness and damping, sum 1 (a pinch's)
  std::vector<double> lowest;       // the lowest z each node is driven to, m (kPressStopFraction)
  glm::dvec3 target{0.0};
  glm::dvec3 targetVelocity{0.0};
  Grip grip = Grip::Pinch;
  double stiffness = kMouseStiffness;  // N/m: a pinch's whole, shared; a fist's on each node
  double damping = 0.0;             // N·s/m, as the stiffness
  double maxForce = SimSettings{}.handForce;  // N; Simulation::grab sets the run's sim.handForce
};

// The k-th node's part of the stiffness and damping: its share in a pinch, all of it in a fist.
inline double nodeShare(const MouseSpring& spring, std::size_t k) {
  return spring.grip == Grip::Fist ? 1.0 : spring.shares[k];
}

// Where the spring drives its k-th node, target + offset_k but no lower than lowest_k, and how fast
// that point moves (not down once it is at its stop).
inline glm::dvec3 springTarget(const MouseSpring& spring, std::size_t k) {
  glm::dvec3 target = spring.target + spring.offsets[k];
  target.z = std::max(target.z, spring.lowest[k]);
  return target;
}
inline glm::dvec3 springTargetVelocity(const MouseSpring& spring, std::size_t k) {
  glm::dvec3 velocity = spring.targetVelocity;
  if (spring.target.z + spring.offsets[k].z <= spring.lowest[k]) velocity.z = std::max(velocity.z, 0.0);
  return velocity;
}

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
