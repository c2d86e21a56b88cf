#include "app/viewer/ui_snapshot.h"

#include "app/viewer/headless_gl.h"
#include "app/viewer/screenshot.h"
#include "app/viewer/viewer.h"

namespace slime {

// Dear ImGui sizes auto-resizing windows from the previous frame's contents, so the layout is final
// from the third frame on.
constexpr int kFramesForLayout = 3;

void writeUiSnapshot(const Settings& settings, const std::string& path,
                     const std::function<void(Simulation&)>& settle, HeadlessApi api) {
  HeadlessGl backend(settings.camera.width, settings.camera.height, api);
  ViewerOptions options;
  options.maxFrames = kFramesForLayout;
  options.screenshotOnExit = path;
  options.refineSamples = 1;  // the picture `snapshot` traces (render.spp), not a partly refined one
  Viewer viewer(backend, settings, options);
  if (settle) {
    settle(viewer.simulation());
    viewer.simulationAdvanced();
  }
  while (viewer.frame()) {
  }
}

struct UiFrames::State {
  State(const Settings& settings, HeadlessApi api) : backend(settings.camera.width, settings.camera.height, api),
                                             viewer(backend, settings) {}
  HeadlessGl backend;
  Viewer viewer;
  int frames = 0;
};

UiFrames::UiFrames(const Settings& settings, HeadlessApi api) : state_(std::make_unique<State>(settings, api)) {}
UiFrames::~UiFrames() = default;

Simulation& UiFrames::simulation() { return state_->viewer.simulation(); }

std::vector<std::uint8_t> UiFrames::draw() {
  state_->viewer.simulationAdvanced();
  // The first picture waits for the panels' layout, as writeUiSnapshot does.
  const int frames = state_->frames == 0 ? kFramesForLayout : 1;
  for (int i = 0; i < frames; ++i) state_->viewer.frame();
  ++state_->frames;
  return readFramebufferRgb(state_->backend.framebufferSize());
}

}  // namespace slime
