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
  // `presentChanges`: where the platform allows it (GLX_MESA_copy_sub_buffer, as Mesa's X11 drivers
  // have, llvmpipe under Xvfb among them), the frames are never swapped: the back buffer keeps its
  // pixels and each frame copies only what it drew again to the window. Otherwise, or without it,
  // every frame is drawn whole and swapped. Throws std::runtime_error.
  Window(const std::string& title, int width, int height, bool presentChanges = true);
  ~Window() override;
  Window(const Window&) = delete;
  Window& operator=(const Window&) = delete;

  FrameInput pollInput() override;
  glm::ivec2 framebufferSize() const override;
  glm::ivec2 windowSize() const override;
  void initImGuiPlatform() override;
  void newImGuiPlatformFrame() override;
  void shutdownImGuiPlatform() override;
  void waitForInput(double seconds) override;
  bool keepsFramebuffer() const override { return copySubBuffer_ != nullptr && !swapped_; }
  void present(const std::vector<PixelRect>& changed) override;

 private:
  static void onMouseButton(GLFWwindow* window, int button, int action, int mods);
  static void onCursorPos(GLFWwindow* window, double x, double y);
  static void onScroll(GLFWwindow* window, double x, double y);
  static void onKey(GLFWwindow* window, int key, int scancode, int action, int mods);
  static void onRefresh(GLFWwindow* window);

  GLFWwindow* window_ = nullptr;
  double lastTime_ = 0.0;
  FrameInput pending_;  // events gathered by the callbacks since the last pollInput
  // The cursor where the events read so far put it. A press takes its position from here, not from
  // glfwGetCursorPos: on X11 that asks the server where the pointer is now, so a press read late (a
  // slow frame) would land where the pointer has moved since.
  glm::dvec2 eventCursor_{0.0, 0.0};
  // When presenting changes: glXCopySubBufferMESA (as GLFW hands it out), the X display and the GLX
  // window it copies to; the whole back buffer is shown again after the window was exposed.
  void (*copySubBuffer_)() = nullptr;
  void* display_ = nullptr;
  unsigned long glxWindow_ = 0;
  bool exposed_ = false;            // X asked for the window's contents again (an expose)
  glm::ivec2 presentedSize_{0, 0};  // the framebuffer's size at the last present
  bool swapped_ = true;             // the last present swapped: the next frame is drawn whole
};

}  // namespace slime
