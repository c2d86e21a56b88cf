#include "core/integrators/integrators.h"

#include <stdexcept>

namespace slime {

Integrator parseIntegrator(std::string_view name) {
  if (name == "explicit_euler") return Integrator::ExplicitEuler;
  if (name == "symplectic_euler") return Integrator::SymplecticEuler;
  if (name == "rk4") return Integrator::Rk4;
  if (name == "implicit_euler") return Integrator::ImplicitEuler;
  if (name == "xpbd") return Integrator::Xpbd;
  if (name == "projective") return Integrator::Projective;
  if (name == "projective_midpoint") return Integrator::ProjectiveMidpoint;
  throw std::invalid_argument("unknown integrator \"" + std::string(name) +
                              "\" (explicit_euler, symplectic_euler, rk4, implicit_euler, xpbd, projective, "
                              "projective_midpoint)");
}

std::string integratorName(Integrator integrator) {
  switch (integrator) {
    case Integrator::ExplicitEuler: return "explicit_euler";
    case Integrator::SymplecticEuler: return "symplectic_euler";
    case Integrator::Rk4: return "rk4";
    case Integrator::ImplicitEuler: return "implicit_euler";
    case Integrator::Xpbd: return "xpbd";
    case Integrator::Projective: return "projective";
    case Integrator::ProjectiveMidpoint: return "projective_midpoint";
  }
  return "unknown";
}

std::vector<std::string> integratorNames() {
  return {"explicit_euler", "symplectic_euler", "rk4", "implicit_euler", "xpbd", "projective", "projective_midpoint"};
}

void explicitEulerStep(ParticleState& state, double dt, const AccelerationField& field,
                       IntegratorScratch& scratch) {
  field(state.positions, state.velocities, scratch.accelerations);
  for (std::size_t i = 0; i < state.size(); ++i) {
    const glm::dvec3& a = scratch.accelerations[i];
    state.positions[i] += state.velocities[i] * dt + a * (dt * dt);
    state.velocities[i] += a * dt;
  }
}

void symplecticEulerStep(ParticleState& state, double dt, const AccelerationField& field,
                         IntegratorScratch& scratch) {
  field(state.positions, state.velocities, scratch.accelerations);
  for (std::size_t i = 0; i < state.size(); ++i) {
    state.velocities[i] += scratch.accelerations[i] * dt;
    state.positions[i] += state.velocities[i] * dt;
  }
}

void symplecticEulerKick(ParticleState& state, double dt, const AccelerationField& field,
                         IntegratorScratch& scratch) {
  field(state.positions, state.velocities, scratch.accelerations);
  for (std::size_t i = 0; i < state.size(); ++i) state.velocities[i] += scratch.accelerations[i] * dt;
}

void symplecticEulerDrift(ParticleState& state, double dt) {
  for (std::size_t i = 0; i < state.size(); ++i) state.positions[i] += state.velocities[i] * dt;
}

void rk4Step(ParticleState& state, double dt, const AccelerationField& field, IntegratorScratch& scratch) {
  const std::size_t count = state.size();
  const std::vector<glm::dvec3>& x0 = state.positions;
  const std::vector<glm::dvec3>& v0 = state.velocities;
  std::vector<glm::dvec3>& a = scratch.accelerations;
  std::vector<glm::dvec3>& x = scratch.positions;
  std::vector<glm::dvec3>& v = scratch.velocities;
  std::vector<glm::dvec3>& sumX = scratch.sumPositionRates;
  std::vector<glm::dvec3>& sumV = scratch.sumVelocityRates;
  x.resize(count);
  v.resize(count);
  sumX.assign(count, glm::dvec3(0.0));
  sumV.assign(count, glm::dvec3(0.0));
  // Stage k (weight 1, 2, 2, 1) evaluated at y0 + c_k dt · slope_{k-1}, c = (0, 1/2, 1/2, 1).
  const double weights[4] = {1.0, 2.0, 2.0, 1.0};
  const double nextOffsets[4] = {0.5, 0.5, 1.0, 0.0};
  field(x0, v0, a);
  for (std::size_t i = 0; i < count; ++i) {
    x[i] = x0[i];
    v[i] = v0[i];
  }
  for (int stage = 0; stage < 4; ++stage) {
    if (stage > 0) field(x, v, a);
    const double offset = nextOffsets[stage] * dt;
    for (std::size_t i = 0; i < count; ++i) {
      const glm::dvec3 positionRate = v[i], velocityRate = a[i];
      sumX[i] += weights[stage] * positionRate;
      sumV[i] += weights[stage] * velocityRate;
      x[i] = x0[i] + offset * positionRate;
      v[i] = v0[i] + offset * velocityRate;
    }
  }
  for (std::size_t i = 0; i < count; ++i) {
    state.positions[i] += sumX[i] * (dt / 6.0);
    state.velocities[i] += sumV[i] * (dt / 6.0);
  }
}

}  // namespace slime
