#include "render/trace/shading_parameters.h"

#include "render/trace/optics.h"

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
  // One pixel subtends 2 tan(fov/2) / height radians at the image centre.
  const double tanHalfFov = std::tan(settings.camera.fov * 3.14159265358979 / 360.0);
  p.pixelSpread = static_cast<float>(2.0 * tanHalfFov / std::max(1, height));
  return p;
}

}  // namespace slime
