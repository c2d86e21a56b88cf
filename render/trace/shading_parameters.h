// The per-frame constants of shading, read once from Settings into floats: light, slime and floor
// optics, sky, the cap on a path's segments, modes, and where a path stops (what it still carries
// could no longer change an 8-bit sRGB pixel).
#pragma once

#include "core/settings/settings.h"

#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>

namespace slime {

enum class OpticsMode { Fresnel, Seed };

// classic: the seed's look, local Phong (ambient, diffuse, highlight) on the jelly plus k_s / k_t
// weighted rays; physical: Fresnel reflection and refraction only, the colour and k_t folded into the
// absorption per metre (makeShadingParameters), no light of the jelly's own.
enum class ShadingModel { Classic, Physical };

// The photons' threshold on their weight (render/caustics/photon_tracer.cpp: an eighth of this).
constexpr float kMinRayWeight = 0.5f / 255.0f;

// The linear radiance below which adding light to a pixel cannot move its 8-bit sRGB value by half a
// step. sRGB's encoding e(L) is concave on [0, ∞), steepest at black (the linear segment's slope
// 12.92 up to L = 0.0031308, then 1.055/2.4 · L^(−1.4/2.4) ≤ 12.70), so for any pixel L ≥ 0 and light
// Δ ≥ 0 added to it, e(L + Δ) − e(L) ≤ e(Δ) − e(0) = e(Δ), and e(Δ) < 0.5/255 exactly when
// Δ < (0.5/255) / 12.92 = 1.518e-4: thirteen times below a linear half step (0.5/255), which near
// black moves the encoded value by 6.5 half steps.
constexpr float kInvisibleRadiance = 0.5f / 255.0f / 12.92f;

// A weight's largest channel.
inline float largest(const glm::vec3& v) { return std::max(v.x, std::max(v.y, v.z)); }

// The most the unrounded 8-bit sRGB value of a pixel holding `linear` moves per unit of linear light
// added to it: the curve's slope there, 12.92 on its linear segment (up to 0.0031308), then
// 1.055/2.4 · L^(−1.4/2.4), and 0 once the pixel is white (it is clamped). The curve is concave, so no
// light added moves it faster than this: e(L + Δ) − e(L) ≤ e'(L) Δ.
inline float srgbSlope(float linear) {
  if (linear <= 0.0031308f) return 12.92f;
  if (linear >= 1.0f) return 0.0f;
  return (1.055f / 2.4f) * std::pow(linear, -1.4f / 2.4f);
}

// Whether light of at most `most` (per channel) added to a pixel that holds `pixel` so far could move
// its 8-bit sRGB value by half a step. Light is only ever added, so the pixel ends at least as bright
// as `pixel` and its slope there bounds the change: e'(pixel) · most ≥ 0.5/255 in some channel. A black
// pixel makes this most < kInvisibleRadiance, the cheap test first.
inline bool visibleLight(const glm::vec3& most, const glm::vec3& pixel) {
  if (!(largest(most) >= kInvisibleRadiance)) return false;
  for (int c = 0; c < 3; ++c)
    if (most[c] * srgbSlope(pixel[c]) >= 0.5f / 255.0f) return true;
  return false;
}

// Whether a path that still carries `throughput` (per channel: the product of the Fresnel, k_s, k_t
// and Beer–Lambert factors along it) could change an 8-bit pixel that holds `pixel` so far, when
// nothing it can meet returns more than `brightest` (per channel): it adds at most throughput × brightest.
inline bool visibleThroughput(const glm::vec3& throughput, const glm::vec3& brightest, const glm::vec3& pixel = glm::vec3(0.0f)) {
  return visibleLight(throughput * brightest, pixel);
}

struct ShadingParameters {
  // Light: a point light without fall-off (the seed's model) plus an ambient term.
  glm::vec3 lightPosition{0.0f}, lightColor{1.0f}, ambientLight{0.2f};
  // Slime (SPEC §2): colour as surface tint; σ per channel from optics.h absorptionCoefficients.
  glm::vec3 slimeColor{1.0f}, slimeAbsorption{0.0f};
  float transmission = 0.7f, ior = 1.35f, specular = 0.4f, diffuse = 0.3f, ambient = 0.1f, shininess = 80.0f;
  ShadingModel shading = ShadingModel::Classic;
  // Floor: varnished wood, its own highlight exponent.
  float floorDiffuse = 0.8f, floorSpecular = 0.1f, floorShininess = 60.0f;
  // Sky gradient and the distance over which the floor fades into the horizon haze.
  glm::vec3 skyHorizon{0.80f, 0.85f, 0.92f}, skyZenith{0.30f, 0.50f, 0.85f};
  float hazeDistance = 6.0f;
  int depth = 16;              // the most ray segments a path has (1 = primary only)
  // The brightest radiance per channel a ray can return (brightestRadiance): a path stops before
  // depth once visibleThroughput says what it carries is invisible.
  glm::vec3 brightest{1.0f};
  bool smoothNormals = true;
  bool shadows = true;
  OpticsMode optics = OpticsMode::Fresnel;
  float pixelSpread = 1e-3f;   // cone spread per unit distance of one pixel, radians (footprint filter)
};

// The shading constants of `settings` for an image `height` pixels tall.
ShadingParameters makeShadingParameters(const Settings& settings, int height);

// The floor's brightest albedo per channel: the pattern's brighter colour times its brightest board
// and grain (floor_texture.cpp's planks: 1.09 × 1.05, rounded up), or 1 for an image.
glm::vec3 brightestFloorAlbedo(const FloorSettings& floor);

// The most radiance per channel any ray can bring back in this scene, from `p`'s light, sky and
// slime and the floor's brightest albedo: the brighter of the sky (its horizon and zenith colours;
// the haze mixes the floor towards the horizon) and the lit floor, albedo × (ambient + k_d I_l) +
// k_s I_l (its highlight), plus what one slime hit adds of its own in classic shading (ambient,
// diffuse and its Phong highlight). The caustic map's focus is left out: a bright spot a few
// millimetres wide met by a path that has lost all but 1/10,000 of its light.
glm::vec3 brightestRadiance(const ShadingParameters& p, const glm::vec3& floorAlbedo);

}  // namespace slime
