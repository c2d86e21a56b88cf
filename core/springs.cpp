#include "core/springs.h"

#include "core/icosphere.h"

#include <glm/geometric.hpp>

#include <cmath>

namespace slime {

double seriesStiffness(double elementaryStiffness, double elementaryLength, double length) {
  return elementaryStiffness * elementaryLength / length;
}

glm::dvec3 springForce(const glm::dvec3& positionI, const glm::dvec3& positionJ, double restLength,
                       double stiffness) {
  const glm::dvec3 x = positionJ - positionI;
  const double length = glm::length(x);
  return -stiffness * (length - restLength) * (x / length);
}

glm::dvec3 damperForce(const glm::dvec3& positionI, const glm::dvec3& positionJ,
                       const glm::dvec3& velocityI, const glm::dvec3& velocityJ, double damping) {
  const glm::dvec3 x = positionJ - positionI;
  const glm::dvec3 v = velocityJ - velocityI;
  return -damping * (glm::dot(v, x) / glm::dot(x, x)) * x;
}

void addSpringForces(const SpringSet& springs, const std::vector<glm::dvec3>& positions,
                     const std::vector<glm::dvec3>& velocities, double damping,
                     std::vector<glm::dvec3>& forces) {
  const std::size_t count = springs.size();
  for (std::size_t s = 0; s < count; ++s) {
    const std::uint32_t i = springs.ends[s].x, j = springs.ends[s].y;
    const glm::dvec3 x = positions[j] - positions[i];
    const glm::dvec3 v = velocities[j] - velocities[i];
    const double lengthSquared = glm::dot(x, x);
    const double length = std::sqrt(lengthSquared);
    // Hooke plus the damper, both along x̂, folded into one scalar on x.
    const double hooke = springs.stiffnesses[s] * (length - springs.restLengths[s]) / length;
    const double viscous = damping * glm::dot(v, x) / lengthSquared;
    const glm::dvec3 forceOnJ = -(hooke + viscous) * x;
    forces[j] += forceOnJ;
    forces[i] -= forceOnJ;
  }
}

namespace {

// Solves one spring's two-body damper exactly: the relative speed u along x̂ becomes u·decay
// (decay = exp(-k_d (w_i + w_j) h)); the impulse is split by inverse mass, so momentum is kept.
void dampOneSpring(const SpringSet& springs, std::size_t s, const std::vector<glm::dvec3>& positions,
                   const std::vector<double>& inverseMasses, double decay, std::vector<glm::dvec3>& velocities) {
  const std::uint32_t i = springs.ends[s].x, j = springs.ends[s].y;
  const double weight = inverseMasses[i] + inverseMasses[j];
  if (weight == 0.0) return;
  const glm::dvec3 x = positions[j] - positions[i];
  const double relative = glm::dot(velocities[j] - velocities[i], x) / glm::dot(x, x);  // u / |x|
  const double impulse = relative * (decay - 1.0) / weight;                            // per |x|
  velocities[j] += (impulse * inverseMasses[j]) * x;
  velocities[i] -= (impulse * inverseMasses[i]) * x;
}

}  // namespace

void springDampingDecays(const SpringSet& springs, const std::vector<double>& inverseMasses, double damping,
                         double h, std::vector<double>& decays) {
  decays.resize(springs.size());
  for (std::size_t s = 0; s < springs.size(); ++s) {
    const double weight = inverseMasses[springs.ends[s].x] + inverseMasses[springs.ends[s].y];
    decays[s] = std::exp(-damping * weight * 0.5 * h);
  }
}

void dampSpringsImplicitly(const SpringSet& springs, const std::vector<glm::dvec3>& positions,
                           const std::vector<double>& inverseMasses, const std::vector<double>& decays,
                           std::vector<glm::dvec3>& velocities) {
  // Symmetric Gauss–Seidel: forward then backward, h/2 each, so the whole pass is a symmetric
  // contraction of the kinetic energy (a one-way sweep is not, and destabilised symplectic Euler).
  const std::size_t count = springs.size();
  for (std::size_t s = 0; s < count; ++s) dampOneSpring(springs, s, positions, inverseMasses, decays[s], velocities);
  for (std::size_t s = count; s-- > 0;) dampOneSpring(springs, s, positions, inverseMasses, decays[s], velocities);
}

void dampSpringsImplicitly(const SpringSet& springs, const std::vector<glm::dvec3>& positions,
                           const std::vector<double>& inverseMasses, double damping, double h,
                           std::vector<glm::dvec3>& velocities) {
  if (damping == 0.0) return;
  std::vector<double> decays;
  springDampingDecays(springs, inverseMasses, damping, h, decays);
  dampSpringsImplicitly(springs, positions, inverseMasses, decays, velocities);
}

SpringSet makeEdgeSprings(const std::vector<glm::dvec3>& positions,
                          const std::vector<glm::u32vec3>& triangles, double elementaryStiffness,
                          double prestrain) {
  SpringSet springs;
  springs.ends = uniqueEdges(triangles);
  springs.restLengths.resize(springs.ends.size());
  springs.stiffnesses.resize(springs.ends.size());
  double meanLength = 0.0;
  for (std::size_t s = 0; s < springs.size(); ++s) {
    const double length = glm::length(positions[springs.ends[s].y] - positions[springs.ends[s].x]);
    springs.restLengths[s] = length;
    meanLength += length;
  }
  meanLength /= static_cast<double>(springs.size());
  for (std::size_t s = 0; s < springs.size(); ++s) {
    springs.stiffnesses[s] = seriesStiffness(elementaryStiffness, meanLength, springs.restLengths[s]);
    springs.restLengths[s] /= 1.0 + prestrain;
  }
  return springs;
}

}  // namespace slime
