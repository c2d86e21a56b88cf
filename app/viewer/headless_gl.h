// The headless back-end of the viewer: an EGL surfaceless context (Mesa llvmpipe, no display) with
// GL 3.3 core, drawing into an FBO of a fixed size. No input arrives and time stands still, so the
// same frame code that runs the window draws a reproducible picture of it.
#pragma once

#include "app/viewer/viewer_backend.h"

namespace slime {

class HeadlessGl final : public ViewerBackend {
 public:
  HeadlessGl(int width, int height);  // throws std::runtime_error naming the EGL step that failed
  ~HeadlessGl() override;
  HeadlessGl(const HeadlessGl&) = delete;
  HeadlessGl& operator=(const HeadlessGl&) = delete;

  FrameInput pollInput() override;
  glm::ivec2 framebufferSize() const override { return size_; }
  glm::ivec2 windowSize() const override { return size_; }
  void initImGuiPlatform() override;
  void newImGuiPlatformFrame() override;
  void shutdownImGuiPlatform() override;
  bool keepsFramebuffer() const override { return true; }  // an FBO: its pixels stay
  void present(const std::vector<PixelRect>& changed) override;

 private:
  glm::ivec2 size_;
  void* display_ = nullptr;  // EGLDisplay
  void* context_ = nullptr;  // EGLContext
  unsigned framebuffer_ = 0;
  unsigned colorBuffer_ = 0;
};

}  // namespace slime
