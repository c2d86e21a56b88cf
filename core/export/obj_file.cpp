#include "core/export/obj_file.h"

#include "core/settings/settings_io.h"

#include <cstdio>

namespace slime {

UpAxis upAxisNamed(const std::string& name, const std::string& option) {
  if (name == "y") return UpAxis::Y;
  if (name == "z") return UpAxis::Z;
  throw SettingsError(option + " " + name +
                      ": expected y (OBJ's convention, the default: Blender and most programs read the slime "
                      "upright) or z (the simulation's own axes, unchanged)");
}

glm::dvec3 toFileAxes(const glm::dvec3& v, UpAxis up) {
  return up == UpAxis::Y ? glm::dvec3(v.x, v.z, -v.y) : v;
}

std::string objText(const SurfaceMesh& mesh, UpAxis up, const std::string& materialFile) {
  std::string text = "# slime surface at t = " + std::to_string(mesh.time) + " s, metres, " +
                     (up == UpAxis::Y ? "y up (the simulation's (x, y, z) as (x, z, -y))" : "z up") +
                     "\nmtllib " + materialFile + "\no slime\nusemtl slime\n";
  char line[160];
  for (const glm::dvec3& position : mesh.positions) {
    const glm::dvec3 p = toFileAxes(position, up);
    std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", p.x, p.y, p.z);
    text += line;
  }
  for (const glm::dvec3& normal : mesh.normals) {
    const glm::dvec3 n = toFileAxes(normal, up);
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

std::string mtlText(const ExportMaterial& material) {
  const double smoothness = 1.0 - material.roughness;
  char text[1200];
  std::snprintf(text, sizeof text,
                "# the slime's material, from the scene's slime.* settings (docs/export.md)\n"
                "newmtl slime\n"
                "Ka 0 0 0\n"
                "Kd %.6g %.6g %.6g\n"
                "Ks %.6g %.6g %.6g\n"
                "Ns %.6g\n"
                "Ni %.6g\n"
                "d 1\n"
                "Tf %.6g %.6g %.6g\n"
                "illum 7\n",
                material.color.x, material.color.y, material.color.z, material.specular, material.specular,
                material.specular, 1000.0 * smoothness * smoothness, material.ior, material.transmission,
                material.transmission, material.transmission);
  return text;
}

}  // namespace slime
