#include "core/settings/settings_io.h"

#include "core/settings/default_scene.h"
#include "core/settings/settings_fields.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <type_traits>

namespace slime {
namespace {

using nlohmann::json;

std::string formatNumber(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::string describe(const Limits& limits, bool integer) {
  std::string text = (integer ? "an integer from " : "a number from ") + formatNumber(limits.min) +
                     " to " + formatNumber(limits.max);
  if (!limits.unit.empty()) text += " (" + std::string(limits.unit) + ")";
  return text;
}

std::string describe(const Choices& choices) {
  std::string text = "one of";
  for (std::size_t i = 0; i < choices.size(); ++i) text += (i ? ", " : " ") + std::string(choices[i]);
  return text;
}

// A JSON value as text for a message; bytes that are not UTF-8 are shown as U+FFFD.
std::string shown(const json& value) {
  if (value.is_number()) return formatNumber(value.get<double>());  // 12, not 12.0, as the user typed it
  return value.dump(-1, ' ', false, json::error_handler_t::replace);
}

[[noreturn]] void fail(std::string_view key, const std::string& value, const std::string& allowed) {
  throw SettingsError(std::string(key) + ": " + value + " is not allowed; expected " + allowed);
}

// Levenshtein distance, for "did you mean" on unknown keys.
std::size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

[[noreturn]] void failUnknownKey(std::string_view key) {
  std::string message = "unknown setting '" + std::string(key) + "'";
  std::string best;
  std::size_t bestDistance = 4;
  for (const std::string& candidate : settingKeys()) {
    const std::size_t distance = editDistance(key, candidate);
    if (distance < bestDistance) bestDistance = distance, best = candidate;
  }
  if (!best.empty()) message += "; did you mean '" + best + "'?";
  else message += "; run with a scene file or see the README for the list of settings";
  throw SettingsError(message);
}

double checkedNumber(std::string_view key, const json& value, const Limits& limits, bool integer) {
  if (!value.is_number()) fail(key, shown(value), describe(limits, integer));
  const double number = value.get<double>();
  if (!std::isfinite(number)) fail(key, shown(value), describe(limits, integer));
  if (integer && number != std::floor(number)) fail(key, shown(value), describe(limits, integer));
  if (number < limits.min || number > limits.max) fail(key, shown(value), describe(limits, integer));
  return number;
}

// Assigns one JSON value to one field, checking its type and range.
struct Assign {
  std::string_view key;
  const json& value;

  void operator()(double& field, const Limits& limits) const { field = checkedNumber(key, value, limits, false); }
  void operator()(int& field, const Limits& limits) const {
    field = static_cast<int>(checkedNumber(key, value, limits, true));
  }
  void operator()(glm::dvec3& field, const Limits& limits) const {
    const std::string allowed = "three numbers [x, y, z], each " + describe(limits, false);
    if (!value.is_array() || value.size() != 3) fail(key, shown(value), allowed);
    glm::dvec3 result;
    for (int i = 0; i < 3; ++i) {
      if (!value[i].is_number() || !std::isfinite(value[i].get<double>())) fail(key, shown(value), allowed);
      result[i] = value[i].get<double>();
      if (result[i] < limits.min || result[i] > limits.max) fail(key, shown(value), allowed);
    }
    field = result;
  }
  void operator()(std::string& field, const Choices& choices) const {
    const std::string allowed = choices.empty() ? std::string("a text") : describe(choices);
    if (!value.is_string()) fail(key, shown(value), allowed);
    const std::string text = value.get<std::string>();
    if (!choices.empty() && std::find(choices.begin(), choices.end(), text) == choices.end())
      fail(key, "\"" + text + "\"", allowed);
    field = text;
  }
  void operator()(bool& field, const Choices&) const {
    if (!value.is_boolean()) fail(key, shown(value), "true or false");
    field = value.get<bool>();
  }
};

// Turns the text of a `--set` value into JSON of the type the field expects.
struct ParseText {
  std::string_view key;
  std::string_view text;
  json result;

  static json number(std::string_view text) {
    double number = 0.0;
    const char* end = text.data() + text.size();
    const auto [pointer, error] = std::from_chars(text.data(), end, number);
    if (error != std::errc() || pointer != end) return json(std::string(text));  // rejected by Assign
    return json(number);
  }
  void operator()(double&, const Limits&) { result = number(text); }
  void operator()(int&, const Limits&) { result = number(text); }
  void operator()(glm::dvec3&, const Limits&) {
    result = json::array();
    std::string_view rest = text;
    while (true) {
      const std::size_t comma = rest.find(',');
      result.push_back(number(rest.substr(0, comma)));
      if (comma == std::string_view::npos) break;
      rest.remove_prefix(comma + 1);
    }
  }
  void operator()(std::string&, const Choices&) { result = std::string(text); }
  void operator()(bool&, const Choices&) {
    if (text == "true" || text == "1" || text == "on") result = true;
    else if (text == "false" || text == "0" || text == "off") result = false;
    else result = std::string(text);
  }
};

// Calls visit(field, limitsOrChoices) for the field named `key`; false when there is none.
template <class Visitor>
bool visitKey(Settings& settings, std::string_view key, Visitor&& visit) {
  bool found = false;
  forEachField(settings, [&](std::string_view name, auto& field, const auto& allowed) {
    if (!found && name == key) {
      visit(field, allowed);
      found = true;
    }
  });
  return found;
}

void flatten(const json& node, const std::string& prefix, std::vector<std::pair<std::string, json>>& out) {
  for (const auto& [name, value] : node.items()) {
    const std::string key = prefix.empty() ? name : prefix + "." + name;
    if (value.is_object()) flatten(value, key, out);
    else out.emplace_back(key, value);
  }
}

}  // namespace

void setSetting(Settings& settings, std::string_view key, const json& value) {
  if (key == "slime.level" && value.is_string() && value.get<std::string>() == "auto") {
    settings.slime.autoLevel = true;
    return;
  }
  if (!visitKey(settings, key, Assign{key, value})) failUnknownKey(key);
  if (key == "slime.level") settings.slime.autoLevel = false;
}

void applyOverride(Settings& settings, std::string_view assignment) {
  const std::size_t equals = assignment.find('=');
  if (equals == std::string_view::npos || equals == 0)
    throw SettingsError("--set " + std::string(assignment) + ": expected key=value, e.g. --set slime.level=5");
  const std::string_view key = assignment.substr(0, equals), text = assignment.substr(equals + 1);
  if (key == "slime.level" && text == "auto") return setSetting(settings, key, json("auto"));
  ParseText parse{key, text, {}};
  if (!visitKey(settings, key, parse)) failUnknownKey(key);
  setSetting(settings, key, parse.result);
}

void applySceneJson(Settings& settings, const json& scene, std::string_view origin) {
  if (!scene.is_object())
    throw SettingsError(std::string(origin) + ": a scene must be a JSON object such as {\"slime\": {\"level\": 4}}");
  std::vector<std::pair<std::string, json>> entries;
  flatten(scene, "", entries);
  // slime.level switches slime.autoLevel off, so a saved autoLevel = true is applied after it (JSON
  // objects come back sorted by name: autoLevel first).
  std::stable_partition(entries.begin(), entries.end(), [](const auto& entry) { return entry.first != "slime.autoLevel"; });
  for (const auto& [key, value] : entries) {
    try {
      setSetting(settings, key, value);
    } catch (const SettingsError& e) {
      throw SettingsError(std::string(origin) + ": " + e.what());
    }
  }
}

void applySceneFile(Settings& settings, const std::string& path) {
  std::ifstream file(path);
  if (!file) throw SettingsError("--scene " + path + ": cannot open the file for reading");
  json scene;
  try {
    scene = json::parse(file);
  } catch (const json::parse_error& e) {
    throw SettingsError("--scene " + path + ": not valid JSON: " + e.what());
  }
  applySceneJson(settings, scene, path);
}

void validateSettings(const Settings& settings) {
  Settings copy = settings;  // each field re-assigned through the same checks as when it was read
  forEachField(copy, [](std::string_view key, auto& field, const auto& allowed) {
    using Field = std::decay_t<decltype(field)>;
    json value;
    if constexpr (std::is_same_v<Field, glm::dvec3>) value = json::array({field.x, field.y, field.z});
    else value = field;
    Assign{key, value}(field, allowed);
  });
  const int samplesPerSide = static_cast<int>(std::lround(std::sqrt(settings.render.spp)));
  if (samplesPerSide * samplesPerSide != settings.render.spp)
    fail("render.spp", std::to_string(settings.render.spp), "a square number of samples: 1, 4, 9, 16, 25, 36, 49 or 64");
  if (settings.slime.position.z < settings.slime.radius)
    fail("slime.position", "z = " + formatNumber(settings.slime.position.z),
         "the ball to start above the floor: z ≥ slime.radius = " + formatNumber(settings.slime.radius) + " m");
  if (settings.slime.model == "bulk" && settings.sim.integrator != "auto" && settings.sim.integrator != "symplectic_euler" &&
      settings.sim.integrator != "explicit_euler" && settings.sim.integrator != "rk4" &&
      settings.sim.integrator != "projective" && settings.sim.integrator != "projective_midpoint")
    fail("sim.integrator", settings.sim.integrator,
         "auto, projective, projective_midpoint, symplectic_euler, explicit_euler or rk4 with slime.model=bulk "
         "(implicit_euler and xpbd are the membrane's only)");
  if (settings.slime.model == "membrane" &&
      (settings.sim.integrator == "projective" || settings.sim.integrator == "projective_midpoint"))
    fail("sim.integrator", settings.sim.integrator,
         "auto, explicit_euler, symplectic_euler, rk4, implicit_euler or xpbd with slime.model=membrane (projective and "
         "projective_midpoint are the bulk body's only)");
  if (settings.floor.pattern == "image" && settings.floor.image.empty())
    fail("floor.image", "\"\"", "the path of a PNG file when floor.pattern is image");
}

Settings defaultSettings() {
  Settings settings;
  applySceneJson(settings, json::parse(defaultSceneJson()), "assets/default.json");
  validateSettings(settings);
  return settings;
}

json settingsToJson(const Settings& settings) {
  Settings copy = settings;
  json document = json::object();
  forEachField(copy, [&](std::string_view key, auto& field, const auto&) {
    using Field = std::decay_t<decltype(field)>;
    json value;
    if constexpr (std::is_same_v<Field, glm::dvec3>) value = json::array({field.x, field.y, field.z});
    else value = field;
    std::string pointer = "/";  // "slime.level" -> "/slime/level"
    pointer.append(key);
    std::replace(pointer.begin(), pointer.end(), '.', '/');
    document[json::json_pointer(pointer)] = value;
  });
  return document;
}

std::vector<std::string> settingKeys() {
  std::vector<std::string> keys;
  Settings settings;
  forEachField(settings, [&](std::string_view key, auto&, const auto&) { keys.emplace_back(key); });
  return keys;
}

}  // namespace slime
