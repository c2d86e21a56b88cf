#include "core/settings/setting_info.h"

#include <sstream>
#include <type_traits>

#include "core/settings/settings_fields.h"
#include "core/settings/settings_io.h"

namespace slime {
namespace {

using nlohmann::json;

// The widest integer range whose every value is tried against validateSettings to find the ones it
// refuses (render.spp: only squares); wider ranges are taken to be whole.
constexpr double kWidestCheckedRange = 64.0;

template <class Field>
json toJson(const Field& field) {
  if constexpr (std::is_same_v<Field, glm::dvec3>)
    return json::array({field.x, field.y, field.z});
  else
    return json(field);
}

// The values of an integer setting that validation accepts, when it refuses some of [min, max].
std::vector<int> acceptedValues(const Settings& settings, const std::string& key, const Limits& limits) {
  if (limits.max - limits.min > kWidestCheckedRange) return {};
  std::vector<int> accepted;
  bool refusedSome = false;
  for (int value = static_cast<int>(limits.min); value <= static_cast<int>(limits.max); ++value) {
    Settings trial = settings;
    try {
      setSetting(trial, key, json(value));
      validateSettings(trial);
      accepted.push_back(value);
    } catch (const SettingsError&) {
      refusedSome = true;
    }
  }
  return refusedSome ? accepted : std::vector<int>{};
}

std::string formatNumber(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace

std::vector<SettingInfo> describeSettings(const Settings& settings) {
  std::vector<SettingInfo> described;
  Settings copy = settings;
  forEachField(copy, [&](std::string_view key, auto& field, const auto& allowed, std::string_view help) {
    using Field = std::decay_t<decltype(field)>;
    SettingInfo info;
    info.key = std::string(key);
    info.help = std::string(help);
    info.value = toJson(field);
    if constexpr (std::is_same_v<std::decay_t<decltype(allowed)>, Limits>) {
      info.min = allowed.min;
      info.max = allowed.max;
      info.unit = std::string(allowed.unit);
      if constexpr (std::is_same_v<Field, int>) {
        info.type = SettingType::Integer;
        info.onlyValues = acceptedValues(settings, info.key, allowed);
      } else {
        info.type = std::is_same_v<Field, glm::dvec3> ? SettingType::Vector : SettingType::Number;
      }
    } else if constexpr (std::is_same_v<Field, bool>) {
      info.type = SettingType::Boolean;
    } else {
      info.type = allowed.empty() ? SettingType::Text : SettingType::Choice;
      for (std::string_view choice : allowed) info.choices.emplace_back(choice);
    }
    described.push_back(std::move(info));
  });
  return described;
}

const char* typeName(SettingType type) {
  switch (type) {
    case SettingType::Number:
      return "number";
    case SettingType::Integer:
      return "integer";
    case SettingType::Vector:
      return "vector";
    case SettingType::Text:
      return "text";
    case SettingType::Choice:
      return "choice";
    case SettingType::Boolean:
      return "boolean";
  }
  return "?";
}

std::string allowedText(const SettingInfo& info) {
  std::string text;
  switch (info.type) {
    case SettingType::Number:
    case SettingType::Integer:
      if (!info.onlyValues.empty()) {
        for (std::size_t i = 0; i < info.onlyValues.size(); ++i)
          text += (i ? ", " : "") + std::to_string(info.onlyValues[i]);
        return text;
      }
      return formatNumber(info.min) + " to " + formatNumber(info.max);
    case SettingType::Vector:
      return "x,y,z each " + formatNumber(info.min) + " to " + formatNumber(info.max);
    case SettingType::Text:
      return "any text";
    case SettingType::Boolean:
      return "true or false";
    case SettingType::Choice:
      for (std::size_t i = 0; i < info.choices.size(); ++i) text += (i ? ", " : "") + info.choices[i];
      return text;
  }
  return text;
}

json settingValue(const Settings& settings, const std::string& key) {
  Settings copy = settings;
  json value;
  bool found = false;
  forEachField(copy, [&](std::string_view name, auto& field, const auto&) {
    if (name == key) value = toJson(field), found = true;
  });
  if (!found) throw SettingsError("unknown setting '" + key + "'");
  return value;
}

}  // namespace slime
