// Grabbing the slime with the mouse, as geometry only (the viewer makes the Simulation calls).
// A left-press picks a surface point; while the button is held the grab target follows the cursor in
// the plane through that point facing the camera (the plane stays put even if the camera moves), and
// pressing — Shift+vertical drag or the wheel — pushes the target along the view ray into the body.
#pragma once

#include "core/geometry/camera.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <optional>

namespace slime {

// Where a world point appears in a window of `windowSize` pixels; empty if it is behind the eye.
std::optional<glm::dvec2> projectToWindow(const Camera& camera, const glm::dvec3& point, glm::ivec2 windowSize);

// The unit ray direction through a cursor position (window pixels, origin top-left).
glm::dvec3 cursorRay(const Camera& camera, glm::dvec2 cursor, glm::ivec2 windowSize);

class GrabInteraction {
 public:
  static constexpr double kRadiusFraction = 0.35;   // grab radius as a fraction of the slime radius
  static constexpr double kPressPerNotch = 0.004;   // metres of press per wheel notch

  // Starts a grab at the picked surface point, seen from the camera, with the cursor at `cursor`.
  void begin(const glm::dvec3& point, const Camera& camera, glm::dvec2 cursor);
  void end() { active_ = false; }
  bool active() const { return active_; }

  // Follows the cursor. With `press` (Shift held) vertical motion pushes in (down) or pulls out (up)
  // instead, and the target keeps its place in the plane.
  void moveCursor(glm::dvec2 cursor, bool press, const Camera& camera, glm::ivec2 windowSize);

  // Pushes the target `notches` × kPressPerNotch along the view ray (positive: into the body).
  void pressBy(double notches) { pressDepth_ += notches * kPressPerNotch; }

  // The grab target: where the ray through the cursor meets the drag plane, pushed pressDepth along it.
  glm::dvec3 target(const Camera& camera, glm::ivec2 windowSize) const;

  double pressDepth() const { return pressDepth_; }

 private:
  bool active_ = false;
  glm::dvec3 planePoint_{0.0};
  glm::dvec3 planeNormal_{0.0, 1.0, 0.0};
  glm::dvec2 planeCursor_{0.0};  // the cursor that places the target in the plane
  glm::dvec2 lastCursor_{0.0};
  double pressDepth_ = 0.0;
};

}  // namespace slime
