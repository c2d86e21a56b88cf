#include "core/export/obj_file.h"

#include <cstdio>

namespace slime {

std::string objText(const SurfaceMesh& mesh) {
  std::string text = "# slime surface at t = " + std::to_string(mesh.time) + " s, metres\no slime\n";
  char line[160];
  for (const glm::dvec3& p : mesh.positions) {
    std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", p.x, p.y, p.z);
    text += line;
  }
  for (const glm::dvec3& n : mesh.normals) {
    std::snprintf(line, sizeof line, "vn %.9g %.9g %.9g\n", n.x, n.y, n.z);
    text += line;
  }
  for (const Triangle& t : mesh.triangles) {
    std::snprintf(line, sizeof line, "f %u//%u %u//%u %u//%u\n", t.x + 1, t.x + 1, t.y + 1, t.y + 1, t.z + 1,
                  t.z + 1);
    text += line;
  }
  return text;
}

}  // namespace slime
