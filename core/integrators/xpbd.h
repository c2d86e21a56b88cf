// Extended position-based dynamics: Macklin, Müller & Chentanez, "XPBD: Position-Based Simulation of
// Compliant Constrained Dynamics", MIG 2016, run as Macklin et al., "Small Steps in Physics
// Simulation", SCA 2019: many substeps h, one Gauss–Seidel pass per substep, λ reset every substep.
//   predict:  v += h g,  x* = x + h v
//   springs:  C = |x_ij| - l, α = 1/k, α̃ = α/h², damping γ = α β / h with β = k_d (the damper
//             of springs.h), Δλ = (-C - γ ∇C·(x - x_prev)) / ((1 + γ)(w_i + w_j) + α̃)
//             (eq. 26 of the 2016 paper with λ = 0 at the start of the pass)
//   volume:   C = V - V0, a hard constraint (α = 0): Δλ = -C / Σ w_i |∇_i V|², Δx_i = w_i ∇_i V Δλ
//   velocity: v = (x - x_prev)/h, then the floor contact of floor_contact.h.
// Unconditionally stable; with one pass per substep the springs act softer than k unless
// w k h² ≪ 1, so substeps should shrink with the subdivision level like an explicit step.
#pragma once

#include "core/geometry/particle_state.h"
#include "core/membrane/springs.h"

#include <glm/vec3.hpp>

#include <vector>

namespace slime {

struct XpbdModel {
  const SpringSet* springs = nullptr;
  double damping = 0.0;                                  // k_d, N·s/m
  const std::vector<glm::u32vec3>* triangles = nullptr;  // null: no volume constraint
  double restVolume = 0.0;
  glm::dvec3 gravity{0.0, 0.0, -9.81};
  double friction = 0.0;  // Coulomb μ of the floor, applied to positions (see xpbdSubstep)
};

struct XpbdScratch {
  std::vector<glm::dvec3> previousPositions;
  std::vector<glm::dvec3> volumeGradient;
};

// One substep of length h. The floor is a constraint on positions here, as in Macklin et al. 2019:
// a point the solve left below z = 0 is put on it, and its sliding over the substep, x - x_prev
// across the floor, is undone up to μ times that depth (all of it when it is smaller: static
// friction). Applying friction to the velocity alone, after the positions had already slid, let
// the contact patch creep, and the level-4 ball rolled 4 m in 40 s. The caller's velocity-level
// contact afterwards only removes what is left of the speed into the floor.
void xpbdSubstep(ParticleState& state, double h, const XpbdModel& model, XpbdScratch& scratch);

}  // namespace slime
