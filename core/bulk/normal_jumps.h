// How faceted a drawn surface looks: the angle between the unit normals of the two triangles that
// share each edge (the dihedral's supplement), over every interior edge of the mesh. A smooth
// surface drawn with edges of length l and curvature κ has jumps of about κ·l everywhere; a surface
// carried piecewise affinely by coarser elements adds a crease wherever two elements' maps differ,
// which is what a person sees as facets. The largest and the 99th percentile summarise it.
#pragma once

#include "core/geometry/icosphere.h"

#include <glm/vec3.hpp>

#include <cstddef>
#include <vector>

namespace slime {

struct NormalJumps {
  double largest = 0.0;       // rad
  double percentile99 = 0.0;  // rad
  double median = 0.0;        // rad
  std::size_t edges = 0;      // edges shared by two triangles
  glm::dvec3 largestAt{0.0};  // the midpoint of the edge with the largest jump
};

// Over the edges shared by exactly two triangles (collapsed triangles are skipped).
NormalJumps normalJumps(const std::vector<glm::dvec3>& positions, const std::vector<Triangle>& triangles);

}  // namespace slime
