#include "core/floor_contact.h"

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

}  // namespace slime
