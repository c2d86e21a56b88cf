#include "app/viewer/panel_fields.h"

#include <algorithm>
#include <cctype>
#include <utility>
#include <type_traits>

#include "core/settings/settings_fields.h"
#include "core/settings/settings_io.h"

namespace slime {
namespace {

// Rebuild-type settings. Keys that a build does not have are simply never met.
constexpr std::string_view kReloadKeys[] = {"slime.shape",   "slime.model",      "slime.radius",
                                            "slime.level",   "slime.resolution", "slime.autoLevel",
                                            "slime.position"};

// The address of every field of `settings`, in the table's order.
std::vector<const void*> fieldAddresses(const Settings& settings) {
  std::vector<const void*> addresses;
  forEachField(settings,
               [&](std::string_view, const auto& field, const auto&) { addresses.push_back(&field); });
  return addresses;
}

// Labels in words where the key's own words ("longTerm") would not say it; other keys' names are
// split at their capitals ("timeScale" → "time scale"). At most 15 letters: what the 250-pixel column
// shows beside a widget. The meaning, with the unit and range, is in the tooltip.
constexpr std::pair<std::string_view, std::string_view> kLabels[] = {
    {"camera.fov", "field of view"},          {"floor.colorA", "colour A"},
    {"floor.colorB", "colour B"},             {"floor.specular", "specular"},
    {"slime.level", "mesh level"},            {"slime.resolution", "body level"},
    {"slime.autoLevel", "automatic level"},   {"slime.stiffness", "stiffness"},
    {"slime.damping", "damping"},      {"slime.pressure", "volume pressure"},
    {"slime.rolling", "rolling decay"},       {"slime.modulus", "shear modulus"},
    {"slime.longTerm", "long-term part"}, {"slime.relaxation", "relaxation time"},
    {"slime.poisson", "Poisson ratio"},       {"slime.viscosity", "viscosity"},
    {"slime.position", "position"},    {"slime.color", "colour"},
    {"slime.ior", "refraction"},        {"render.depth", "ray depth"},
    {"render.spp", "samples/pixel"},      {"render.scale", "image scale"},
    {"render.targetFps", "target frames/s"}, {"render.optics", "optics"},
    {"sim.dt", "time step"},                  {"sim.paused", "paused"},
};

std::string labelFor(const SettingInfo& info) {
  for (const auto& [key, label] : kLabels)
    if (key == info.key) return std::string(label);
  std::string words;
  for (char c : info.name()) {
    if (std::isupper(static_cast<unsigned char>(c))) {
      words += ' ';
      words += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    } else {
      words += c;
    }
  }
  return words;
}

// A number whose range spans this many orders of magnitude gets a logarithmic slider.
constexpr double kLogarithmicSpan = 100.0;

Widget widgetFor(const SettingInfo& info) {
  switch (info.type) {
    case SettingType::Boolean:
      return Widget::Checkbox;
    case SettingType::Choice:
      return Widget::Combo;
    case SettingType::Text:
      return Widget::Text;
    case SettingType::Vector:
      return info.unit.find("RGB") != std::string::npos && info.max <= 1.0 ? Widget::Color : Widget::Drag3;
    case SettingType::Integer:
      if (info.key == "camera.width" || info.key == "camera.height") return Widget::WindowSize;
      return info.onlyValues.empty() ? Widget::Slider : Widget::ValueCombo;
    case SettingType::Number: {
      const bool spansDecades = info.min > 0.0 ? info.max / info.min >= kLogarithmicSpan
                                               : info.min == 0.0 && info.max >= kLogarithmicSpan;
      return spansDecades ? Widget::LogSlider : Widget::Slider;
    }
  }
  return Widget::Slider;
}

std::vector<PanelField> generateFields() {
  std::vector<PanelField> fields;
  for (SettingInfo& info : describeSettings(defaultSettings())) {
    PanelField field;
    field.widget = widgetFor(info);
    field.appliesOnReload = appliesOnReload(info.key);
    field.label = labelFor(info);
    field.setting = std::move(info);
    fields.push_back(std::move(field));
  }
  return fields;
}

}  // namespace

const std::vector<PanelGroup>& panelGroups() {
  static const std::vector<PanelGroup> groups = {{"camera", "Camera"}, {"light", "Light"},
                                                 {"floor", "Floor"},   {"slime", "Slime"},
                                                 {"render", "Render"}, {"sim", "Simulation"}};
  return groups;
}

const std::vector<PanelField>& panelFields() {
  static const std::vector<PanelField> fields = generateFields();
  return fields;
}

std::string inactiveReason(const PanelField& field, const Settings& shown) {
  const SettingInfo& info = field.setting;
  const std::string model = info.model();
  if (!model.empty() && model != shown.slime.model) {
    std::string reason = "acts on the " + model + " model only; this slime is " + shown.slime.model + " (slime.model)";
    if (info.key == "slime.stiffness") reason += "; its stiffness is slime.modulus";
    if (info.key == "slime.damping") reason += "; its damping is slime.viscosity";
    return reason;
  }
  if ((info.key == "slime.level" || info.key == "slime.autoLevel") && shown.slime.shape == "sphere")
    return "the analytic sphere is drawn, not the mesh (slime.shape)";
  if (info.key == "slime.level" && shown.slime.autoLevel) return "slime.autoLevel picks the level";
  if (info.key == "floor.image" && shown.floor.pattern != "image")
    return "used when floor.pattern is image; it is " + shown.floor.pattern;
  return "";
}

std::vector<const PanelField*> offeredFields(const std::string& group, const Settings& shown) {
  std::vector<const PanelField*> offered;
  for (const PanelField& field : panelFields())
    if (field.setting.group() == group && inactiveReason(field, shown).empty()) offered.push_back(&field);
  return offered;
}

bool appliesOnReload(std::string_view key) {
  return std::find(std::begin(kReloadKeys), std::end(kReloadKeys), key) != std::end(kReloadKeys);
}

void copyReloadFields(const Settings& from, Settings& to) {
  const std::vector<const void*> source = fieldAddresses(from);
  std::size_t index = 0;
  forEachField(to, [&](std::string_view key, auto& field, const auto&) {
    const void* address = source[index++];
    if (appliesOnReload(key)) field = *static_cast<const std::decay_t<decltype(field)>*>(address);
  });
}

std::vector<std::string> differingReloadFields(const Settings& a, const Settings& b) {
  const std::vector<const void*> other = fieldAddresses(b);
  std::vector<std::string> differing;
  std::size_t index = 0;
  forEachField(a, [&](std::string_view key, const auto& field, const auto&) {
    const void* address = other[index++];
    if (appliesOnReload(key) && !(field == *static_cast<const std::decay_t<decltype(field)>*>(address)))
      differing.emplace_back(key);
  });
  return differing;
}

}  // namespace slime
