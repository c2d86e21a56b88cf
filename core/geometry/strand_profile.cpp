#include "core/geometry/strand_profile.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace slime {

double strandThickness(const std::vector<glm::dvec3>& points, const glm::dvec3& a, const glm::dvec3& b, double s,
                       double slab) {
  const glm::dvec3 line = b - a;
  const glm::dvec3 across = glm::cross(line, glm::dvec3(0.0, 0.0, 1.0));
  if (glm::length(line) < 1e-12 || glm::length(across) < 1e-12 * glm::length(line)) return 0.0;
  const glm::dvec3 along = glm::normalize(line), side = glm::normalize(across);
  const glm::dvec3 centre = a + s * line;
  double low = 0.0, high = 0.0;
  bool any = false;
  for (const glm::dvec3& p : points) {
    if (std::abs(glm::dot(p - centre, along)) > slab) continue;
    const double d = glm::dot(p - centre, side);
    low = any ? std::min(low, d) : d;
    high = any ? std::max(high, d) : d;
    any = true;
  }
  return any ? high - low : 0.0;
}

}  // namespace slime
