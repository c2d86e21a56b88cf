#include "app/viewer/window.h"

#include "app/viewer/gl_loader.h"

#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>
#include <imgui.h>

#include <cstdio>
#include <stdexcept>

#include <GL/glx.h>  // last: X11's macros (None, Bool, ...) would clash with the headers above

// GLFW's native access (glfw3native.h would also need the XRandR headers).
extern "C" Display* glfwGetX11Display(void);
extern "C" GLXWindow glfwGetGLXWindow(GLFWwindow* window);

namespace {
using CopySubBufferMesa = void (*)(Display*, GLXDrawable, int x, int y, int width, int height);
}

namespace slime {
namespace {

void reportGlfwError(int code, const char* description) {
  std::fprintf(stderr, "slime: GLFW error %d: %s\n", code, description);
}

// The seed's keys, in CameraKey order.
constexpr int kCameraKeyCodes[kCameraKeyCount] = {GLFW_KEY_W, GLFW_KEY_S, GLFW_KEY_A, GLFW_KEY_D,
                                                  GLFW_KEY_Q, GLFW_KEY_E, GLFW_KEY_R, GLFW_KEY_F};

Window& owner(GLFWwindow* window) { return *static_cast<Window*>(glfwGetWindowUserPointer(window)); }

}  // namespace

Window::Window(const std::string& title, int width, int height, bool presentChanges) {
  glfwSetErrorCallback(reportGlfwError);
  if (!glfwInit()) throw std::runtime_error("cannot initialise GLFW (is there a display? try `slime snapshot --ui`)");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  // Nothing drawn uses depth or stencil (the blit and the panels are 2-D). Without them Mesa's software
  // rasterizer, which draws this window under Xvfb, keeps its faster paths: 0.7 ms a frame at
  // 1280x720 with the rectangle blit (gl_blit.cpp), measured 2026-11-24.
  glfwWindowHint(GLFW_DEPTH_BITS, 0);
  glfwWindowHint(GLFW_STENCIL_BITS, 0);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    throw std::runtime_error("cannot create a GL 3.3 core window");
  }
  glfwMakeContextCurrent(window_);
  try {
    loadGl([](const char* name) { return reinterpret_cast<void*>(glfwGetProcAddress(name)); });
  } catch (...) {
    glfwDestroyWindow(window_);
    glfwTerminate();
    throw;
  }
  glfwSwapInterval(0);  // the ray tracer sets the pace; waiting for vsync would only add latency
  glfwSetWindowUserPointer(window_, this);
  // Our callbacks first: ImGui's back-end, installed later, chains to them.
  glfwGetCursorPos(window_, &eventCursor_.x, &eventCursor_.y);
  glfwSetCursorPosCallback(window_, onCursorPos);
  glfwSetMouseButtonCallback(window_, onMouseButton);
  glfwSetScrollCallback(window_, onScroll);
  glfwSetKeyCallback(window_, onKey);
  glfwSetWindowRefreshCallback(window_, onRefresh);
  if (presentChanges && glfwExtensionSupported("GLX_MESA_copy_sub_buffer")) {
    display_ = glfwGetX11Display();
    glxWindow_ = glfwGetGLXWindow(window_);
    if (display_ && glxWindow_ != 0) copySubBuffer_ = glfwGetProcAddress("glXCopySubBufferMESA");
  }
  lastTime_ = glfwGetTime();
}

Window::~Window() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

void Window::onMouseButton(GLFWwindow* window, int button, int action, int mods) {
  MouseButtonEvent event;
  if (button == GLFW_MOUSE_BUTTON_LEFT) event.button = MouseButton::Left;
  else if (button == GLFW_MOUSE_BUTTON_RIGHT) event.button = MouseButton::Right;
  else if (button == GLFW_MOUSE_BUTTON_MIDDLE) event.button = MouseButton::Middle;
  else return;
  event.pressed = action == GLFW_PRESS;
  event.position = owner(window).eventCursor_;
  event.shift = (mods & GLFW_MOD_SHIFT) != 0;
  event.control = (mods & GLFW_MOD_CONTROL) != 0;
  owner(window).pending_.buttons.push_back(event);
}

void Window::onCursorPos(GLFWwindow* window, double x, double y) { owner(window).eventCursor_ = {x, y}; }

void Window::onScroll(GLFWwindow* window, double, double y) { owner(window).pending_.wheel += y; }

void Window::onKey(GLFWwindow* window, int key, int, int action, int mods) {
  if (action != GLFW_PRESS) return;
  FrameInput& pending = owner(window).pending_;
  if (key == GLFW_KEY_F12) pending.screenshotRequested = true;
  if (key == GLFW_KEY_ESCAPE) pending.escapePressed = true;
  if (key == GLFW_KEY_F1 || key == GLFW_KEY_H) pending.helpKey = key == GLFW_KEY_F1 ? HelpKey::F1 : HelpKey::H;
  if ((mods & GLFW_MOD_CONTROL) != 0) {  // Ctrl+S saves, Ctrl+O loads; no chord moves the camera
    pending.saveRequested = pending.saveRequested || key == GLFW_KEY_S;
    pending.loadRequested = pending.loadRequested || key == GLFW_KEY_O;
    return;
  }
  // A tap shorter than a frame still moves the camera for one frame.
  for (int index = 0; index < kCameraKeyCount; ++index)
    if (key == kCameraKeyCodes[index]) pending.cameraKeys[index] = true;
}

FrameInput Window::pollInput() {
  glfwPollEvents();
  FrameInput input = std::move(pending_);
  pending_ = FrameInput{};
  const double now = glfwGetTime();
  input.elapsedSeconds = now - lastTime_;
  lastTime_ = now;
  glfwGetCursorPos(window_, &input.cursor.x, &input.cursor.y);
  input.windowSize = windowSize();
  input.shift = glfwGetKey(window_, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
                glfwGetKey(window_, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
  input.control = glfwGetKey(window_, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS ||
                  glfwGetKey(window_, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS;
  for (int index = 0; index < kCameraKeyCount; ++index)
    input.cameraKeys[index] = !input.control && (input.cameraKeys[index] ||
                                                 glfwGetKey(window_, kCameraKeyCodes[index]) == GLFW_PRESS);
  input.closeRequested = glfwWindowShouldClose(window_);
  return input;
}

glm::ivec2 Window::framebufferSize() const {
  glm::ivec2 size;
  glfwGetFramebufferSize(window_, &size.x, &size.y);
  return size;
}

glm::ivec2 Window::windowSize() const {
  glm::ivec2 size;
  glfwGetWindowSize(window_, &size.x, &size.y);
  return size;
}

void Window::initImGuiPlatform() { ImGui_ImplGlfw_InitForOpenGL(window_, true); }
void Window::newImGuiPlatformFrame() { ImGui_ImplGlfw_NewFrame(); }
void Window::shutdownImGuiPlatform() { ImGui_ImplGlfw_Shutdown(); }
void Window::onRefresh(GLFWwindow* window) { owner(window).exposed_ = true; }

void Window::waitForInput(double seconds) {
  if (seconds > 0.0) glfwWaitEventsTimeout(seconds);  // the events go to the callbacks, for pollInput
}

void Window::present(const std::vector<PixelRect>& changed) {
  const glm::ivec2 size = framebufferSize();
  if (size.x <= 0 || size.y <= 0) {  // minimised: nothing was drawn; wait for events a little
    glfwWaitEventsTimeout(0.05);
    return;
  }
  if (!copySubBuffer_ || size != presentedSize_) {
    // A new size (and the first frame): swapped whole, which lets Mesa's window system code take the
    // window's new size before any rectangle is copied from the back buffer (a copy sized for the
    // new window from the old buffer is an X error that ends the program). A swap need not keep the
    // back buffer: the next frame is drawn whole (keepsFramebuffer), so all of it is copied.
    glfwSwapBuffers(window_);
    presentedSize_ = size;
    swapped_ = true;
    return;
  }
  swapped_ = false;
  // The back buffer keeps every pixel: copy what changed (all of it after an expose) to the window.
  // GLX counts rows from the bottom.
  const auto copy = reinterpret_cast<CopySubBufferMesa>(copySubBuffer_);
  auto* display = static_cast<Display*>(display_);
  if (exposed_) {
    copy(display, glxWindow_, 0, 0, size.x, size.y);
    exposed_ = false;
    return;
  }
  for (const PixelRect& rect : changed) {
    const PixelRect part = rect.intersectedWith({0, 0, size.x, size.y});
    if (!part.empty()) copy(display, glxWindow_, part.x0, size.y - part.y1, part.x1 - part.x0, part.y1 - part.y0);
  }
}

}  // namespace slime
