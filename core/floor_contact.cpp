#include "core/floor_contact.h"

#include <algorithm>
#include <cmath>

namespace slime {

std::size_t resolveFloorContact(ParticleState& state, double friction) {
  std::size_t touching = 0;
  const std::size_t count = state.size();
  for (std::size_t i = 0; i < count; ++i) {
    if (state.inverseMasses[i] == 0.0) continue;
    glm::dvec3& position = state.positions[i];
    glm::dvec3& velocity = state.velocities[i];
    const bool below = position.z < 0.0;
    const bool pressingDown = position.z <= 0.0 && velocity.z < 0.0;
    if (!below && !pressingDown) continue;
    ++touching;
    position.z = 0.0;
    const double normalSpeedChange = std::max(0.0, -velocity.z);
    velocity.z = std::max(0.0, velocity.z);
    const double tangentialSpeed = std::hypot(velocity.x, velocity.y);
    const double frictionBudget = friction * normalSpeedChange;
    const double keep = tangentialSpeed <= frictionBudget ? 0.0 : 1.0 - frictionBudget / tangentialSpeed;
    velocity.x *= keep;
    velocity.y *= keep;
  }
  return touching;
}

}  // namespace slime
