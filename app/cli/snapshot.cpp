#include "app/cli/snapshot.h"

#include "core/simulation/scenario.h"
#include "core/settings/settings_io.h"
#include "core/simulation/simulation.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <string>

namespace slime {

void applyImageSize(Settings& settings, const std::string& size) {
  constexpr long kLargest = 8192;
  const auto fail = [&] {
    return SettingsError("--size must be WxH with W and H whole numbers in 1.." + std::to_string(kLargest) +
                         " pixels, got '" + size + "'");
  };
  const std::size_t separator = size.find_first_of("xX");
  if (separator == std::string::npos) throw fail();
  const std::string widthText = size.substr(0, separator), heightText = size.substr(separator + 1);
  const auto parse = [&](const std::string& text) {
    if (text.empty() || text.size() > 6) throw fail();
    for (const char c : text)
      if (!std::isdigit(static_cast<unsigned char>(c))) throw fail();
    const long value = std::stol(text);
    if (value < 1 || value > kLargest) throw fail();
    return static_cast<int>(value);
  };
  settings.camera.width = parse(widthText);
  settings.camera.height = parse(heightText);
}

Settings settleForSnapshot(Simulation& simulation, const Settings& initialSettings, double settleSeconds,
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
  const double limit = untilRest ? lastEvent + kMaxSettleSeconds : settleSeconds;
  const auto steps = static_cast<std::int64_t>(std::llround(limit / dt));
  const auto checkEvery = std::max<std::int64_t>(1, std::llround(0.01 / dt));
  while (simulation.stepCount() < steps) {
    if (player) player->advanceTo(simulation.time(), simulation, settings);
    simulation.step();
    const bool scenarioDone = !player || (player->finished() && simulation.time() >= lastEvent);
    if (untilRest && scenarioDone && simulation.time() >= kMinSettleSeconds &&
        simulation.stepCount() % checkEvery == 0 && simulation.metrics().maxSpeed < kRestSpeed)
      break;
  }
  return settings;
}

SnapshotResult takeSnapshot(const Settings& initialSettings, double settleSeconds, const std::string& scenarioFile) {
  Renderer renderer(initialSettings);  // first: a bad floor image fails before any simulating
  Simulation simulation(initialSettings);
  const Settings settings = settleForSnapshot(simulation, initialSettings, settleSeconds, scenarioFile);

  SnapshotResult result;
  result.simulatedSeconds = simulation.time();
  result.metrics = simulation.metrics();
  result.divergences = simulation.divergences().size();
  result.surface = surfaceMeshOf(simulation.time(), simulation.surfaces());
  result.slime = settings.slime;
  renderer.updateSlime(simulation.surfaces());
  result.image.resize(settings.camera.width, settings.camera.height);
  result.stats = renderer.render(settings, result.image);
  return result;
}

}  // namespace slime
