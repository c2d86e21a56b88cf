// A surface as binary little-endian PLY: per vertex x y z as doubles (the simulation's exact values,
// m) and nx ny nz as floats; per face a list of three int indices.
#pragma once

#include "core/export/surface_mesh.h"

#include <string>

namespace slime {

std::string plyBytes(const SurfaceMesh& mesh);

}  // namespace slime
