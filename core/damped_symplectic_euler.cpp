#include "core/damped_symplectic_euler.h"

#include "core/floor_contact.h"
#include "core/volume.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace slime {
namespace {

// Pass 1: returns 6V and adds 6∇_i V into `sixGradient` (volume.h's formula, with the same origin).
double addSixVolumeGradient(const std::vector<glm::dvec3>& positions, const std::vector<glm::u32vec3>& triangles,
                            std::vector<glm::dvec3>& sixGradient) {
  const glm::dvec3 origin = positions[0];
  double sixTimesVolume = 0.0;
  for (const glm::u32vec3& t : triangles) {
    const glm::dvec3 a = positions[t.x] - origin, b = positions[t.y] - origin, c = positions[t.z] - origin;
    const glm::dvec3 bc = glm::cross(b, c);
    sixTimesVolume += glm::dot(a, bc);
    sixGradient[t.x] += bc;
    sixGradient[t.y] += glm::cross(c, a);
    sixGradient[t.z] += glm::cross(a, b);
  }
  return sixTimesVolume;
}

// Pass 2: Hooke's force F_j = -k (|x| - l) x/|x| on every spring (no damper: it is solved in pass 4),
// and what the damper needs of the same x_ij.
void addHookeForcesAndDamperGeometry(const SpringSet& springs, const std::vector<double>& dampingDecays,
                                     const std::vector<glm::dvec3>& positions, std::vector<glm::dvec3>& forces,
                                     std::vector<SpringDamperGeometry>& dampers) {
  const std::size_t count = springs.size();
  for (std::size_t s = 0; s < count; ++s) {
    const std::uint32_t i = springs.ends[s].x, j = springs.ends[s].y;
    const glm::dvec3 x = positions[j] - positions[i];
    const double lengthSquared = glm::dot(x, x);
    const double length = std::sqrt(lengthSquared);
    const double inverseLength = 1.0 / length;  // the one division per spring
    const double hooke = springs.stiffnesses[s] * (length - springs.restLengths[s]) * inverseLength;
    const glm::dvec3 forceOnJ = -hooke * x;
    forces[j] += forceOnJ;
    forces[i] -= forceOnJ;
    dampers[s] = {x, dampingDecays[s] * (inverseLength * inverseLength)};
  }
}

// Pass 4, one spring: its relative speed along x̂ decays exactly over the half substep, the impulse
// split by inverse mass (springs.cpp's dampOneSpring with the division done in pass 2).
inline void dampOneSpring(const glm::u32vec2& ends, const SpringDamperGeometry& damper,
                          const std::vector<double>& inverseMasses, std::vector<glm::dvec3>& velocities) {
  const std::uint32_t i = ends.x, j = ends.y;
  const double impulse = glm::dot(velocities[j] - velocities[i], damper.x) * damper.factorPerLengthSquared;
  velocities[j] += (impulse * inverseMasses[j]) * damper.x;
  velocities[i] -= (impulse * inverseMasses[i]) * damper.x;
}

}  // namespace

void dampedSymplecticEulerSubstep(ParticleState& state, double h, const DampedSymplecticEulerModel& model,
                                  DampedSymplecticEulerScratch& scratch) {
  const std::size_t count = state.size();
  if (count == 0) return;
  const SpringSet& springs = *model.springs;
  std::vector<glm::dvec3>& positions = state.positions;
  std::vector<glm::dvec3>& velocities = state.velocities;
  const std::vector<double>& inverseMasses = state.inverseMasses;
  // The accumulators stay zero between substeps (pass 3 clears what it reads), so only a new size
  // needs filling here.
  if (scratch.springForces.size() != count) scratch.springForces.assign(count, glm::dvec3(0.0));
  if (scratch.sixVolumeGradient.size() != count) scratch.sixVolumeGradient.assign(count, glm::dvec3(0.0));
  scratch.dampers.resize(springs.size());

  // 1. The fill: p = p0 + K (1 - V/V0) and ∇V, at the positions of the kick.
  const bool hasVolume = model.triangles && !model.triangles->empty();
  double pressureOverSix = 0.0;
  if (hasVolume) {
    const double volume = addSixVolumeGradient(positions, *model.triangles, scratch.sixVolumeGradient) / 6.0;
    pressureOverSix = fillPressure(volume, model.restVolume, model.restPressure, model.bulkModulus) / 6.0;
  }
  // 2. The springs.
  addHookeForcesAndDamperGeometry(springs, *model.dampingDecays, positions, scratch.springForces, scratch.dampers);
  // 3. Kick with a = w F + g (kinematic points keep their velocity).
  for (std::size_t i = 0; i < count; ++i) {
    glm::dvec3& springForce = scratch.springForces[i];
    glm::dvec3& sixGradient = scratch.sixVolumeGradient[i];
    const double w = inverseMasses[i];
    if (w != 0.0) velocities[i] += ((springForce + pressureOverSix * sixGradient) * w + model.gravity) * h;
    springForce = glm::dvec3(0.0);
    sixGradient = glm::dvec3(0.0);
  }
  // 4. The damper, implicitly: symmetric Gauss–Seidel, forward then backward, h/2 each (a one-way
  //    sweep is not a symmetric contraction and destabilised symplectic Euler).
  if (!model.dampingDecays->empty()) {
    const std::size_t springCount = springs.size();
    for (std::size_t s = 0; s < springCount; ++s)
      dampOneSpring(springs.ends[s], scratch.dampers[s], inverseMasses, velocities);
    for (std::size_t s = springCount; s-- > 0;)
      dampOneSpring(springs.ends[s], scratch.dampers[s], inverseMasses, velocities);
  }
  // 5. Drift, then put back on the floor whatever went through it.
  for (std::size_t i = 0; i < count; ++i) {
    positions[i] += velocities[i] * h;
    if (inverseMasses[i] != 0.0) resolveFloorContactAt(positions[i], velocities[i], model.friction);
  }
}

}  // namespace slime
