#include "core/divergence.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>

namespace slime {
namespace {

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

std::string findDivergence(const ParticleState& state, double absurdSpeed) {
  char text[128];
  for (std::size_t i = 0; i < state.size(); ++i) {
    if (!finite(state.positions[i])) {
      std::snprintf(text, sizeof text, "NaN/inf position at vertex %zu", i);
      return text;
    }
    if (!finite(state.velocities[i])) {
      std::snprintf(text, sizeof text, "NaN/inf velocity at vertex %zu", i);
      return text;
    }
    const double speed = glm::length(state.velocities[i]);
    if (speed > absurdSpeed) {
      std::snprintf(text, sizeof text, "speed %.3g m/s at vertex %zu (limit %.3g m/s)", speed, i, absurdSpeed);
      return text;
    }
  }
  return {};
}

}  // namespace slime
