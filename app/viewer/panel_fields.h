// What the viewer's panels show, as plain data: one PanelField per setting, generated from the table
// of settings (core/settings/settings_fields.h via describeSettings), so every key appears with the table's
// unit and range and none can drift. No ImGui here: tests check the list without a GL context.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/settings/setting_info.h"

namespace slime {

// How one setting is edited.
enum class Widget {
  Slider,      // a number or integer over [min, max]
  LogSlider,   // a number over [min, max] spanning orders of magnitude
  Drag3,       // a vector (positions): dragged, clamped to [min, max] per component
  Color,       // a linear RGB colour in [0, 1]
  Combo,       // a choice among words
  ValueCombo,  // an integer among the only values validation accepts (render.spp: 1, 4, 9, ...)
  Checkbox,    // a boolean
  Text,        // free text (a file path)
  WindowSize,  // camera.width/height: the viewer's window sets them; shown, not edited
};

struct PanelField {
  SettingInfo setting;  // key, range, unit, choices, meaning: the table's
  std::string label;    // in words ("long-term fraction"); the key goes in the tooltip
  Widget widget = Widget::Slider;
  bool appliesOnReload = false;  // rebuilds the slime: held until "Reload slime"
};

struct PanelGroup {
  std::string name;   // the scene file's group: "camera", "light", "floor", "slime", "render", "sim"
  std::string title;  // the panel header
};

// The groups in the scene file's order.
const std::vector<PanelGroup>& panelGroups();

// Every setting, in the table's order, with how the panels edit it.
const std::vector<PanelField>& panelFields();

// Why `field` does nothing to the slime on screen, built from `shown` (its slime.model and shape, the
// floor's pattern): "" when it acts. The panels leave such a field out and list it, with this reason,
// under the section.
std::string inactiveReason(const PanelField& field, const Settings& shown);

// The fields of `group` the panels offer for the slime built from `shown`, in the table's order.
std::vector<const PanelField*> offeredFields(const std::string& group, const Settings& shown);

// Settings that rebuild the slime (its mesh, size or start): the viewer applies them on Reload only.
bool appliesOnReload(std::string_view key);

// Copies the rebuild-type settings of `from` into `to`, leaving the others.
void copyReloadFields(const Settings& from, Settings& to);

// The rebuild-type keys whose values differ between a and b.
std::vector<std::string> differingReloadFields(const Settings& a, const Settings& b);

}  // namespace slime
