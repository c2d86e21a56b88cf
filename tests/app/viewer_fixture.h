// Helpers shared by the viewer's tests: a small scene and the headless back-end with a clock that runs.
#pragma once

#include "app/viewer/headless_gl.h"
#include "app/viewer/viewer_backend.h"
#include "core/settings/settings_io.h"

#include <vector>

namespace slime::fixture {

// The default scene in a 320×240 window with a level-2 slime: cheap to trace, still the whole viewer.
inline Settings smallViewerScene() {
  Settings settings = defaultSettings();
  settings.camera.width = 320;
  settings.camera.height = 240;
  settings.slime.level = 2;
  return settings;
}

// The headless back-end with a clock that runs: every frame `secondsPerFrame` of wall time passes, so
// the physics steps and a scenario plays, the same in every run whatever the machine's speed.
class SteppingHeadlessGl final : public ViewerBackend {
 public:
  SteppingHeadlessGl(int width, int height, double secondsPerFrame)
      : gl_(width, height), secondsPerFrame_(secondsPerFrame) {}
  FrameInput pollInput() override {
    FrameInput input = gl_.pollInput();
    input.elapsedSeconds = secondsPerFrame_;
    return input;
  }
  glm::ivec2 framebufferSize() const override { return gl_.framebufferSize(); }
  glm::ivec2 windowSize() const override { return gl_.windowSize(); }
  void initImGuiPlatform() override { gl_.initImGuiPlatform(); }
  void newImGuiPlatformFrame() override { gl_.newImGuiPlatformFrame(); }
  void shutdownImGuiPlatform() override { gl_.shutdownImGuiPlatform(); }
  bool keepsFramebuffer() const override { return gl_.keepsFramebuffer(); }
  void present(const std::vector<PixelRect>& changed) override { gl_.present(changed); }
  void waitForInput(double seconds) override { waits.push_back(seconds); }

  std::vector<double> waits;  // every waitForInput the viewer asked for, in order

 private:
  HeadlessGl gl_;
  double secondsPerFrame_;
};

}  // namespace slime::fixture
