// Contact with the floor plane z = 0: an inelastic, impulse-based contact with Coulomb friction.
// A point found below the floor (or on it and moving down) is put back on it, loses its downward
// velocity (normal impulse j_n = m max(0, -v_z)) and its sliding velocity shrinks by at most μ j_n / m
// (Coulomb's cone: static when |v_t| ≤ μ |Δv_n|, kinetic otherwise). Kinematic points (w = 0) are
// left alone. Applied after every (sub)step of every integrator, so no point is ever left below z = 0,
// and a point resting on the floor gets exactly zero velocity each step (no jitter).
#pragma once

#include "core/particle_state.h"

namespace slime {

// Returns how many points touched the floor.
std::size_t resolveFloorContact(ParticleState& state, double friction);

}  // namespace slime
