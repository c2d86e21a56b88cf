#include "core/volume.h"

#include <glm/geometric.hpp>

namespace slime {

double enclosedVolume(const std::vector<glm::dvec3>& positions,
                      const std::vector<glm::u32vec3>& triangles) {
  if (positions.empty()) return 0.0;
  const glm::dvec3 origin = positions[0];  // a nearby origin keeps the sum well conditioned
  double sixTimesVolume = 0.0;
  for (const glm::u32vec3& t : triangles) {
    const glm::dvec3 a = positions[t.x] - origin, b = positions[t.y] - origin, c = positions[t.z] - origin;
    sixTimesVolume += glm::dot(a, glm::cross(b, c));
  }
  return sixTimesVolume / 6.0;
}

double volumeGradient(const std::vector<glm::dvec3>& positions,
                      const std::vector<glm::u32vec3>& triangles, std::vector<glm::dvec3>& gradient) {
  gradient.assign(positions.size(), glm::dvec3(0.0));
  if (positions.empty()) return 0.0;
  const glm::dvec3 origin = positions[0];
  double sixTimesVolume = 0.0;
  for (const glm::u32vec3& t : triangles) {
    const glm::dvec3 a = positions[t.x] - origin, b = positions[t.y] - origin, c = positions[t.z] - origin;
    const glm::dvec3 bc = glm::cross(b, c);
    sixTimesVolume += glm::dot(a, bc);
    gradient[t.x] += bc;
    gradient[t.y] += glm::cross(c, a);
    gradient[t.z] += glm::cross(a, b);
  }
  for (glm::dvec3& g : gradient) g /= 6.0;
  return sixTimesVolume / 6.0;
}

double fillPressure(double volume, double restVolume, double restPressure, double bulkModulus) {
  return restPressure + bulkModulus * (1.0 - volume / restVolume);
}

}  // namespace slime
