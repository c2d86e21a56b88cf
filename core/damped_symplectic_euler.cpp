#include "core/damped_symplectic_euler.h"

#include <cmath>
#include <glm/geometric.hpp>

#include "core/floor_contact.h"
#include "core/volume.h"

// The helpers below take and return 32-byte vectors; GCC warns that their ABI differs with and
// without AVX, which does not matter for functions that are always inlined in this file.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace slime {
namespace {

[[gnu::always_inline]] inline Vector4 pad(const glm::dvec3& v) { return Vector4{v.x, v.y, v.z, 0.0}; }
[[gnu::always_inline]] inline glm::dvec3 unpad(const Vector4& v) { return {v[0], v[1], v[2]}; }
[[gnu::always_inline]] inline Vector4 broadcast(double s) { return Vector4{s, s, s, s}; }
// glm::dot's order, ((x + y) + z), so the result does not depend on the vector width.
[[gnu::always_inline]] inline double dot(const Vector4& a, const Vector4& b) {
  const Vector4 product = a * b;
  return (product[0] + product[1]) + product[2];
}
// a × b = a.yzx b.zxy - a.zxy b.yzx (the fourth lane stays 0).
[[gnu::always_inline]] inline Vector4 cross(const Vector4& a, const Vector4& b) {
  const Vector4 aYzx = __builtin_shufflevector(a, a, 1, 2, 0, 3);
  const Vector4 aZxy = __builtin_shufflevector(a, a, 2, 0, 1, 3);
  const Vector4 bYzx = __builtin_shufflevector(b, b, 1, 2, 0, 3);
  const Vector4 bZxy = __builtin_shufflevector(b, b, 2, 0, 1, 3);
  return aYzx * bZxy - aZxy * bYzx;
}

// Pass 1: Hooke's force F_j = -k (|x| - l) x/|x| on every spring (no damper: it is solved in pass
// 4), the edge's share ±(p_i - o) × x_ij of 6∇V at its opposite vertices ((p_i - o) × (p_j - o)
// with the same origin o for every edge), and what the damper needs of the same x_ij.
template <bool kWithVolume>
[[gnu::always_inline]] inline void springPass(const SpringSet& springs, const glm::u32vec2* opposites,
                                              const double* decays, const double* inverseMasses,
                                              DampedSymplecticEulerScratch& scratch) {
  const std::size_t count = springs.size();
  const glm::u32vec2* ends = springs.ends.data();
  const double* stiffnesses = springs.stiffnesses.data();
  const double* restLengths = springs.restLengths.data();
  const PaddedVector* positions = scratch.positions.data();
  PaddedVector* forces = scratch.springForces.data();
  PaddedVector* sixGradient = scratch.sixVolumeGradient.data();
  PaddedVector* vectors = scratch.springVectors.data();
  glm::dvec2* damperFactors = scratch.damperFactors.data();
  const Vector4 origin = positions[0].lanes;  // near the mesh, so the cross products stay well conditioned
  for (std::size_t s = 0; s < count; ++s) {
    const std::uint32_t i = ends[s].x, j = ends[s].y;
    const Vector4 positionI = positions[i].lanes;
    const Vector4 x = positions[j].lanes - positionI;
    const double length = std::sqrt(dot(x, x));
    const double inverseLength = 1.0 / length;  // the one division per spring
    const double hooke = stiffnesses[s] * (length - restLengths[s]) * inverseLength;
    const Vector4 forceOnJ = broadcast(-hooke) * x;
    forces[j].lanes += forceOnJ;
    forces[i].lanes -= forceOnJ;
    if constexpr (kWithVolume) {
      const Vector4 share = cross(positionI - origin, x);
      sixGradient[opposites[s].x].lanes += share;
      sixGradient[opposites[s].y].lanes -= share;
    }
    vectors[s].lanes = x;
    const double factor = decays[s] * (inverseLength * inverseLength);
    damperFactors[s] = {factor * inverseMasses[i], factor * inverseMasses[j]};
  }
}

// Pass 4, one spring: its relative speed along x̂ decays exactly over the half substep, the impulse
// split by inverse mass (springs.cpp's dampOneSpring with the division and the inverse masses
// folded into the two factors in pass 1).
[[gnu::always_inline]] inline void dampOneSpring(const glm::u32vec2& ends, const Vector4& x,
                                                 const glm::dvec2& damperFactors, PaddedVector* velocities) {
  const std::uint32_t i = ends.x, j = ends.y;
  const double relative = dot(velocities[j].lanes - velocities[i].lanes, x);
  velocities[j].lanes += broadcast(relative * damperFactors.y) * x;
  velocities[i].lanes -= broadcast(relative * damperFactors.x) * x;
}

}  // namespace

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx2", "default")))
#endif
void dampedSymplecticEulerSubstep(ParticleState& state, double h, const DampedSymplecticEulerModel& model,
                                  DampedSymplecticEulerScratch& scratch) {
  const std::size_t count = state.size();
  if (count == 0) return;
  const SpringSet& springs = *model.springs;
  const std::size_t springCount = springs.size();
  const double* inverseMasses = state.inverseMasses.data();
  // The accumulators stay zero between substeps (pass 3 clears what it reads), so only a new size
  // needs filling here.
  if (scratch.springForces.size() != count) scratch.springForces.assign(count, PaddedVector{});
  if (scratch.sixVolumeGradient.size() != count) scratch.sixVolumeGradient.assign(count, PaddedVector{});
  scratch.positions.resize(count);
  scratch.velocities.resize(count);
  scratch.springVectors.resize(springCount);
  scratch.damperFactors.resize(springCount);
  PaddedVector* positions = scratch.positions.data();
  PaddedVector* velocities = scratch.velocities.data();

  // 0. The state, padded.
  for (std::size_t i = 0; i < count; ++i) {
    positions[i].lanes = pad(state.positions[i]);
    velocities[i].lanes = pad(state.velocities[i]);
  }
  // 1. The springs, and the fill's ∇V, at the positions of the kick.
  const bool hasVolume = model.springOpposites != nullptr;
  if (hasVolume)
    springPass<true>(springs, model.springOpposites->data(), model.dampingDecays->data(), inverseMasses,
                     scratch);
  else
    springPass<false>(springs, nullptr, model.dampingDecays->data(), inverseMasses, scratch);
  // 2. The fill pressure p = p0 + K (1 - V/V0), with 18 V = Σ (p_i - o) · 6∇_i V.
  double pressureOverSix = 0.0;
  if (hasVolume) {
    const Vector4 origin = positions[0].lanes;
    double eighteenTimesVolume = 0.0;
    for (std::size_t i = 0; i < count; ++i)
      eighteenTimesVolume += dot(positions[i].lanes - origin, scratch.sixVolumeGradient[i].lanes);
    pressureOverSix =
        fillPressure(eighteenTimesVolume / 18.0, model.restVolume, model.restPressure, model.bulkModulus) /
        6.0;
  }
  // 3. Kick with a = w F + g (kinematic points keep their velocity).
  const Vector4 gravity = pad(model.gravity);
  for (std::size_t i = 0; i < count; ++i) {
    Vector4& springForce = scratch.springForces[i].lanes;
    Vector4& sixGradient = scratch.sixVolumeGradient[i].lanes;
    const double w = inverseMasses[i];
    if (w != 0.0)
      velocities[i].lanes +=
          ((springForce + broadcast(pressureOverSix) * sixGradient) * broadcast(w) + gravity) * broadcast(h);
    springForce = Vector4{};
    sixGradient = Vector4{};
  }
  // 4. The damper, implicitly: symmetric Gauss–Seidel, forward then backward, h/2 each (a one-way
  //    sweep is not a symmetric contraction and destabilised symplectic Euler).
  const glm::u32vec2* ends = springs.ends.data();
  const PaddedVector* vectors = scratch.springVectors.data();
  const glm::dvec2* damperFactors = scratch.damperFactors.data();
  for (std::size_t s = 0; s < springCount; ++s)
    dampOneSpring(ends[s], vectors[s].lanes, damperFactors[s], velocities);
  for (std::size_t s = springCount; s-- > 0;)
    dampOneSpring(ends[s], vectors[s].lanes, damperFactors[s], velocities);
  // 5. Drift, then put back on the floor whatever went through it.
  for (std::size_t i = 0; i < count; ++i) {
    glm::dvec3& position = state.positions[i];
    glm::dvec3& velocity = state.velocities[i];
    velocity = unpad(velocities[i].lanes);
    position += velocity * h;
    if (inverseMasses[i] != 0.0) resolveFloorContactAt(position, velocity, model.friction);
  }
}

}  // namespace slime
