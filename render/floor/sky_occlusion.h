// How much of the ambient (sky) light a floor point in the slime's shadow loses to the slime standing
// between it and the sky.
//
// The ambient term albedo × I_a is what a uniform sky of radiance I_a gives a Lambertian floor that sees
// all of it. Under and beside the slime part of that sky is seen through the jelly, which absorbs: a
// path-traced reference (scripts/reference/, Cycles) found the green slime's shadow 29, 19 and 28 % darker
// in red, green and blue than an unoccluded ambient makes it (docs/rendering.md, "The shadow's colour").
// Each piece of the slime is taken as a ball of its volume V at its centroid c (radius R = ∛(3V/4π)):
//  - the share of the floor point's cosine-weighted sky it covers is the form factor of a ball seen from
//    a surface element, F = (R/D)² cos β (D the distance to c, β the angle of c above the horizon, so
//    cos β = c_z / D), at most 1;
//  - it passes t_c = k_t exp(−σ_c · n² · 4V/A) of what lies behind it in channel c: 4V/A is the mean
//    chord of a convex body (Cauchy) and n² the lengthening of light's mean path inside a clear body of
//    index n under uniform light (light trapped by total internal reflection stays longer), A the
//    piece's area; k_t is classic shading's transmission (1 in physical, where it is in σ). Fresnel's
//    reflection is left out: what the jelly reflects is sky too.
// So the ambient is albedo × I_a × (1 − Σ F (1 − t_c)), the sum over the pieces at most 1.
//
// Where: only in the slime's shadow, the floor inside the convex hull of its vertices cast from the
// light onto z = 0. F falls off as 1/D³ and reaches well beyond the shadow, but there it would dim floor
// outside the renderer's screen footprint (render/slime/screen_footprint.h), which is copied from the last
// frame when the slime moves, and growing the footprint to hold it doubled the pixels traced a frame at
// 1280×720 (98 k → 206 k). At the shadow's edge the light already steps from lit to shadowed, which
// hides the step in the ambient there.
#pragma once

#include "render/slime/slime_geometry.h"
#include "render/trace/shading_parameters.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <vector>

namespace slime {

struct SkyBlocker {
  glm::vec3 centroid{0.0f};
  float radius2 = 0.0f;      // R², m²
  glm::vec3 absorbed{0.0f};  // 1 − t_c
};

class SkyOcclusion {
 public:
  SkyOcclusion() = default;
  // The slime's pieces and its shadow on the floor for this frame; none (visibility 1 everywhere)
  // without an ambient light, without shadows, or with the light not above every vertex.
  SkyOcclusion(const SlimeGeometry& geometry, const ShadingParameters& parameters);

  bool empty() const { return blockers_.empty(); }

  // The share of the ambient light reaching floor point `point` (z = 0), per channel: 1 outside the
  // shadow.
  glm::vec3 visibility(const glm::vec3& point) const {
    if (blockers_.empty() || point.x < low_.x || point.y < low_.y || point.x > high_.x || point.y > high_.y ||
        !inShadow({point.x, point.y}))
      return glm::vec3(1.0f);
    glm::vec3 lost(0.0f);
    for (const SkyBlocker& b : blockers_) {
      const float dx = point.x - b.centroid.x, dy = point.y - b.centroid.y;
      const float distance2 = dx * dx + dy * dy + b.centroid.z * b.centroid.z;
      // (R/D)² cos β with cos β = c_z / D.
      const float covered = b.centroid.z > 0.0f ? b.radius2 * b.centroid.z / (distance2 * std::sqrt(distance2)) : 1.0f;
      lost += std::min(covered, 1.0f) * b.absorbed;
    }
    return glm::max(glm::vec3(1.0f) - lost, glm::vec3(0.0f));
  }

  // Whether `p` lies inside the shadow's hull (its corners counter-clockwise): the wedge about the first
  // corner that holds it, found by bisection, then that wedge's outer edge.
  bool inShadow(glm::vec2 p) const;

  const std::vector<SkyBlocker>& blockers() const { return blockers_; }

 private:
  std::vector<SkyBlocker> blockers_;
  std::vector<glm::vec2> hull_;  // the shadow on the floor, counter-clockwise
  glm::vec2 low_{0.0f}, high_{0.0f};
};

}  // namespace slime
