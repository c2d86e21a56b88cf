#include "core/contact/floor_contact.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

namespace slime {

std::size_t resolveFloorContact(ParticleState& state, double friction) {
  std::size_t touching = 0;
  const std::size_t count = state.size();
  for (std::size_t i = 0; i < count; ++i) {
    if (state.inverseMasses[i] == 0.0) continue;
    if (resolveFloorContactAt(state.positions[i], state.velocities[i], friction)) ++touching;
  }
  return touching;
}

bool dampTurningOnFloor(ParticleState& state, double rate, double dt, bool touching) {
  if (rate <= 0.0) return false;
  const std::size_t count = state.size();
  if (count == 0) return false;
  // One pass of sums about the first point (close by, so nothing cancels badly): M, Σ m r, Σ m v,
  // Σ m r × v and the six entries of Σ m r rᵀ, as plain scalars so that the loop stays cheap
  // (it runs every step); the centre-of-mass quantities follow by the parallel-axis rule.
  const glm::dvec3 origin = state.positions[0];
  double mass = 0.0, rx = 0.0, ry = 0.0, rz = 0.0, px = 0.0, py = 0.0, pz = 0.0, lx = 0.0, ly = 0.0, lz = 0.0;
  double sxx = 0.0, syy = 0.0, szz = 0.0, sxy = 0.0, sxz = 0.0, syz = 0.0;
  double lowest = 1.0;
  for (std::size_t i = 0; i < count; ++i) {
    const double w = state.inverseMasses[i];
    if (w == 0.0) continue;
    const double m = 1.0 / w;
    const glm::dvec3& p = state.positions[i];
    const glm::dvec3& v = state.velocities[i];
    const double x = p.x - origin.x, y = p.y - origin.y, z = p.z - origin.z;
    const double mx = m * x, my = m * y, mz = m * z;
    mass += m;
    rx += mx, ry += my, rz += mz;
    px += m * v.x, py += m * v.y, pz += m * v.z;
    lx += my * v.z - mz * v.y, ly += mz * v.x - mx * v.z, lz += mx * v.y - my * v.x;
    sxx += mx * x, syy += my * y, szz += mz * z, sxy += mx * y, sxz += mx * z, syz += my * z;
    lowest = std::min(lowest, p.z);
  }
  if ((lowest > 0.0 && !touching) || mass == 0.0) return false;
  const glm::dvec3 centre = glm::dvec3(rx, ry, rz) / mass;  // relative to origin
  const glm::dvec3 centreVelocity = glm::dvec3(px, py, pz) / mass;
  const glm::dvec3 spin = glm::dvec3(lx, ly, lz) - mass * glm::cross(centre, centreVelocity);
  const glm::dmat3 spread = glm::dmat3(sxx, sxy, sxz, sxy, syy, syz, sxz, syz, szz) -
                            mass * glm::outerProduct(centre, centre);  // Σ m ρ ρᵀ about the centre
  const double trace = spread[0][0] + spread[1][1] + spread[2][2];
  const glm::dmat3 inertia = trace * glm::dmat3(1.0) - spread;
  // A body all on one line cannot turn about it: nothing to damp (and I is singular).
  if (!(glm::determinant(inertia) > 1e-12 * trace * trace * trace)) return true;
  const glm::dvec3 loss = (1.0 - std::exp(-rate * dt)) * (glm::inverse(inertia) * spin);  // of ω, rad/s
  const glm::dvec3 centreAbsolute = origin + centre;
  for (std::size_t i = 0; i < count; ++i)
    if (state.inverseMasses[i] != 0.0) state.velocities[i] -= glm::cross(loss, state.positions[i] - centreAbsolute);
  return true;
}

}  // namespace slime
