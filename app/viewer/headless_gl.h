// The headless back-end of the viewer: a GL 3.3 core context without a display — EGL surfaceless or
// OSMesa, both Mesa's llvmpipe — drawing into an FBO of a fixed size. No input arrives and time
// stands still, so the same frame code that runs the window draws a reproducible picture of it;
// unless setRealTime: then the wall clock runs as in a window (`slime bench viewer`, which times the
// viewer's frames through a scenario).
#pragma once

#include "app/viewer/viewer_backend.h"

#include <chrono>
#include <memory>
#include <string>

namespace slime {

class EglContext;
class OsMesaContext;

// Which library gives the headless context (`--gl`): auto tries EGL and falls back to OSMesa,
// saying so on stderr, when EGL gives no context (no vendor library, a broken driver).
enum class HeadlessApi { Auto, Egl, OsMesa };
HeadlessApi headlessApiNamed(const std::string& name);  // "auto", "egl", "osmesa"; else SettingsError
const char* nameOf(HeadlessApi api);

class HeadlessGl final : public ViewerBackend {
 public:
  // Throws std::runtime_error saying why no context could be made (both reasons, for auto).
  HeadlessGl(int width, int height, HeadlessApi api = HeadlessApi::Auto);
  ~HeadlessGl() override;
  HeadlessGl(const HeadlessGl&) = delete;
  HeadlessGl& operator=(const HeadlessGl&) = delete;

  HeadlessApi api() const { return api_; }  // the one in use: Egl or OsMesa
  // Real time: each frame's input carries the wall time since the last, and waitForInput sleeps (no
  // input can come), as a window's would.
  void setRealTime(bool realTime) { realTime_ = realTime; }
  FrameInput pollInput() override;
  glm::ivec2 framebufferSize() const override { return size_; }
  glm::ivec2 windowSize() const override { return size_; }
  void initImGuiPlatform() override;
  void newImGuiPlatformFrame() override;
  void shutdownImGuiPlatform() override;
  bool keepsFramebuffer() const override { return true; }  // an FBO: its pixels stay
  void present(const std::vector<PixelRect>& changed) override;
  void waitForInput(double seconds) override;

 private:
  glm::ivec2 size_;
  HeadlessApi api_;
  std::unique_ptr<EglContext> egl_;
  std::unique_ptr<OsMesaContext> osMesa_;
  unsigned framebuffer_ = 0;
  unsigned colorBuffer_ = 0;
  bool realTime_ = false;
  std::chrono::steady_clock::time_point lastPoll_{};
  bool polled_ = false;
};

}  // namespace slime
