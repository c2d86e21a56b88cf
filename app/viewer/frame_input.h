// What the user did since the last frame, in platform-free terms. A back-end (GLFW window or headless)
// fills it; the viewer's input step reads it. Coordinates are window pixels, origin top-left.
#pragma once

#include <glm/vec2.hpp>

#include <array>
#include <vector>

namespace slime {

// The seed's camera keys: W forward, S back, A left, D right, Q turn left, E turn right, R tilt up,
// F tilt down.
enum class CameraKey { Forward, Back, Left, Right, TurnLeft, TurnRight, TiltUp, TiltDown, Count };
inline constexpr int kCameraKeyCount = static_cast<int>(CameraKey::Count);

enum class MouseButton { Left, Right, Middle };

// One press or release, with where the cursor was and which modifiers were held at that moment.
struct MouseButtonEvent {
  MouseButton button = MouseButton::Left;
  bool pressed = true;  // false: released
  glm::dvec2 position{0.0};
  bool shift = false;
  bool control = false;
};

struct FrameInput {
  double elapsedSeconds = 0.0;              // wall time since the previous frame
  glm::dvec2 cursor{0.0};                   // cursor position now
  glm::ivec2 windowSize{0, 0};              // the space cursor coordinates live in
  std::vector<MouseButtonEvent> buttons;    // presses and releases since the last frame, in order
  double wheel = 0.0;                       // wheel notches since the last frame (up = positive)
  bool shift = false;                       // modifiers held now
  bool control = false;
  std::array<bool, kCameraKeyCount> cameraKeys{};  // held now, or tapped since the last frame
  bool screenshotRequested = false;         // F12 pressed
  bool escapePressed = false;               // Esc: quits unless a panel's text field has the keyboard
  bool closeRequested = false;              // the window's close button
  bool mouseCapturedByUi = false;           // ImGui wants the mouse: hide it from the app
  bool keyboardCapturedByUi = false;        // ImGui wants the keyboard: hide it from the app

  bool keyHeld(CameraKey key) const { return cameraKeys[static_cast<int>(key)]; }
};

}  // namespace slime
