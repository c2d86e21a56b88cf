#include "render/trace/optics.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace slime {

glm::vec3 absorptionCoefficients(const glm::vec3& color, float absorption) {
  constexpr float kDarkest = 1e-3f;
  return {-absorption * std::log(std::clamp(color.x, kDarkest, 1.0f)),
          -absorption * std::log(std::clamp(color.y, kDarkest, 1.0f)),
          -absorption * std::log(std::clamp(color.z, kDarkest, 1.0f))};
}

}  // namespace slime
