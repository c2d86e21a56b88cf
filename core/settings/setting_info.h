// Every setting described for people and for generated UIs: its key, type, allowed values, unit,
// one-line meaning and value, all read from the one table of settings (settings_fields.h). `slime
// settings` prints it; the viewer builds its panels from it.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/settings/settings.h"

namespace slime {

enum class SettingType { Number, Integer, Vector, Text, Choice, Boolean };

struct SettingInfo {
  std::string key;  // dotted key, e.g. "slime.level"
  SettingType type = SettingType::Number;
  double min = 0.0;  // Number, Integer and each component of a Vector
  double max = 0.0;
  std::string unit;                  // may be empty (a dimensionless coefficient)
  std::vector<std::string> choices;  // Choice: the allowed words
  std::vector<int> onlyValues;       // Integer: when validation accepts only some of [min, max] (render.spp)
  std::string help;                  // one-line meaning
  nlohmann::json value;              // the value in the settings it was described from

  std::string group() const { return key.substr(0, key.find('.')); }  // "slime" of "slime.level"
  std::string name() const { return key.substr(key.find('.') + 1); }  // "level" of "slime.level"
  // The slime.model the setting acts on alone — its meaning in the table starts "bulk:" or
  // "membrane:" — or "" when it acts on both.
  std::string model() const {
    for (const char* only : {"bulk", "membrane"})
      if (help.rfind(std::string(only) + ":", 0) == 0) return only;
    return "";
  }
};

// Every setting in table order, with its value taken from `settings`.
std::vector<SettingInfo> describeSettings(const Settings& settings);

// "number", "integer", "vector", "text", "choice", "boolean".
const char* typeName(SettingType type);

// What a value must be, as `slime settings` prints it: "0 to 7", "one of mesh, sphere", "1, 4, 9, ...".
std::string allowedText(const SettingInfo& info);

// The value of one dotted key as JSON (vectors as [x, y, z]); throws SettingsError for an unknown key.
nlohmann::json settingValue(const Settings& settings, const std::string& key);

}  // namespace slime
