#include "core/export/export_material.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace slime {
namespace {

constexpr double kDarkest = 1e-3;  // as render/trace/optics.cpp: a black channel still lets 1/1000 through

}  // namespace

glm::dvec3 ExportMaterial::absorptionPerMetre() const {
  if (attenuationDistance <= 0.0) return glm::dvec3(0.0);
  return {-std::log(attenuationColor.x) / attenuationDistance,
          -std::log(attenuationColor.y) / attenuationDistance,
          -std::log(attenuationColor.z) / attenuationDistance};
}

ExportMaterial exportMaterialOf(const SlimeSettings& slime) {
  ExportMaterial material;
  material.color = glm::clamp(slime.color, glm::dvec3(0.0), glm::dvec3(1.0));
  material.transmission = slime.transmission;
  material.ior = slime.ior;
  if (slime.absorption > 0.0) {
    material.attenuationColor = glm::clamp(slime.color, glm::dvec3(kDarkest), glm::dvec3(1.0));
    material.attenuationDistance = 1.0 / slime.absorption;
  }
  material.specular = slime.specular;
  return material;
}

double meanChord(const SurfaceMesh& mesh) {
  double volume = 0.0, area = 0.0;
  for (const Triangle& t : mesh.triangles) {
    const glm::dvec3 &a = mesh.positions[t.x], &b = mesh.positions[t.y], &c = mesh.positions[t.z];
    volume += glm::dot(a, glm::cross(b, c)) / 6.0;  // the signed tetrahedron to the origin
    area += 0.5 * glm::length(glm::cross(b - a, c - a));
  }
  return area > 0.0 ? 4.0 * std::abs(volume) / area : 0.0;
}

}  // namespace slime
