// Every force on the slime's mass points (SPEC §3 plus what a slime needs), as plain values:
//   F_i = m_i g + Σ_j (Hooke + damper) + p ∇_i V
// with the springs and damper of springs.h and the fill pressure of volume.h. Kinematic points
// (inverse mass 0) get zero acceleration: whoever drives them sets their motion.
#pragma once

#include "core/geometry/particle_state.h"
#include "core/membrane/springs.h"

#include <glm/vec3.hpp>

#include <functional>
#include <vector>

namespace slime {

struct ForceModel {
  const SpringSet* springs = nullptr;
  double damping = 0.0;                                  // k_d of the damper, N·s/m
  const std::vector<glm::u32vec3>* triangles = nullptr;  // null: no volume term
  double restVolume = 0.0;                               // V0, m^3
  double restPressure = 0.0;                             // p at V = V0, Pa (balances the skin's prestress)
  double bulkModulus = 0.0;                              // K in p = p0 + K (1 - V/V0), Pa
  glm::dvec3 gravity{0.0, 0.0, -9.81};                   // m/s^2
};

// Scratch buffers so that a force evaluation allocates nothing.
struct ForceScratch {
  std::vector<glm::dvec3> forces;
  std::vector<glm::dvec3> volumeGradient;
};

// a_i = F_i w_i (+ g for every dynamic point); returns the pressure used (0 without a volume term).
double computeAccelerations(const ForceModel& model, const std::vector<double>& inverseMasses,
                            const std::vector<glm::dvec3>& positions,
                            const std::vector<glm::dvec3>& velocities, ForceScratch& scratch,
                            std::vector<glm::dvec3>& accelerations);

// What the generic integrators call: fill `accelerations` for the given positions and velocities.
using AccelerationField = std::function<void(const std::vector<glm::dvec3>& positions,
                                             const std::vector<glm::dvec3>& velocities,
                                             std::vector<glm::dvec3>& accelerations)>;

}  // namespace slime
