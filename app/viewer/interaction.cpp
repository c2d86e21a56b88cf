#include "app/viewer/interaction.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace slime {

std::optional<glm::dvec2> projectToWindow(const Camera& camera, const glm::dvec3& point, glm::ivec2 windowSize) {
  const glm::dvec3 offset = point - camera.position;
  const double depth = glm::dot(offset, camera.forward);
  if (depth <= 1e-9) return std::nullopt;
  // Invert Camera::rayDirection: x = (2u - 1) tan(fov/2) aspect, y = (1 - 2v) tan(fov/2).
  const double x = glm::dot(offset, camera.right) / depth;
  const double y = glm::dot(offset, camera.up) / depth;
  const double u = (x / (camera.tanHalfFov * camera.aspect) + 1.0) / 2.0;
  const double v = (1.0 - y / camera.tanHalfFov) / 2.0;
  return glm::dvec2(u * windowSize.x, v * windowSize.y);
}

glm::dvec3 cursorRay(const Camera& camera, glm::dvec2 cursor, glm::ivec2 windowSize) {
  return camera.rayDirection(cursor.x / std::max(windowSize.x, 1), cursor.y / std::max(windowSize.y, 1));
}

void GrabInteraction::begin(const glm::dvec3& point, const Camera& camera, glm::dvec2 cursor) {
  active_ = true;
  planePoint_ = point;
  planeNormal_ = camera.forward;
  planeCursor_ = cursor;
  lastCursor_ = cursor;
  pressDepth_ = 0.0;
}

void GrabInteraction::moveCursor(glm::dvec2 cursor, bool press, const Camera& camera, glm::ivec2 windowSize) {
  if (!active_) return;
  if (press && windowSize.y > 0) {
    // One pixel of vertical motion presses as far as one pixel spans at the grab depth.
    const double depth = std::max(glm::dot(planePoint_ - camera.position, camera.forward), 1e-3);
    const double metresPerPixel = 2.0 * camera.tanHalfFov * depth / windowSize.y;
    pressDepth_ += (cursor.y - lastCursor_.y) * metresPerPixel;
  } else {
    planeCursor_ = cursor;
  }
  lastCursor_ = cursor;
}

glm::dvec3 GrabInteraction::target(const Camera& camera, glm::ivec2 windowSize) const {
  const glm::dvec3 direction = cursorRay(camera, planeCursor_, windowSize);
  const double facing = glm::dot(direction, planeNormal_);
  // A ray parallel to the plane (camera turned 90° mid-drag) keeps the grab point where it was.
  glm::dvec3 onPlane = planePoint_;
  if (std::abs(facing) > 1e-6) {
    const double distance = glm::dot(planePoint_ - camera.position, planeNormal_) / facing;
    if (distance > 0.0) onPlane = camera.position + distance * direction;
  }
  return onPlane + pressDepth_ * direction;
}

}  // namespace slime
