#include "core/damped_symplectic_euler.h"

#include "core/floor_contact.h"
#include "core/volume.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace slime {
namespace {

// Pass 1: Hooke's force F_j = -k (|x| - l) x/|x| on every spring (no damper: it is solved in pass
// 4), the edge's share ±(p_i - o) × x_ij of 6∇V at its opposite vertices ((p_i - o) × (p_j - o)
// with the same origin o for every edge), and what the damper needs of the same x_ij.
template <bool kWithVolume>
void springPass(const SpringSet& springs, const glm::u32vec2* opposites, const std::vector<double>& dampingDecays,
                const std::vector<glm::dvec3>& positions, DampedSymplecticEulerScratch& scratch) {
  const std::size_t count = springs.size();
  const glm::u32vec2* ends = springs.ends.data();
  const double* stiffnesses = springs.stiffnesses.data();
  const double* restLengths = springs.restLengths.data();
  const double* decays = dampingDecays.data();
  glm::dvec3* forces = scratch.springForces.data();
  glm::dvec3* sixGradient = scratch.sixVolumeGradient.data();
  glm::dvec3* vectors = scratch.springVectors.data();
  double* damperFactors = scratch.damperFactors.data();
  const glm::dvec3 origin = positions[0];  // near the mesh, so the cross products stay well conditioned
  for (std::size_t s = 0; s < count; ++s) {
    const std::uint32_t i = ends[s].x, j = ends[s].y;
    const glm::dvec3 x = positions[j] - positions[i];
    const double length = std::sqrt(glm::dot(x, x));
    const double inverseLength = 1.0 / length;  // the one division per spring
    const double hooke = stiffnesses[s] * (length - restLengths[s]) * inverseLength;
    const glm::dvec3 forceOnJ = -hooke * x;
    forces[j] += forceOnJ;
    forces[i] -= forceOnJ;
    if constexpr (kWithVolume) {
      const glm::dvec3 share = glm::cross(positions[i] - origin, x);
      sixGradient[opposites[s].x] += share;
      sixGradient[opposites[s].y] -= share;
    }
    vectors[s] = x;
    damperFactors[s] = decays[s] * (inverseLength * inverseLength);
  }
}

// Pass 4, one spring: its relative speed along x̂ decays exactly over the half substep, the impulse
// split by inverse mass (springs.cpp's dampOneSpring with the division done in pass 1).
inline void dampOneSpring(const glm::u32vec2& ends, const glm::dvec3& x, double damperFactor,
                          const std::vector<double>& inverseMasses, std::vector<glm::dvec3>& velocities) {
  const std::uint32_t i = ends.x, j = ends.y;
  const double impulse = glm::dot(velocities[j] - velocities[i], x) * damperFactor;
  velocities[j] += (impulse * inverseMasses[j]) * x;
  velocities[i] -= (impulse * inverseMasses[i]) * x;
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
  scratch.springVectors.resize(springs.size());
  scratch.damperFactors.resize(springs.size());

  // 1. The springs, and the fill's ∇V, at the positions of the kick.
  const bool hasVolume = model.springOpposites != nullptr;
  if (hasVolume)
    springPass<true>(springs, model.springOpposites->data(), *model.dampingDecays, positions, scratch);
  else
    springPass<false>(springs, nullptr, *model.dampingDecays, positions, scratch);
  // 2. The fill pressure p = p0 + K (1 - V/V0), with 18 V = Σ (p_i - o) · 6∇_i V.
  double pressureOverSix = 0.0;
  if (hasVolume) {
    const glm::dvec3 origin = positions[0];
    double eighteenTimesVolume = 0.0;
    for (std::size_t i = 0; i < count; ++i)
      eighteenTimesVolume += glm::dot(positions[i] - origin, scratch.sixVolumeGradient[i]);
    pressureOverSix =
        fillPressure(eighteenTimesVolume / 18.0, model.restVolume, model.restPressure, model.bulkModulus) / 6.0;
  }
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
      dampOneSpring(springs.ends[s], scratch.springVectors[s], scratch.damperFactors[s], inverseMasses, velocities);
    for (std::size_t s = springCount; s-- > 0;)
      dampOneSpring(springs.ends[s], scratch.springVectors[s], scratch.damperFactors[s], inverseMasses, velocities);
  }
  // 5. Drift, then put back on the floor whatever went through it.
  for (std::size_t i = 0; i < count; ++i) {
    positions[i] += velocities[i] * h;
    if (inverseMasses[i] != 0.0) resolveFloorContactAt(positions[i], velocities[i], model.friction);
  }
}

}  // namespace slime
