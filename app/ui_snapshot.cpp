#include "app/ui_snapshot.h"

#include "app/headless_gl.h"
#include "app/snapshot.h"
#include "app/viewer.h"
#include "core/scenario.h"

#include <algorithm>
#include <cmath>
#include <optional>

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
  if (settle) settle(viewer.simulation());
  while (viewer.frame()) {
  }
}

void settleForSnapshot(Simulation& simulation, const Settings& initialSettings, double settleSeconds,
                       const std::string& scenarioFile) {
  Settings settings = initialSettings;  // scenario "set" events change it as they fire
  std::optional<ScenarioPlayer> player;
  double lastEvent = 0.0;
  if (!scenarioFile.empty()) {
    Scenario scenario = loadScenario(scenarioFile);
    for (const ScenarioEvent& event : scenario.events) lastEvent = std::max(lastEvent, event.time + event.duration);
    player.emplace(std::move(scenario));
  }
  const double dt = settings.sim.dt;
  const bool untilRest = settleSeconds < 0.0;
  const auto steps = std::llround((untilRest ? lastEvent + kMaxSettleSeconds : settleSeconds) / dt);
  const auto checkEvery = std::max<long long>(1, std::llround(0.01 / dt));
  while (simulation.stepCount() < steps) {
    if (player) player->advanceTo(simulation.time(), simulation, settings);
    simulation.step();
    const bool scenarioDone = !player || (player->finished() && simulation.time() >= lastEvent);
    if (untilRest && scenarioDone && simulation.time() >= kMinSettleSeconds &&
        simulation.stepCount() % checkEvery == 0 && simulation.metrics().maxSpeed < kRestSpeed)
      break;
  }
}

}  // namespace slime
