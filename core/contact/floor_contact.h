// Contact with the floor plane z = 0: an inelastic, impulse-based contact with Coulomb friction.
// A point found below the floor (or on it and moving down) is put back on it, loses its downward
// velocity (normal impulse j_n = m max(0, -v_z)) and its sliding velocity shrinks by at most μ j_n / m
// (Coulomb's cone: static when |v_t| ≤ μ |Δv_n|, kinetic otherwise). Kinematic points (w = 0) are
// left alone. Applied after every (sub)step of every integrator, so no point is ever left below z = 0,
// and a point resting on the floor gets exactly zero velocity each step (no jitter).
#pragma once

#include "core/geometry/particle_state.h"

#include <algorithm>
#include <cmath>

namespace slime {

// One dynamic point's contact; true when it touched the floor. Inline so that integrators can
// apply it in their own last pass over the points.
// The floor stops a point's fall (normal impulse m max(0, −v_z)) and Coulomb's cone takes at most
// μ times that off its sliding speed (static when |v_t| ≤ μ |Δv_n|).
inline void stopFallWithFriction(glm::dvec3& velocity, double friction) {
  const double normalSpeedChange = std::max(0.0, -velocity.z);
  velocity.z = std::max(0.0, velocity.z);
  const double tangentialSpeed = std::hypot(velocity.x, velocity.y);
  const double frictionBudget = friction * normalSpeedChange;
  const double keep = tangentialSpeed <= frictionBudget ? 0.0 : 1.0 - frictionBudget / tangentialSpeed;
  velocity.x *= keep;
  velocity.y *= keep;
}

inline bool resolveFloorContactAt(glm::dvec3& position, glm::dvec3& velocity, double friction) {
  const bool below = position.z < 0.0;
  const bool pressingDown = position.z <= 0.0 && velocity.z < 0.0;
  if (!below && !pressingDown) return false;
  position.z = 0.0;
  stopFallWithFriction(velocity, friction);
  return true;
}

// Returns how many points touched the floor.
std::size_t resolveFloorContact(ParticleState& state, double friction);

// Rolling resistance: while a dynamic point lies on the floor (z ≤ 0, as resolveFloorContact leaves
// it), the body's turning about its centre of mass, ω = I⁻¹ L over the dynamic points, decays by
// exp(-rate·dt): each point loses (1 - exp(-rate·dt)) ω × (x - c). That is the mass-weighted
// projection of the velocities on rigid turning, scaled, so it keeps the momentum, only lowers the
// kinetic energy, and leaves stretching, sliding and falling alone. It stands for what the surface
// model lacks: a real slime's viscous bulk, which dissipates as it rocks or rolls on its flattened
// contact patch. Returns whether the body touched the floor.
// `touching` says the body is on the floor though no point lies at z ≤ 0 (the bulk slime's nodes sit
// just above it while its drawn surface touches).
bool dampTurningOnFloor(ParticleState& state, double rate, double dt, bool touching = false);

}  // namespace slime
