#include "app/viewer/camera_controller.h"

#include "core/geometry/camera.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include <algorithm>
#include <cmath>

namespace slime {
namespace {

double axis(const FrameInput& input, CameraKey positive, CameraKey negative) {
  return (input.keyHeld(positive) ? 1.0 : 0.0) - (input.keyHeld(negative) ? 1.0 : 0.0);
}

}  // namespace

bool CameraController::applyKeys(const FrameInput& input, CameraSettings& camera) const {
  const double seconds = input.elapsedSeconds;
  const double forward = axis(input, CameraKey::Forward, CameraKey::Back);
  const double sideways = axis(input, CameraKey::Right, CameraKey::Left);
  const double turn = axis(input, CameraKey::TurnLeft, CameraKey::TurnRight);
  const double tilt = axis(input, CameraKey::TiltUp, CameraKey::TiltDown);
  if (forward == 0.0 && sideways == 0.0 && turn == 0.0 && tilt == 0.0) return false;
  const Camera frame = makeCamera(camera, 1, 1);
  camera.position += (forward * frame.forward + sideways * frame.right) * (kMoveSpeed * seconds);
  camera.yaw = std::remainder(camera.yaw + turn * kTurnSpeed * seconds, 360.0);
  camera.pitch = std::clamp(camera.pitch + tilt * kTurnSpeed * seconds, -kMaxPitch, kMaxPitch);
  return true;
}

void CameraController::handleButton(const MouseButtonEvent& event) {
  if (event.button == MouseButton::Left) return;  // the left button grabs the slime
  if (event.pressed && !drag_) drag_ = Drag{event.button, event.position};
  if (!event.pressed && drag_ && drag_->button == event.button) drag_.reset();
}

void CameraController::orbit(double azimuthDegrees, double elevationDegrees, const glm::dvec3& centre,
                             CameraSettings& camera) {
  // Turn the eye about the centre on a sphere, then look at the centre.
  const glm::dvec3 offset = camera.position - centre;
  const double distance = std::max(glm::length(offset), kMinDistance);
  const double azimuth = std::atan2(offset.y, offset.x) + glm::radians(azimuthDegrees);
  const double elevation = std::clamp(std::asin(std::clamp(offset.z / distance, -1.0, 1.0)) + glm::radians(elevationDegrees),
                                      glm::radians(-kMaxPitch), glm::radians(kMaxPitch));
  const glm::dvec3 eye = centre + distance * glm::dvec3(std::cos(elevation) * std::cos(azimuth),
                                                        std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
  lookAt(camera, eye, centre);
}

bool CameraController::applyMouse(glm::dvec2 cursor, glm::ivec2 windowSize, double wheel,
                                  const glm::dvec3& centre, CameraSettings& camera) {
  bool changed = false;
  if (drag_ && cursor != drag_->lastCursor && windowSize.y > 0) {
    const glm::dvec2 delta = cursor - drag_->lastCursor;
    drag_->lastCursor = cursor;
    if (drag_->button == MouseButton::Right) {
      orbit(-delta.x * kOrbitPerPixel, delta.y * kOrbitPerPixel, centre, camera);
    } else {
      // Pan: the point under the cursor at the centre's depth stays under the cursor.
      const Camera frame = makeCamera(camera, windowSize.x, windowSize.y);
      const double depth = std::max(glm::dot(centre - camera.position, frame.forward), kMinDistance);
      const double metresPerPixel = 2.0 * frame.tanHalfFov * depth / windowSize.y;
      camera.position += (-delta.x * frame.right + delta.y * frame.up) * metresPerPixel;
    }
    changed = true;
  }
  if (wheel != 0.0) {
    // Zoom: move along the view direction by a fraction of the distance to the centre.
    const Camera frame = makeCamera(camera, 1, 1);
    const double distance = glm::length(centre - camera.position);
    const double travel = std::min(distance * (1.0 - std::pow(kZoomPerNotch, wheel)), distance - kMinDistance);
    camera.position += frame.forward * travel;
    changed = true;
  }
  return changed;
}

}  // namespace slime
