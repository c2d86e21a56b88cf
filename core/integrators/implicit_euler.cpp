#include "core/integrators/implicit_euler.h"

#include "core/geometry/volume.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace slime {
namespace {

glm::dvec3 multiplyBlock(const std::array<double, 6>& b, const glm::dvec3& u) {
  return {b[0] * u.x + b[1] * u.y + b[2] * u.z, b[1] * u.x + b[3] * u.y + b[4] * u.z,
          b[2] * u.x + b[4] * u.y + b[5] * u.z};
}

double dotAll(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) sum += glm::dot(a[i], b[i]);
  return sum;
}

// y = (M + h D' + h² K') u with D' = -∂f/∂v, K' = -∂f/∂x; kinematic rows are the identity.
void multiplySystem(const ParticleState& state, const ForceModel& model, double dt,
                    double volumeCoupling, const ImplicitEulerScratch& scratch,
                    const std::vector<glm::dvec3>& u, std::vector<glm::dvec3>& y) {
  const std::size_t count = state.size();
  for (std::size_t i = 0; i < count; ++i) {
    const double w = state.inverseMasses[i];
    y[i] = w == 0.0 ? u[i] : u[i] / w;
  }
  const SpringSet& springs = *model.springs;
  for (std::size_t s = 0; s < springs.size(); ++s) {
    const std::uint32_t i = springs.ends[s].x, j = springs.ends[s].y;
    const glm::dvec3 f = multiplyBlock(scratch.springBlocks[s], u[j] - u[i]);
    if (state.inverseMasses[j] != 0.0) y[j] += f;
    if (state.inverseMasses[i] != 0.0) y[i] -= f;
  }
  if (volumeCoupling != 0.0) {
    const std::vector<glm::dvec3>& g = scratch.forceScratch.volumeGradient;
    double projection = 0.0;
    for (std::size_t i = 0; i < count; ++i)
      if (state.inverseMasses[i] != 0.0) projection += glm::dot(g[i], u[i]);
    const double scale = dt * dt * volumeCoupling * projection;
    for (std::size_t i = 0; i < count; ++i)
      if (state.inverseMasses[i] != 0.0) y[i] += scale * g[i];
  }
}

}  // namespace

int implicitEulerStep(ParticleState& state, double dt, const ForceModel& model,
                      const ImplicitEulerOptions& options, ImplicitEulerScratch& scratch) {
  const std::size_t count = state.size();
  computeAccelerations(model, state.inverseMasses, state.positions, state.velocities,
                       scratch.forceScratch, scratch.accelerations);
  const bool hasVolume = model.triangles && !model.triangles->empty();
  const double volumeCoupling = hasVolume ? model.bulkModulus / model.restVolume : 0.0;

  // Per-spring blocks h² K' + h D' and the right-hand side h (f0 - h K' v0).
  const SpringSet& springs = *model.springs;
  scratch.springBlocks.resize(springs.size());
  scratch.rhs.resize(count);
  scratch.diagonal.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double w = state.inverseMasses[i];
    // h f0 with f0 = m a (gravity included); kinematic points get no equation.
    scratch.rhs[i] = w == 0.0 ? glm::dvec3(0.0) : dt * scratch.accelerations[i] / w;
    scratch.diagonal[i] = w == 0.0 ? glm::dvec3(1.0) : glm::dvec3(1.0 / w);
  }
  for (std::size_t s = 0; s < springs.size(); ++s) {
    const std::uint32_t i = springs.ends[s].x, j = springs.ends[s].y;
    const glm::dvec3 x = state.positions[j] - state.positions[i];
    const double length = glm::length(x);
    const glm::dvec3 n = x / length;
    const double k = springs.stiffnesses[s];
    const double transverse = k * std::max(0.0, 1.0 - springs.restLengths[s] / length);
    const double axial = k - transverse;  // K' = transverse I + (k - transverse) n nᵀ
    const double viscous = model.damping;
    const double along = dt * dt * axial + dt * viscous;
    const double across = dt * dt * transverse;
    std::array<double, 6>& b = scratch.springBlocks[s];
    b = {across + along * n.x * n.x, along * n.x * n.y, along * n.x * n.z,
         across + along * n.y * n.y, along * n.y * n.z, across + along * n.z * n.z};
    // h² K' v0 along this spring, moved to the right-hand side.
    const glm::dvec3 relative = state.velocities[j] - state.velocities[i];
    const glm::dvec3 stiffnessTimesVelocity = transverse * relative + axial * glm::dot(n, relative) * n;
    const glm::dvec3 diagonalPart{b[0], b[3], b[5]};
    if (state.inverseMasses[j] != 0.0) {
      scratch.rhs[j] -= dt * dt * stiffnessTimesVelocity;
      scratch.diagonal[j] += diagonalPart;
    }
    if (state.inverseMasses[i] != 0.0) {
      scratch.rhs[i] += dt * dt * stiffnessTimesVelocity;
      scratch.diagonal[i] += diagonalPart;
    }
  }
  if (hasVolume) {
    const std::vector<glm::dvec3>& g = scratch.forceScratch.volumeGradient;
    double projection = 0.0;
    for (std::size_t i = 0; i < count; ++i)
      if (state.inverseMasses[i] != 0.0) projection += glm::dot(g[i], state.velocities[i]);
    for (std::size_t i = 0; i < count; ++i) {
      if (state.inverseMasses[i] == 0.0) continue;
      scratch.rhs[i] -= dt * dt * volumeCoupling * projection * g[i];
      scratch.diagonal[i] += dt * dt * volumeCoupling * g[i] * g[i];
    }
  }

  // Preconditioned conjugate gradients from Δv = 0.
  std::vector<glm::dvec3>& deltaV = scratch.deltaV;
  std::vector<glm::dvec3>& r = scratch.residual;
  std::vector<glm::dvec3>& p = scratch.direction;
  std::vector<glm::dvec3>& q = scratch.product;
  std::vector<glm::dvec3>& z = scratch.preconditioned;
  // Warm start from the previous step's Δv (the motion changes little from step to step).
  if (deltaV.size() != count) deltaV.assign(count, glm::dvec3(0.0));
  for (std::size_t i = 0; i < count; ++i)
    if (state.inverseMasses[i] == 0.0) deltaV[i] = glm::dvec3(0.0);
  z.resize(count);
  q.resize(count);
  multiplySystem(state, model, dt, volumeCoupling, scratch, deltaV, q);
  r.resize(count);
  for (std::size_t i = 0; i < count; ++i) r[i] = scratch.rhs[i] - q[i];
  for (std::size_t i = 0; i < count; ++i) z[i] = r[i] / scratch.diagonal[i];
  p = z;
  double rz = dotAll(r, z);
  const double threshold = options.tolerance * options.tolerance * dotAll(scratch.rhs, scratch.rhs);
  int iteration = 0;
  while (iteration < options.maxIterations && dotAll(r, r) > threshold && rz > 0.0) {
    multiplySystem(state, model, dt, volumeCoupling, scratch, p, q);
    const double alpha = rz / dotAll(p, q);
    for (std::size_t i = 0; i < count; ++i) {
      deltaV[i] += alpha * p[i];
      r[i] -= alpha * q[i];
      z[i] = r[i] / scratch.diagonal[i];
    }
    const double rzNext = dotAll(r, z);
    const double beta = rzNext / rz;
    rz = rzNext;
    for (std::size_t i = 0; i < count; ++i) p[i] = z[i] + beta * p[i];
    ++iteration;
  }

  for (std::size_t i = 0; i < count; ++i) {
    if (state.inverseMasses[i] != 0.0) state.velocities[i] += deltaV[i];
    state.positions[i] += dt * state.velocities[i];
  }
  return iteration;
}

}  // namespace slime
