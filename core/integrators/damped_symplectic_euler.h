// The default integrator's whole substep in few passes over memory: symplectic Euler on the elastic
// forces (springs without their damper, fill pressure, gravity), the springs' damper solved
// implicitly between two half kicks, then the drift and the floor contact. The same mathematics as
//   computeAccelerations (damping 0) → symplecticEulerKick (h/2) → dampSpringsImplicitly →
//   symplecticEulerKick (h/2, the same forces) → symplecticEulerDrift → resolveFloorContact
// Why between half kicks: there the velocity is leapfrog's synchronous one, whose step keeps
// ½ vᵀM v + ½ xᵀ(K - h²K M⁻¹K/4) x (Hairer, Lubich & Wanner 2006); that has no x·v cross term, so
// a damper that only slows relative motion can only lower it. After a whole kick the kept quantity
// has a cross term (h/2) xᵀK v that a damper can raise: with slime.damping ≥ 0.5 points beside
// the contact patch were pumped to 0.9 m/s (tests/core/simulation/simulation_test.cpp, StifferDamper).
// and the same results up to floating-point rounding (tests/core/integrators/damped_symplectic_euler_test.cpp
// checks it), but fused: the split version makes about ten passes over vertices, springs and
// triangles per substep, this one makes six, and loads nothing it does not use (the elastic
// springs' velocities, the damper's positions, masses and divisions):
//   0. vertices:  the state copied into padded arrays (PaddedVector below);
//   1. springs:   Hooke's force, each edge's share of 6∇V (volume.h: one cross product per edge,
//                 none per triangle), and x_ij and the damper's factors for the same x_ij;
//   2. vertices:  V = Σ p_i · ∇_i V / 3, hence the fill pressure p = p0 + K (1 - V/V0);
//   3. vertices:  half kick v += h/2 (w (F + p ∇V) + g), clearing the accumulators for the next
//                 substep but for the half kick, which it keeps;
//   4. springs:   the damper's symmetric Gauss–Seidel sweep, forward then backward;
//   5. vertices:  the kept half kick again, drift x += v h and the floor contact, back into the state.
// Where the CPU has AVX2 a build of it for AVX2 is chosen at run time; both builds give the same
// bits (the same operations in the same order, no fused multiply-add).
// From kParallelPointCount points on (level 6 and up) the passes run on TBB threads: over points in
// fixed chunks, the springs of pass 1 in kParallelSpringBlocks fixed blocks with an accumulator each,
// the sweeps run by run of springs that share no vertex (independentSpringRuns). The result then
// depends on the mesh size only, never on the number of threads.
#pragma once

#include "core/geometry/particle_state.h"
#include "core/membrane/springs.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstddef>
#include <vector>

namespace slime {

constexpr std::size_t kParallelPointCount = 20000;
constexpr std::size_t kParallelSpringBlocks = 2;
constexpr std::size_t kPointChunk = 4096;   // points per task, and per partial sum of the volume
constexpr std::size_t kSpringChunk = 4096;  // springs per task in the sweeps

struct DampedSymplecticEulerModel {
  const SpringSet* springs = nullptr;
  const std::vector<glm::dvec2>* dampingShares = nullptr;  // per spring, springDampingShares for this h
  const std::vector<glm::u32vec2>* springOpposites =
      nullptr;                          // edgeOpposites of the springs; null: no volume term
  double restVolume = 0.0;              // V0, m^3
  double restPressure = 0.0;            // p at V = V0, Pa
  double bulkModulus = 0.0;             // K in p = p0 + K (1 - V/V0), Pa
  glm::dvec3 gravity{0.0, 0.0, -9.81};  // m/s^2
  double friction = 0.0;                // Coulomb μ of the floor
  const std::vector<std::size_t>* independentRuns = nullptr;  // independentSpringRuns; null: never on threads
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
  std::vector<glm::dvec2> damperFactors;  // per spring, (decay - 1) (w_i, w_j) / ((w_i + w_j) |x_ij|²)
  std::vector<double> volumeParts;        // 18 V per chunk of points
};

// Advances every dynamic point (w > 0) by h; kinematic points (w = 0) drift with their own
// velocity and are left to the caller (as are the other integrators').
void dampedSymplecticEulerSubstep(ParticleState& state, double h, const DampedSymplecticEulerModel& model,
                                  DampedSymplecticEulerScratch& scratch);

}  // namespace slime
