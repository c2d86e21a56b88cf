// Reading, overriding and validating Settings. Order of precedence: the embedded default scene, then
// a scene file, then `--set key=value` overrides (dotted keys such as `slime.level`, `camera.position`).
// Every error names the key, the value and what is allowed; nothing is clamped silently.
#pragma once

#include "core/settings/settings.h"

#include <nlohmann/json_fwd.hpp>

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace slime {

// A bad setting, scene file or override. The CLI prints what() and exits with code 2.
class SettingsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The embedded default scene (assets/default.json), validated.
Settings defaultSettings();

// Applies every key of a scene document (nested objects: {"slime": {"level": 5}}) onto settings.
void applySceneJson(Settings& settings, const nlohmann::json& scene, std::string_view origin);

// Reads a scene file (JSON) and applies it; a missing/unreadable file or bad JSON is a SettingsError.
void applySceneFile(Settings& settings, const std::string& path);

// Applies one `key=value` override: numbers, booleans, strings, and vectors written `x,y,z`.
void applyOverride(Settings& settings, std::string_view assignment);

// Sets one dotted key from a JSON value (used by overrides, scene files and scenario "set" events).
void setSetting(Settings& settings, std::string_view key, const nlohmann::json& value);

// Checks every field against its allowed range; throws SettingsError naming the first bad key.
void validateSettings(const Settings& settings);

// Every setting as a nested JSON document (the format of scene files).
nlohmann::json settingsToJson(const Settings& settings);

// All dotted keys that setSetting accepts.
std::vector<std::string> settingKeys();

}  // namespace slime
