#include "core/geometry/enclosed_solid.h"

#include <glm/geometric.hpp>

namespace slime {

EnclosedSolid enclosedSolid(const SurfaceView& surface) {
  // About the surface's first vertex rather than the origin: the same sums, smaller terms.
  EnclosedSolid solid;
  if (surface.positions.empty()) return solid;
  const glm::dvec3 o = surface.positions[0];
  double sixVolume = 0.0;
  glm::dvec3 moment(0.0);  // Σ 6 V_t (a + b + c) about o
  for (const Triangle& t : surface.triangles) {
    const glm::dvec3 a = surface.positions[t.x] - o, b = surface.positions[t.y] - o, c = surface.positions[t.z] - o;
    const double six = glm::dot(a, glm::cross(b, c));
    sixVolume += six;
    moment += six * (a + b + c);
  }
  solid.volume = sixVolume / 6.0;
  solid.centroid = sixVolume != 0.0 ? o + moment / (4.0 * sixVolume) : glm::dvec3(0.0);
  return solid;
}

}  // namespace slime
