#include "render/screen_footprint.h"

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace slime {
namespace {

constexpr double kMarginPixels = 2.0;

// Screen bounds of a set of world points, in pixel coordinates (pixel x's centre at x + 0.5).
class ScreenBounds {
 public:
  ScreenBounds(const Camera& camera, int width, int height) : camera_(camera), width_(width), height_(height) {}

  // False when the point is not in front of the eye: no finite bounds then.
  bool add(const glm::dvec3& point) {
    const glm::dvec3 d = point - camera_.position;
    const double depth = glm::dot(d, camera_.forward);
    if (!(depth > 1e-9)) return false;
    // Camera::rayDirection inverted: x = u W − 1/2 with 2u − 1 = (d·right) / (depth tan(fov/2) aspect).
    const double sx = glm::dot(d, camera_.right) / (depth * camera_.tanHalfFov * camera_.aspect);
    const double sy = glm::dot(d, camera_.up) / (depth * camera_.tanHalfFov);
    const double x = 0.5 * (sx + 1.0) * width_, y = 0.5 * (1.0 - sy) * height_;
    low_ = glm::min(low_, glm::dvec2(x, y));
    high_ = glm::max(high_, glm::dvec2(x, y));
    return true;
  }

  PixelRect rect() const {
    if (low_.x > high_.x) return {};
    const auto clampTo = [](double value, int limit) {
      return static_cast<int>(std::clamp(value, 0.0, static_cast<double>(limit)));
    };
    return {clampTo(std::floor(low_.x - kMarginPixels), width_), clampTo(std::floor(low_.y - kMarginPixels), height_),
            clampTo(std::ceil(high_.x + kMarginPixels), width_), clampTo(std::ceil(high_.y + kMarginPixels), height_)};
  }

 private:
  const Camera& camera_;
  int width_, height_;
  glm::dvec2 low_{std::numeric_limits<double>::infinity()}, high_{-std::numeric_limits<double>::infinity()};
};

}  // namespace

PixelRect slimeFootprint(const Camera& camera, const SlimeGeometry& geometry, const ShadingParameters& parameters,
                         int width, int height) {
  const PixelRect whole{0, 0, width, height};
  if (geometry.boundRadius <= 0.0f && !geometry.analyticSphere) return {};  // no slime
  // The bounding sphere's box, with the same slack as SlimeGeometry::mayHit.
  const glm::dvec3 center(geometry.boundCenter);
  const double radius = geometry.boundRadius * 1.0001 + 1e-6;
  const glm::dvec3 light(parameters.lightPosition);
  ScreenBounds bounds(camera, width, height);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 point = center + radius * glm::dvec3(corner & 1 ? 1.0 : -1.0, corner & 2 ? 1.0 : -1.0,
                                                          corner & 4 ? 1.0 : -1.0);
    if (!bounds.add(point)) return whole;
    // A varnished floor mirrors the slime: its image below z = 0 is seen there.
    if (parameters.floorSpecular > 0.0f && !bounds.add({point.x, point.y, -point.z})) return whole;
    if (!parameters.shadows || light.z <= 0.0) continue;  // no shadows, or the floor is unlit
    if (point.z >= light.z) return whole;
    // Projected from the light onto z = 0: L + (p − L) · L_z / (L_z − p_z) (a projective map, so for
    // points below the light it keeps the box's shadow inside the hull of its corners' shadows).
    const glm::dvec3 shadow = light + (point - light) * (light.z / (light.z - point.z));
    if (!bounds.add({shadow.x, shadow.y, 0.0})) return whole;
  }
  return bounds.rect();
}

}  // namespace slime
