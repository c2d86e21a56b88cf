#include "core/hands/grab.h"

#include "core/geometry/nearest_point.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace slime {

glm::dvec3 nearestSurfacePoint(const std::vector<glm::dvec3>& positions,
                               const std::vector<Triangle>& triangles, const glm::dvec3& point) {
  glm::dvec3 best = positions.empty() ? point : positions[0];
  double bestDistance = std::numeric_limits<double>::infinity();
  for (const Triangle& t : triangles) {
    const glm::dvec3 q = closestPointOnTriangle(point, positions[t.x], positions[t.y], positions[t.z]);
    const double distance = glm::dot(q - point, q - point);
    if (distance < bestDistance) {
      bestDistance = distance;
      best = q;
    }
  }
  return best;
}

std::vector<std::uint32_t> pointsWithinRadius(const std::vector<glm::dvec3>& positions,
                                              const glm::dvec3& center, double radius) {
  std::vector<std::uint32_t> indices;
  for (std::size_t i = 0; i < positions.size(); ++i)
    if (glm::dot(positions[i] - center, positions[i] - center) <= radius * radius)
      indices.push_back(static_cast<std::uint32_t>(i));
  return indices;
}

glm::dvec3 stepTowards(const glm::dvec3& anchor, const glm::dvec3& target, double maxStep) {
  const glm::dvec3 offset = target - anchor;
  const double distance = glm::length(offset);
  if (distance <= maxStep) return target;
  return anchor + offset * (maxStep / distance);
}

glm::dvec3 addMouseSpringForces(const MouseSpring& spring, const std::vector<glm::dvec3>& positions,
                                const std::vector<glm::dvec3>& velocities, std::vector<glm::dvec3>& forces) {
  glm::dvec3 total(0.0);
  for (std::size_t k = 0; k < spring.nodes.size(); ++k) {
    const std::uint32_t i = spring.nodes[k];
    total += nodeShare(spring, k) * (spring.stiffness * (springTarget(spring, k) - positions[i]) +
                                 spring.damping * (springTargetVelocity(spring, k) - velocities[i]));
  }
  const double magnitude = glm::length(total);
  const double scale = magnitude > spring.maxForce ? spring.maxForce / magnitude : 1.0;
  for (std::size_t k = 0; k < spring.nodes.size(); ++k) {
    const std::uint32_t i = spring.nodes[k];
    forces[i] += (scale * nodeShare(spring, k)) *
                 (spring.stiffness * (springTarget(spring, k) - positions[i]) +
                  spring.damping * (springTargetVelocity(spring, k) - velocities[i]));
  }
  return scale * total;
}

glm::dvec3 applyMouseSpringImplicitly(const MouseSpring& spring, const std::vector<glm::dvec3>& positions,
                                      const std::vector<double>& inverseMasses, double h,
                                      std::vector<glm::dvec3>& velocities) {
  std::vector<glm::dvec3> change(spring.nodes.size(), glm::dvec3(0.0));
  glm::dvec3 hand(0.0);
  for (std::size_t k = 0; k < spring.nodes.size(); ++k) {
    const std::uint32_t i = spring.nodes[k];
    const double w = inverseMasses[i];
    if (w <= 0.0) continue;
    const double mass = 1.0 / w, stiffness = nodeShare(spring, k) * spring.stiffness,
                 damping = nodeShare(spring, k) * spring.damping;
    const glm::dvec3 v = velocities[i];
    const glm::dvec3 next =
        (mass / h * v + stiffness * (springTarget(spring, k) - positions[i]) + damping * springTargetVelocity(spring, k)) /
        (mass / h + stiffness * h + damping);
    change[k] = next - v;
    hand += mass * change[k] / h;
  }
  const double magnitude = glm::length(hand);
  const double scale = magnitude > spring.maxForce ? spring.maxForce / magnitude : 1.0;
  for (std::size_t k = 0; k < spring.nodes.size(); ++k) velocities[spring.nodes[k]] += scale * change[k];
  return scale * hand;
}

}  // namespace slime
