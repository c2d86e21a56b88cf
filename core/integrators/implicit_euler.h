// Backward (implicit) Euler after Baraff & Witkin, "Large Steps in Cloth Simulation", SIGGRAPH 1998:
// one Newton step of the linearised system, solved by conjugate gradients (Jacobi preconditioned),
//   (M - h ∂f/∂v - h² ∂f/∂x) Δv = h (f0 + h ∂f/∂x v0),   v = v0 + Δv,   x = x0 + h v.
// Jacobians: spring  ∂f_j/∂x_j = -k [x̂x̂ᵀ + max(0, 1 - l/|x|)(I - x̂x̂ᵀ)]   (the compressed-spring
//            term is dropped so the matrix stays definite, Choi & Ko 2002);
//            damper  ∂f_j/∂v_j = -k_d x̂x̂ᵀ;
//            fill    ∂f/∂x ≈ -(K/V0) ∇V ∇Vᵀ   (the pressure's own Hessian term p ∂²V/∂x² is left out).
// Kinematic points (w = 0) are filtered out of the solve (Δv = 0), as Baraff & Witkin's constraint filter.
#pragma once

#include "core/membrane/force_model.h"
#include "core/geometry/particle_state.h"

#include <array>
#include <vector>

namespace slime {

struct ImplicitEulerScratch {
  ForceScratch forceScratch;
  std::vector<glm::dvec3> accelerations;
  std::vector<std::array<double, 6>> springBlocks;  // h² ∂f/∂x + h ∂f/∂v per spring, negated (xx xy xz yy yz zz)
  std::vector<glm::dvec3> rhs, deltaV, residual, direction, product, preconditioned, diagonal;
};

struct ImplicitEulerOptions {
  double tolerance = 1e-4;   // relative residual |r| / |b| at which CG stops
  int maxIterations = 200;
};

// Returns the number of CG iterations used.
int implicitEulerStep(ParticleState& state, double dt, const ForceModel& model,
                      const ImplicitEulerOptions& options, ImplicitEulerScratch& scratch);

}  // namespace slime
