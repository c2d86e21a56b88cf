// `slime settings`: every setting with its unit, allowed values, default and one-line meaning, read
// from the one table of settings (core/settings/settings_fields.h), as a table or as JSON (--json).
#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>

#include "app/cli/commands.h"
#include "core/settings/setting_info.h"
#include "core/settings/settings_io.h"

namespace slime {
namespace {

nlohmann::json asJson(const std::vector<SettingInfo>& settings) {
  nlohmann::json list = nlohmann::json::array();
  for (const SettingInfo& info : settings) {
    nlohmann::json entry = {{"key", info.key},
                            {"type", typeName(info.type)},
                            {"default", info.value},
                            {"help", info.help},
                            {"allowed", allowedText(info)}};
    if (info.type == SettingType::Number || info.type == SettingType::Integer ||
        info.type == SettingType::Vector) {
      entry["min"] = info.min;
      entry["max"] = info.max;
      entry["unit"] = info.unit;
    }
    if (!info.onlyValues.empty()) entry["values"] = info.onlyValues;
    if (info.type == SettingType::Choice) entry["choices"] = info.choices;
    list.push_back(entry);
  }
  return list;
}

std::string shownValue(const nlohmann::json& value) {
  if (value.is_array()) {
    std::string text;
    for (const auto& component : value) text += (text.empty() ? "" : ",") + shownValue(component);
    return text;
  }
  if (value.is_string()) return value.get<std::string>().empty() ? "\"\"" : value.get<std::string>();
  return value.dump();
}

// Key, default, allowed values with the unit, and the meaning, in aligned columns.
void printTable(const std::vector<SettingInfo>& settings) {
  std::size_t keyWidth = 3, valueWidth = 7, allowedWidth = 7;
  std::vector<std::string> allowed;
  for (const SettingInfo& info : settings) {
    std::string text = allowedText(info);
    if (!info.unit.empty()) text += " " + info.unit;
    keyWidth = std::max(keyWidth, info.key.size());
    valueWidth = std::max(valueWidth, shownValue(info.value).size());
    allowedWidth = std::max(allowedWidth, text.size());
    allowed.push_back(std::move(text));
  }
  std::printf("%-*s  %-*s  %-*s  %s\n", int(keyWidth), "key", int(valueWidth), "default", int(allowedWidth),
              "allowed", "meaning");
  std::string group;
  for (std::size_t i = 0; i < settings.size(); ++i) {
    const SettingInfo& info = settings[i];
    if (info.group() != group && !group.empty()) std::printf("\n");
    group = info.group();
    // Units such as N·s/m hold multi-byte characters: pad by what a terminal shows, not by bytes.
    const auto shownWidth = [](const std::string& text) {
      return static_cast<int>(
          std::count_if(text.begin(), text.end(), [](char c) { return (c & 0xC0) != 0x80; }));
    };
    const int allowedPad = int(allowedWidth) + int(allowed[i].size()) - shownWidth(allowed[i]);
    std::printf("%-*s  %-*s  %-*s  %s\n", int(keyWidth), info.key.c_str(), int(valueWidth),
                shownValue(info.value).c_str(), allowedPad, allowed[i].c_str(), info.help.c_str());
  }
  std::printf("\nSet them in a scene file (--scene FILE, JSON nested by group) or with --set key=value.\n");
}

}  // namespace

void registerSettingsCommand(CLI::App& root, int& exitCode) {
  auto json = std::make_shared<bool>(false);
  auto* command =
      root.add_subcommand("settings", "List every setting: its default, allowed values, unit and meaning");
  command->add_flag("--json", *json, "Print the list as JSON");
  command->callback([json, &exitCode] {
    const std::vector<SettingInfo> settings = describeSettings(defaultSettings());
    if (*json)
      std::printf("%s\n", asJson(settings).dump(2).c_str());
    else
      printTable(settings);
    exitCode = 0;
  });
}

}  // namespace slime
