#include "app/cli/commands.h"
#include "core/settings/settings_io.h"

namespace slime {

void addSceneOptions(CLI::App& command, SceneOptions& options) {
  command.add_option("--scene", options.sceneFile, "Scene file (JSON) applied over the embedded default scene");
  command.add_option("--set", options.overrides, "Override one setting, e.g. --set slime.level=5 --set slime.color=0.2,0.8,0.3")
      ->allow_extra_args(false);
  command.add_option("--scenario", options.scenarioFile, "Scenario file (JSON) of timed grab/drag/release/press/set events");
}

Settings loadSettings(const SceneOptions& options) {
  Settings settings = defaultSettings();
  if (!options.sceneFile.empty()) applySceneFile(settings, options.sceneFile);
  for (const std::string& assignment : options.overrides) applyOverride(settings, assignment);
  validateSettings(settings);
  return settings;
}

}  // namespace slime
