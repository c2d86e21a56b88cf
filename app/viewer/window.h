// The GLFW back-end of the viewer: a window with a GL 3.3 core context. Input arrives through GLFW
// callbacks (so a press and release between two slow frames is not lost) and is forwarded to Dear
// ImGui first; ImGui's back-end chains to ours.
#pragma once

#include "app/viewer/viewer_backend.h"

#include <string>

struct GLFWwindow;

namespace slime {

class Window final : public ViewerBackend {
 public:
  Window(const std::string& title, int width, int height);  // throws std::runtime_error
  ~Window() override;
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  FrameInput pollInput() override;
  glm::ivec2 framebufferSize() const override;
  glm::ivec2 windowSize() const override;
  void initImGuiPlatform() override;
  void newImGuiPlatformFrame() override;
  void shutdownImGuiPlatform() override;
  void present() override;

 private:
  static void onMouseButton(GLFWwindow* window, int button, int action, int mods);
  static void onScroll(GLFWwindow* window, double x, double y);
  static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);

  GLFWwindow* window_ = nullptr;
  double lastTime_ = 0.0;
  FrameInput pending_;  // events gathered by the callbacks since the last pollInput
};

}  // namespace slime
