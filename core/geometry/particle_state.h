// The slime's mass points as parallel arrays (structure of arrays, as in PositionBasedDynamics):
// positions x, velocities v and inverse masses w = 1/m, where w = 0 marks a point that is driven
// kinematically (grabbed or pressed) instead of by forces. Double precision throughout.
#pragma once

#include <glm/vec3.hpp>

#include <vector>

namespace slime {

struct ParticleState {
  std::vector<glm::dvec3> positions;   // m
  std::vector<glm::dvec3> velocities;  // m/s
  std::vector<double> inverseMasses;   // 1/kg; 0 = kinematic (not moved by forces)

  std::size_t size() const { return positions.size(); }
};

}  // namespace slime
