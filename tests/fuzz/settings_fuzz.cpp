// libFuzzer target for everything a user can type or feed as settings: scene files (JSON),
// `--set key=value` overrides and scenario files (parsed, then replayed for a few steps on a small
// slime). The first byte picks the reader; the rest is the input. Any exception other than
// SettingsError (or a crash, hang, leak or sanitizer report) is a bug.
#include "core/simulation/scenario.h"
#include "core/settings/settings_io.h"
#include "core/simulation/simulation.h"

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  slime::Settings settings = slime::defaultSettings();
  try {
    if (data[0] % 3 == 2) {
      const nlohmann::json document = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
      if (document.is_discarded()) return 0;
      slime::ScenarioPlayer player(slime::parseScenario(document, "fuzz"));
      settings.slime.level = 1;
      slime::Simulation simulation(settings);
      for (int step = 0; step < 50; ++step) {  // events are due at their time; t is clamped by the steps
        player.advanceTo(simulation.time(), simulation, settings);
        simulation.step();
      }
      return 0;
    }
    if (data[0] % 3 == 0) {
      const nlohmann::json scene = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
      if (scene.is_discarded()) return 0;
      slime::applySceneJson(settings, scene, "fuzz");
    } else {
      for (std::size_t start = 0; start <= text.size();) {  // one override per line
        const std::size_t end = std::min(text.find('\n', start), text.size());
        slime::applyOverride(settings, std::string_view(text).substr(start, end - start));
        start = end + 1;
      }
    }
    slime::validateSettings(settings);
    (void)slime::settingsToJson(settings).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  } catch (const slime::SettingsError&) {
  }
  return 0;
}
