#include "core/geometry/camera.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <cmath>

namespace slime {

glm::dvec3 viewDirection(double yawDegrees, double pitchDegrees) {
  const double yaw = glm::radians(yawDegrees), pitch = glm::radians(pitchDegrees);
  return {std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw), std::sin(pitch)};
}

Camera makeCamera(const CameraSettings& settings, int width, int height) {
  Camera camera;
  camera.position = settings.position;
  camera.forward = viewDirection(settings.yaw, settings.pitch);
  const double yaw = glm::radians(settings.yaw);
  camera.right = {std::sin(yaw), -std::cos(yaw), 0.0};
  camera.up = glm::cross(camera.right, camera.forward);
  camera.tanHalfFov = std::tan(glm::radians(settings.fov) / 2.0);
  camera.aspect = static_cast<double>(width) / static_cast<double>(height);
  return camera;
}

glm::dvec3 Camera::rayDirection(double u, double v) const {
  const double x = (2.0 * u - 1.0) * tanHalfFov * aspect;
  const double y = (1.0 - 2.0 * v) * tanHalfFov;
  return glm::normalize(forward + x * right + y * up);
}

void lookAt(CameraSettings& settings, const glm::dvec3& eye, const glm::dvec3& target) {
  const glm::dvec3 d = target - eye;
  settings.position = eye;
  settings.yaw = glm::degrees(std::atan2(d.y, d.x));
  settings.pitch = glm::degrees(std::atan2(d.z, std::hypot(d.x, d.y)));
}

}  // namespace slime
