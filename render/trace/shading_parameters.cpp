#include "render/trace/shading_parameters.h"

#include "render/trace/optics.h"

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>

namespace slime {

ShadingParameters makeShadingParameters(const Settings& settings, int height) {
  ShadingParameters p;
  p.lightPosition = glm::vec3(settings.light.position);
  p.lightColor = glm::vec3(settings.light.color);
  p.ambientLight = glm::vec3(settings.light.ambient);
  const SlimeSettings& slime = settings.slime;
  p.slimeColor = glm::vec3(slime.color);
  p.slimeAbsorption = absorptionCoefficients(p.slimeColor, static_cast<float>(slime.absorption));
  p.transmission = static_cast<float>(slime.transmission);
  p.ior = static_cast<float>(slime.ior);
  p.specular = static_cast<float>(slime.specular);
  p.diffuse = static_cast<float>(slime.diffuse);
  p.ambient = static_cast<float>(slime.ambient);
  p.shininess = static_cast<float>(slime.shininess);
  p.floorDiffuse = static_cast<float>(settings.floor.diffuse);
  p.floorSpecular = static_cast<float>(settings.floor.specular);
  p.depth = settings.render.depth;
  p.smoothNormals = settings.render.normals != "flat";
  p.shadows = settings.render.shadows;
  p.optics = settings.render.optics == "seed" ? OpticsMode::Seed : OpticsMode::Fresnel;
  if (settings.render.shading == "physical") {
    // A dielectric that absorbs: Fresnel's weights alone at its surface, and inside a path of 1/k
    // metres transmits slime.color × slime.transmission, σ_c = k (−ln(color_c · k_t)). No ambient,
    // diffuse or highlight of its own (the point light's reflection has no area to be seen).
    p.shading = ShadingModel::Physical;
    p.optics = OpticsMode::Fresnel;
    p.slimeAbsorption = absorptionCoefficients(p.slimeColor * p.transmission, static_cast<float>(slime.absorption));
    p.transmission = 1.0f;
    p.specular = p.diffuse = p.ambient = 0.0f;
  }
  p.brightest = brightestRadiance(p, brightestFloorAlbedo(settings.floor));
  // One pixel subtends 2 tan(fov/2) / height radians at the image centre.
  const double tanHalfFov = std::tan(settings.camera.fov * 3.14159265358979 / 360.0);
  p.pixelSpread = static_cast<float>(2.0 * tanHalfFov / std::max(1, height));
  return p;
}

glm::vec3 brightestFloorAlbedo(const FloorSettings& floor) {
  if (floor.pattern == "image") return glm::vec3(1.0f);
  return 1.15f * glm::max(glm::vec3(floor.colorA), glm::vec3(floor.colorB));
}

glm::vec3 brightestRadiance(const ShadingParameters& p, const glm::vec3& floorAlbedo) {
  const glm::vec3 sky = glm::max(p.skyHorizon, p.skyZenith);
  const glm::vec3 floor = floorAlbedo * (p.ambientLight + p.floorDiffuse * p.lightColor) + p.floorSpecular * p.lightColor;
  const glm::vec3 slimeOwn = p.ambient * p.ambientLight * p.slimeColor + p.lightColor * (p.diffuse * p.slimeColor + p.specular);
  return glm::max(sky, floor) + slimeOwn;
}

}  // namespace slime
