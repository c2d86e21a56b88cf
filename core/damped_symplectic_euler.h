// The default integrator's whole substep in few passes over memory: symplectic Euler on the elastic
// forces (springs without their damper, fill pressure, gravity), the springs' damper solved
// implicitly between kick and drift, then the floor contact. The same mathematics as
//   computeAccelerations (damping 0) → symplecticEulerKick → dampSpringsImplicitly →
//   symplecticEulerDrift → resolveFloorContact
// and the same results up to floating-point rounding (tests/core/damped_symplectic_euler_test.cpp
// checks it), but fused: the split version makes about ten passes over vertices, springs and
// triangles per substep; this one makes seven lighter ones, and loads nothing it does not use (the elastic
// springs' velocities, the damper's positions and divisions).
//   1. triangles: 6V and 6∇_i V = Σ (b × c), accumulated unscaled;
//   2. springs:   x_ij, then Hooke's factor and the damper's factor/|x_ij|² (vectorised), then
//                 the Hooke forces;
//   3. vertices:  kick v += h (w (F + p ∇V) + g), clearing the accumulators for the next substep;
//   4. springs:   the damper's symmetric Gauss–Seidel sweep, forward then backward;
//   5. vertices:  drift x += v h and the floor contact.
#pragma once

#include "core/particle_state.h"
#include "core/springs.h"

#include <glm/vec3.hpp>

#include <vector>

namespace slime {

struct DampedSymplecticEulerModel {
  const SpringSet* springs = nullptr;
  const std::vector<double>* dampingDecays = nullptr;    // per spring, springDampingDecays for this h
  const std::vector<glm::u32vec2>* springOpposites = nullptr;  // edgeOpposites of the springs; null: no volume term
  double restVolume = 0.0;                               // V0, m^3
  double restPressure = 0.0;                             // p at V = V0, Pa
  double bulkModulus = 0.0;                              // K in p = p0 + K (1 - V/V0), Pa
  glm::dvec3 gravity{0.0, 0.0, -9.81};                   // m/s^2
  double friction = 0.0;                                 // Coulomb μ of the floor
};

// Four doubles (x, y, z, 0): a dvec3 padded to 32 bytes so that one vector instruction (AVX2)
// or two (SSE2) does what glm's dvec3 does in three scalar ones or a pair and a scalar. Stored
// in a struct because GCC drops a vector type's alignment when it is a template argument.
using Vector4 = double __attribute__((vector_size(32)));
struct alignas(32) PaddedVector {
  Vector4 lanes;
};

struct DampedSymplecticEulerScratch {
  std::vector<PaddedVector> positions, velocities;  // the state's, padded for the substep
  std::vector<PaddedVector> springForces;           // Σ Hooke forces per vertex (kept zero between substeps)
  std::vector<PaddedVector> sixVolumeGradient;      // 6 ∇_i V (kept zero between substeps)
  std::vector<PaddedVector> springVectors;          // per spring, x_ij = p_j - p_i at the kick
  std::vector<double> damperFactors;                // per spring, (decay - 1) / ((w_i + w_j) |x_ij|²)
};

// Advances every dynamic point (w > 0) by h; kinematic points (w = 0) drift with their own
// velocity and are left to the caller (as are the other integrators').
void dampedSymplecticEulerSubstep(ParticleState& state, double h, const DampedSymplecticEulerModel& model,
                                  DampedSymplecticEulerScratch& scratch);

}  // namespace slime
