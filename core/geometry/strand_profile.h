// The shape of a strand pulled between two hands: how thick the body is across the pull at given
// fractions of the way from one hand to the other (issue 29 item 2, "thinning in the middle").
#pragma once

#include <glm/vec3.hpp>

#include <vector>

namespace slime {

// The body's thickness across the line from a to b at the point a + s (b − a), m: among `points`
// within `slab` (m) of the plane through that point normal to the line, the extent along the
// horizontal direction across the line, (b − a) × ẑ normalised (the thickness seen from above, as a
// strand lifted between two hands is looked at). 0 when no point is that close, or a and b are
// closer than a picometre or stacked vertically.
double strandThickness(const std::vector<glm::dvec3>& points, const glm::dvec3& a, const glm::dvec3& b, double s,
                       double slab = 0.005);

}  // namespace slime
