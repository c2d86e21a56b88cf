// One piece of the slime as it is drawn: a closed, watertight triangle surface (every edge shared by
// two triangles, wound counter-clockwise seen from outside), borrowed from whoever holds it. The
// simulation hands the renderer and the exporters a list of these, one per piece; pieces do not
// overlap, so a ray that enters one leaves that same one before it can meet another.
#pragma once

#include "core/geometry/icosphere.h"

#include <glm/vec3.hpp>

#include <span>

namespace slime {

struct SurfaceView {
  std::span<const glm::dvec3> positions;  // the piece's vertices
  std::span<const Triangle> triangles;    // indices into `positions`

  SurfaceView() = default;
  SurfaceView(std::span<const glm::dvec3> vertices, std::span<const Triangle> faces)
      : positions(vertices), triangles(faces) {}
  SurfaceView(const TriangleMesh& mesh) : positions(mesh.positions), triangles(mesh.triangles) {}  // NOLINT: a mesh is one piece
};

}  // namespace slime
