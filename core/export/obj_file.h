// A surface as Wavefront OBJ text: v and vn lines (positions in m with 17 significant digits, so a
// double reads back exactly), faces "f a//a b//b c//c" counted from 1.
#pragma once

#include "core/export/surface_mesh.h"

#include <string>

namespace slime {

std::string objText(const SurfaceMesh& mesh);

}  // namespace slime
