#include "app/viewer/headless_gl.h"

#include "app/viewer/egl_context.h"
#include "app/viewer/gl.h"
#include "app/viewer/osmesa_context.h"
#include "core/settings/settings_io.h"

#include <imgui.h>

#include <cfloat>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <thread>

namespace slime {

HeadlessApi headlessApiNamed(const std::string& name) {
  if (name == "auto") return HeadlessApi::Auto;
  if (name == "egl") return HeadlessApi::Egl;
  if (name == "osmesa") return HeadlessApi::OsMesa;
  throw SettingsError("--gl " + name + ": expected egl, osmesa or auto");
}

const char* nameOf(HeadlessApi api) {
  switch (api) {
    case HeadlessApi::Egl: return "egl";
    case HeadlessApi::OsMesa: return "osmesa";
    case HeadlessApi::Auto: break;
  }
  return "auto";
}

HeadlessGl::HeadlessGl(int width, int height, HeadlessApi api) : size_(width, height), api_(api) {
  if (api == HeadlessApi::Egl) {
    egl_ = std::make_unique<EglContext>();
  } else if (api == HeadlessApi::OsMesa) {
    osMesa_ = std::make_unique<OsMesaContext>(width, height);
  } else {
    try {
      egl_ = std::make_unique<EglContext>();
      api_ = HeadlessApi::Egl;
    } catch (const std::runtime_error& eglFailure) {
      std::fprintf(stderr, "headless GL: %s\nheadless GL: drawing with OSMesa instead\n", eglFailure.what());
      try {
        osMesa_ = std::make_unique<OsMesaContext>(width, height);
      } catch (const std::runtime_error& osMesaFailure) {
        throw std::runtime_error(std::string("headless GL: no context from EGL (") + eglFailure.what() +
                                 ") nor from OSMesa (" + osMesaFailure.what() + ")");
      }
      api_ = HeadlessApi::OsMesa;
    }
  }

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
}

FrameInput HeadlessGl::pollInput() {
  FrameInput input;
  input.windowSize = size_;
  input.cursor = {-1.0, -1.0};  // no cursor: nothing is hovered
  if (realTime_) {
    const auto now = std::chrono::steady_clock::now();
    if (polled_) input.elapsedSeconds = std::chrono::duration<double>(now - lastPoll_).count();
    lastPoll_ = now;
    polled_ = true;
  }
  return input;
}

void HeadlessGl::waitForInput(double seconds) {
  if (realTime_ && seconds > 0.0) std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
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
