#include "app/viewer/ui_snapshot.h"

#include "app/viewer/headless_gl.h"
#include "app/viewer/viewer.h"

namespace slime {

// Dear ImGui sizes auto-resizing windows from the previous frame's contents, so the layout is final
// from the third frame on.
constexpr int kFramesForLayout = 3;

void writeUiSnapshot(const Settings& settings, const std::string& path,
                     const std::function<void(Simulation&)>& settle) {
  HeadlessGl backend(settings.camera.width, settings.camera.height);
  ViewerOptions options;
  options.maxFrames = kFramesForLayout;
  options.screenshotOnExit = path;
  Viewer viewer(backend, settings, options);
  if (settle) {
    settle(viewer.simulation());
    viewer.simulationAdvanced();
  }
  while (viewer.frame()) {
  }
}

}  // namespace slime
