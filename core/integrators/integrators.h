// Time integrators over a generic acceleration field a(x, v), as stateless free functions. Each
// advances positions and velocities of the dynamic points (w > 0) by one step dt; kinematic points
// (w = 0) move with their own velocity and are driven by the caller.
//   explicit_euler:   x = x0 + v0 dt + a dt²,  v = v0 + a dt           (the seed's update, SPEC §3)
//   symplectic_euler: v = v0 + a(x0, v0) dt,  x = x0 + v dt            (semi-implicit; stable for
//                     an undamped oscillator while dt < 2/ω, Hairer, Lubich & Wanner 2006)
//   rk4:              classical fourth-order Runge–Kutta on y = (x, v), y' = (v, a(x, v))
// The unconditionally stable methods are in implicit_euler.h and xpbd.h.
#pragma once

#include "core/membrane/force_model.h"
#include "core/geometry/particle_state.h"

#include <string>
#include <string_view>
#include <vector>

namespace slime {

enum class Integrator { ExplicitEuler, SymplecticEuler, Rk4, ImplicitEuler, Xpbd, Projective, ProjectiveMidpoint };

// "explicit_euler" ... "xpbd", "projective" (the bulk body's backward Euler by projective dynamics,
// core/bulk/projective_dynamics.h), "projective_midpoint" (its implicit midpoint rule on the same
// factorisation, with the sticky floor in the solve: kMidpointTheta there); parseIntegrator throws std::invalid_argument on an unknown name.
Integrator parseIntegrator(std::string_view name);
std::string integratorName(Integrator integrator);
std::vector<std::string> integratorNames();

struct IntegratorScratch {
  std::vector<glm::dvec3> accelerations, positions, velocities;
  std::vector<glm::dvec3> sumPositionRates, sumVelocityRates;  // rk4's weighted slopes
};

void explicitEulerStep(ParticleState& state, double dt, const AccelerationField& field,
                       IntegratorScratch& scratch);
void symplecticEulerStep(ParticleState& state, double dt, const AccelerationField& field,
                         IntegratorScratch& scratch);
// symplecticEulerStep = kick (v += a dt) then drift (x += v dt); split so a caller can treat some
// forces implicitly between the two (the Simulation damps springs there).
void symplecticEulerKick(ParticleState& state, double dt, const AccelerationField& field,
                         IntegratorScratch& scratch);
void symplecticEulerDrift(ParticleState& state, double dt);
void rk4Step(ParticleState& state, double dt, const AccelerationField& field, IntegratorScratch& scratch);

}  // namespace slime
