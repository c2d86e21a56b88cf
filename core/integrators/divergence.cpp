#include "core/integrators/divergence.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>

namespace slime {
namespace {

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// A quick pass with no square root or branch per point, conservative: it can only call a sound
// state suspect (a huge but finite sum, a speed within rounding of the limit), never the reverse.
bool surelySound(const ParticleState& state, double absurdSpeed) {
  const double suspectSpeedSquared = absurdSpeed * absurdSpeed * (1.0 - 1e-9);
  bool sound = true;
  for (std::size_t i = 0; i < state.size(); ++i) {
    const glm::dvec3& p = state.positions[i];
    const glm::dvec3& v = state.velocities[i];
    // NaN fails every comparison and inf reaches the sum, so both make `sound` false.
    sound &= std::isfinite(p.x + p.y + p.z) && glm::dot(v, v) <= suspectSpeedSquared;
  }
  return sound;
}

}  // namespace

std::string findDivergence(const ParticleState& state, double absurdSpeed) {
  if (surelySound(state, absurdSpeed)) return {};
  // Name the first bad point exactly as the careful test sees it.
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
