// The point of a triangle nearest to a point: the grab's surface point, the distance a drawn surface
// made afresh is extracted from.
#pragma once

#include <glm/vec3.hpp>

namespace slime {

// Closest point to p on triangle abc (Ericson, Real-Time Collision Detection, 2005, §5.1.5).
glm::dvec3 closestPointOnTriangle(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b,
                                  const glm::dvec3& c);

}  // namespace slime
