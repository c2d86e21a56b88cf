// Moves the camera of the settings from the user's keys and mouse. Keys are the seed's (W/S forward and
// back, A/D left and right, Q/E turn, R/F tilt), scaled by the frame's wall time so speed does not
// depend on the frame rate. The mouse works as in Embree's tutorial viewer, with the left button left
// free for grabbing the slime: right-drag orbits around the slime, middle-drag pans, the wheel zooms.
#pragma once

#include "app/viewer/frame_input.h"
#include "core/settings/settings.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <optional>

namespace slime {

class CameraController {
 public:
  static constexpr double kMoveSpeed = 0.15;       // m/s for W/S/A/D
  static constexpr double kTurnSpeed = 45.0;       // deg/s for Q/E/R/F
  static constexpr double kOrbitPerPixel = 0.3;    // degrees of orbit per pixel of right-drag
  static constexpr double kZoomPerNotch = 0.9;     // distance factor per wheel notch towards the centre
  static constexpr double kMinDistance = 0.03;     // closest approach to the orbit centre, m
  static constexpr double kMaxPitch = 89.0;        // degrees: the pinhole frame degenerates at ±90

  // Moves and turns for the held camera keys; true if the camera changed.
  bool applyKeys(const FrameInput& input, CameraSettings& camera) const;

  // Starts or ends a right/middle drag for a button event the UI did not take.
  void handleButton(const MouseButtonEvent& event);

  // Orbits or pans for the cursor motion of an ongoing drag, zooms for `wheel` notches; true if the
  // camera changed. `centre` is the point orbited around and zoomed towards (the slime).
  bool applyMouse(glm::dvec2 cursor, glm::ivec2 windowSize, double wheel, const glm::dvec3& centre,
                  CameraSettings& camera);

  // Turns the eye about `centre` by the angles (counter-clockwise about +z seen from above, and up)
  // at its distance, looking at the centre: what a right-drag does, and a scenario's "orbit" event.
  static void orbit(double azimuthDegrees, double elevationDegrees, const glm::dvec3& centre, CameraSettings& camera);

  bool dragging() const { return drag_.has_value(); }

 private:
  struct Drag {
    MouseButton button;
    glm::dvec2 lastCursor;
  };
  std::optional<Drag> drag_;
};

}  // namespace slime
