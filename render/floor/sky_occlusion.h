// How much of the ambient (sky) light a floor point loses to the slime standing between it and the sky.
//
// The ambient term albedo × I_a is what a uniform sky of radiance I_a gives a Lambertian floor that sees
// all of it. Beside and under the slime part of that sky is seen through the jelly, which absorbs: a
// path-traced reference (scripts/reference/, Cycles) found the green slime's shadow 29, 19 and 28 % darker
// in red, green and blue than an unoccluded ambient makes it (docs/rendering.md, "The shadow's colour").
// Each piece of the slime is taken as a ball of its volume V at its centroid c (radius R = ∛(3V/4π)):
//  - the share of the floor point's cosine-weighted sky it covers is the form factor of a ball seen from
//    a surface element, F = (R/D)² cos β (D the distance to c, β the angle of c above the horizon, so
//    cos β = c_z / D), at most 1;
//  - it passes t_c = k_t exp(−σ_c · n² · 4V/A) of what lies behind it in channel c: 4V/A is the mean
//    chord of a convex body (Cauchy) and n² the lengthening of light's mean path inside a clear body of
//    index n under uniform light (the invariance of the mean path length: light trapped by total internal
//    reflection stays longer), A the piece's area; k_t is classic shading's transmission (1 in physical,
//    where it is in σ). Fresnel's reflection is left out: what the jelly reflects is sky too.
// So the ambient is albedo × I_a × (1 − Σ F (1 − t_c)), the sum over the pieces at most 1. F falls
// as 1/D³ away from the piece; it is tapered smoothly to 0 between kTaperStart and kReach radii from
// its centroid (on the floor), so that the floor beyond does not change when the slime moves and the
// renderer's screen footprint (render/slime/screen_footprint.h) covers every point it reaches.
#pragma once

#include "render/slime/slime_geometry.h"
#include "render/trace/shading_parameters.h"

#include <glm/vec3.hpp>

#include <vector>

namespace slime {

// The occlusion's support, in the piece's equivalent radii R from its centroid, measured on the floor.
constexpr float kSkyOcclusionTaperStart = 1.5f;
constexpr float kSkyOcclusionReach = 2.25f;

struct SkyBlocker {
  glm::vec3 centroid{0.0f};
  float radius2 = 0.0f;                     // R², m²
  float taperStart2 = 0.0f, reach2 = 0.0f;  // (1.5 R)² and (2.5 R)², horizontal distances², m²
  glm::vec3 absorbed{0.0f};                 // 1 − t_c
};

// The discs on the floor (centre x, y and radius, m) outside which no piece occludes the sky.
struct SkyDisc {
  float x = 0.0f, y = 0.0f, radius = 0.0f;
};
std::vector<SkyDisc> skyOcclusionDiscs(const SlimeGeometry& geometry);

// The pieces as the floor's ambient sees them (empty when there is no ambient light or no slime).
std::vector<SkyBlocker> skyBlockers(const SlimeGeometry& geometry, const ShadingParameters& parameters);

// The share of the ambient light reaching floor point `point` (z = 0), per channel: 1 outside every
// piece's reach.
inline glm::vec3 skyVisibility(const std::vector<SkyBlocker>& blockers, const glm::vec3& point) {
  glm::vec3 lost(0.0f);
  for (const SkyBlocker& b : blockers) {
    const float dx = point.x - b.centroid.x, dy = point.y - b.centroid.y;
    const float horizontal2 = dx * dx + dy * dy;
    if (horizontal2 >= b.reach2) continue;
    const float distance2 = horizontal2 + b.centroid.z * b.centroid.z;
    // (R/D)² cos β with cos β = c_z / D.
    float covered = b.centroid.z > 0.0f ? b.radius2 * b.centroid.z / (distance2 * std::sqrt(distance2)) : 1.0f;
    covered = std::min(covered, 1.0f);
    if (horizontal2 > b.taperStart2) {
      const float s = (b.reach2 - horizontal2) / (b.reach2 - b.taperStart2);  // 1 → 0 over the taper
      covered *= s * s * (3.0f - 2.0f * s);
    }
    lost += covered * b.absorbed;
  }
  return glm::max(glm::vec3(1.0f) - lost, glm::vec3(0.0f));
}

}  // namespace slime
