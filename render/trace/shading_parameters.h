// The per-frame constants of shading, read once from Settings into floats: light, slime and floor
// optics, sky, recursion depth, modes, and the ray-pruning threshold.
#pragma once

#include "core/settings/settings.h"

#include <glm/vec3.hpp>

#include <algorithm>

namespace slime {

enum class OpticsMode { Fresnel, Seed };

// A secondary ray is traced only if its weight (the product of the k_s / k_t / Fresnel / Beer–Lambert
// factors along its path, largest channel) is at least this: the light it could bring (radiance ≤ 1)
// is then below half an 8-bit step, 0.5/255, invisible in the PNG.
constexpr float kMinRayWeight = 0.5f / 255.0f;

// A weight's largest channel, the one kMinRayWeight is compared with.
inline float largest(const glm::vec3& v) { return std::max(v.x, std::max(v.y, v.z)); }

struct ShadingParameters {
  // Light: a point light without fall-off (the seed's model) plus an ambient term.
  glm::vec3 lightPosition{0.0f}, lightColor{1.0f}, ambientLight{0.2f};
  // Slime (SPEC §2): colour as surface tint; σ per channel from optics.h absorptionCoefficients.
  glm::vec3 slimeColor{1.0f}, slimeAbsorption{0.0f};
  float transmission = 0.7f, ior = 1.35f, specular = 0.4f, diffuse = 0.3f, ambient = 0.1f, shininess = 80.0f;
  // Floor: varnished wood, its own highlight exponent.
  float floorDiffuse = 0.8f, floorSpecular = 0.1f, floorShininess = 60.0f;
  // Sky gradient and the distance over which the floor fades into the horizon haze.
  glm::vec3 skyHorizon{0.80f, 0.85f, 0.92f}, skyZenith{0.30f, 0.50f, 0.85f};
  float hazeDistance = 6.0f;
  int depth = 3;               // ray segments per path (1 = primary only)
  bool smoothNormals = true;
  bool shadows = true;
  OpticsMode optics = OpticsMode::Fresnel;
  float pixelSpread = 1e-3f;   // cone spread per unit distance of one pixel, radians (footprint filter)
};

// The shading constants of `settings` for an image `height` pixels tall.
ShadingParameters makeShadingParameters(const Settings& settings, int height);

}  // namespace slime
