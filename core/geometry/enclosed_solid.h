// The solid a closed, outward-wound surface encloses: its volume and its centroid (the centre of mass
// of a uniform fill), by the divergence theorem over the triangles, each a tetrahedron with the origin:
//   V = Σ_t a · (b × c) / 6,   c_V = Σ_t (a + b + c) / 4 · (a · (b × c) / 6) / V.
// A piece's figures in `slime sim`'s report (Simulation::pieceFigures).
#pragma once

#include "core/geometry/surface_view.h"

#include <glm/vec3.hpp>

namespace slime {

struct EnclosedSolid {
  double volume = 0.0;            // m³
  glm::dvec3 centroid{0.0};       // m; the origin when the volume is 0
};

EnclosedSolid enclosedSolid(const SurfaceView& surface);

}  // namespace slime
