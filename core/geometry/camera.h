// The pinhole camera of the scene: an eye, a heading (yaw), an elevation (pitch) and a vertical field
// of view. Z is up. Image coordinates u, v run from 0 to 1, left to right and top to bottom.
#pragma once

#include "core/settings/settings.h"

#include <glm/vec3.hpp>

namespace slime {

struct Camera {
  glm::dvec3 position{0.0};
  glm::dvec3 forward{0.0, 1.0, 0.0};  // unit view direction
  glm::dvec3 right{1.0, 0.0, 0.0};    // unit, horizontal
  glm::dvec3 up{0.0, 0.0, 1.0};       // unit, completes the right-handed frame
  double tanHalfFov = 0.41;           // tan(vertical fov / 2)
  double aspect = 1.0;                // width / height

  // The unit direction of the ray through image point (u, v).
  glm::dvec3 rayDirection(double u, double v) const;
};

// The camera of the settings for an image of width × height pixels.
Camera makeCamera(const CameraSettings& settings, int width, int height);

// The unit view direction for a yaw and pitch in degrees (yaw 0 = +x, 90 = +y; pitch up positive).
glm::dvec3 viewDirection(double yawDegrees, double pitchDegrees);

// Yaw and pitch (degrees) that look from `eye` towards `target` (the `--vi` option).
void lookAt(CameraSettings& settings, const glm::dvec3& eye, const glm::dvec3& target);

}  // namespace slime
