// The slime's look as other programs' materials carry it: the colour, transmission, index of
// refraction and Beer–Lambert absorption of the scene's `slime.*` settings, in the terms of glTF's
// KHR_materials_volume (an attenuation colour reached after an attenuation distance) and of an MTL
// file. The renderer's absorption per metre (render/trace/optics.h absorptionCoefficients) is
//   σ_c = k · (−ln max(color_c, 1/1000)),
// which is glTF's σ_c = −ln(attenuationColor_c) / attenuationDistance with
//   attenuationColor = max(color, 1/1000), attenuationDistance = 1/k
// (a path of 1/k metres transmits `color`); k = 0 is a clear jelly with no attenuation distance.
#pragma once

#include "core/export/surface_mesh.h"
#include "core/settings/settings.h"

#include <glm/vec3.hpp>

namespace slime {

struct ExportMaterial {
  glm::dvec3 color{1.0};             // slime.color, linear RGB: the base (diffuse) colour
  double transmission = 0.0;         // slime.transmission: the weight of the refracted light
  double ior = 1.5;                  // slime.ior
  glm::dvec3 attenuationColor{1.0};  // what a path of attenuationDistance transmits, each channel
  double attenuationDistance = 0.0;  // m; 0 when slime.absorption is 0 (nothing is absorbed)
  double specular = 0.0;             // slime.specular: the Phong highlight's weight
  // glTF's roughness: the renderer's reflected and refracted rays are sharp (Whitted), so the surface is
  // smooth; kept off exactly 0 so that rasterisers still draw a light's highlight, as its Phong term does.
  double roughness = 0.05;

  // σ_c, 1/m: what the renderer absorbs per metre of jelly (0 for a clear one).
  glm::dvec3 absorptionPerMetre() const;
};

ExportMaterial exportMaterialOf(const SlimeSettings& slime);

// The mean length of a straight chord through the closed surface, m: 4V/A (Cauchy), 4r/3 for a ball of
// radius r. glTF's thicknessFactor: how much jelly light crosses on its way through, on average.
double meanChord(const SurfaceMesh& mesh);

}  // namespace slime
