#include "app/viewer/headless_gl.h"

#include "app/viewer/gl.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <imgui.h>

#include <cfloat>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace slime {
namespace {

[[noreturn]] void failEgl(const char* step) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", static_cast<unsigned>(eglGetError()));
  throw std::runtime_error(std::string("headless GL: ") + step + " failed (EGL error " + code +
                           "); is Mesa's EGL installed?");
}

}  // namespace

HeadlessGl::HeadlessGl(int width, int height) : size_(width, height) {
  EGLDisplay display = eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY) failEgl("eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA)");
  if (!eglInitialize(display, nullptr, nullptr)) failEgl("eglInitialize");
  display_ = display;
  if (!eglBindAPI(EGL_OPENGL_API)) failEgl("eglBindAPI(EGL_OPENGL_API)");
  const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,
                                     EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configCount = 0;
  if (!eglChooseConfig(display, configAttributes, &config, 1, &configCount) || configCount == 0)
    failEgl("eglChooseConfig");
  const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, contextAttributes);
  if (context == EGL_NO_CONTEXT) failEgl("eglCreateContext(GL 3.3 core)");
  context_ = context;
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) failEgl("eglMakeCurrent (surfaceless)");

  // There is no window, so the frame is drawn into an FBO and read back from it. Colour only, as the
  // window (window.cpp): nothing drawn uses depth or stencil.
  glGenFramebuffers(1, &framebuffer_);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glGenRenderbuffers(1, &colorBuffer_);
  glBindRenderbuffer(GL_RENDERBUFFER, colorBuffer_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colorBuffer_);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("headless GL: the framebuffer object is incomplete");
}

HeadlessGl::~HeadlessGl() {
  glDeleteRenderbuffers(1, &colorBuffer_);
  glDeleteFramebuffers(1, &framebuffer_);
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, context_);
  eglTerminate(display_);
  eglReleaseThread();  // the thread's EGL state, which eglTerminate leaves allocated
}

FrameInput HeadlessGl::pollInput() {
  FrameInput input;
  input.windowSize = size_;
  input.cursor = {-1.0, -1.0};  // no cursor: nothing is hovered
  return input;
}

void HeadlessGl::initImGuiPlatform() {
  ImGuiIO& io = ImGui::GetIO();
  io.BackendPlatformName = "slime_headless";
}

void HeadlessGl::newImGuiPlatformFrame() {
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(static_cast<float>(size_.x), static_cast<float>(size_.y));
  io.DisplayFramebufferScale = ImVec2(1.0f, 1.0f);
  io.DeltaTime = 1.0f / 60.0f;  // ImGui needs a positive step; physics does not see it
  io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
}

void HeadlessGl::shutdownImGuiPlatform() { ImGui::GetIO().BackendPlatformName = nullptr; }

void HeadlessGl::present(const std::vector<PixelRect>&) { glFinish(); }

}  // namespace slime
