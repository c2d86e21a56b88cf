#include "app/viewer/panel_fields.h"

#include <algorithm>
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
