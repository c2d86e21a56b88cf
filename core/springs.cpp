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
  const double lengthSquared = glm::dot(x, x);
  return -damping * (glm::dot(v, x) / lengthSquared) * (x / std::sqrt(lengthSquared));
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
    // Hooke plus the strain-rate damper, both along x̂, folded into one scalar on x.
    const double hooke = springs.stiffnesses[s] * (length - springs.restLengths[s]);
    const double viscous = damping * glm::dot(v, x) / lengthSquared;
    const glm::dvec3 forceOnJ = -((hooke + viscous) / length) * x;
    forces[j] += forceOnJ;
    forces[i] -= forceOnJ;
  }
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
