// The panels offer only the settings that act on what is on screen: the bulk slime gets no membrane
// slider and the membrane slime no bulk one, each left-out setting with its reason; labels are words.
#include "app/viewer/panel_fields.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <set>
#include <string>

#include "core/settings/settings_io.h"

namespace slime {
namespace {

std::set<std::string> offeredKeys(const std::string& group, const Settings& shown) {
  std::set<std::string> keys;
  for (const PanelField* field : offeredFields(group, shown)) keys.insert(field->setting.key);
  return keys;
}

const PanelField& fieldOf(const std::string& key) {
  const auto& fields = panelFields();
  return *std::find_if(fields.begin(), fields.end(), [&](const PanelField& f) { return f.setting.key == key; });
}

TEST(PanelOffer, BulkSlimeGetsNoMembraneSlider) {
  Settings bulk = defaultSettings();
  bulk.slime.model = "bulk";
  const std::set<std::string> offered = offeredKeys("slime", bulk);
  for (const char* membrane : {"slime.stiffness", "slime.damping", "slime.pressure", "slime.rolling"})
    EXPECT_EQ(offered.count(membrane), 0u) << membrane << " is offered for the bulk slime";
  for (const char* own : {"slime.modulus", "slime.longTerm", "slime.relaxation", "slime.viscosity", "slime.mass"})
    EXPECT_EQ(offered.count(own), 1u) << own << " is not offered for the bulk slime";
  // The seed's sliders say where they went.
  EXPECT_NE(inactiveReason(fieldOf("slime.stiffness"), bulk).find("slime.modulus"), std::string::npos);
  EXPECT_NE(inactiveReason(fieldOf("slime.damping"), bulk).find("slime.viscosity"), std::string::npos);
  EXPECT_NE(fieldOf("slime.modulus").setting.help.find("stiffness"), std::string::npos);
  EXPECT_NE(fieldOf("slime.viscosity").setting.help.find("damping"), std::string::npos);
}

TEST(PanelOffer, MembraneSlimeGetsNoBulkSlider) {
  Settings membrane = defaultSettings();
  membrane.slime.model = "membrane";
  const std::set<std::string> offered = offeredKeys("slime", membrane);
  for (const char* bulk : {"slime.modulus", "slime.longTerm", "slime.relaxation", "slime.poisson",
                           "slime.viscosity", "slime.resolution"})
    EXPECT_EQ(offered.count(bulk), 0u) << bulk << " is offered for the membrane slime";
  for (const char* own : {"slime.stiffness", "slime.damping", "slime.pressure", "slime.rolling"})
    EXPECT_EQ(offered.count(own), 1u) << own;
  EXPECT_NE(inactiveReason(fieldOf("slime.modulus"), membrane).find("bulk model only"), std::string::npos);
}

TEST(PanelOffer, ShapeAutoLevelAndFloorPatternHideWhatTheyOverrule) {
  Settings settings = defaultSettings();
  settings.slime.autoLevel = false;
  settings.floor.pattern = "planks";
  EXPECT_EQ(offeredKeys("slime", settings).count("slime.level"), 1u);
  EXPECT_EQ(offeredKeys("floor", settings).count("floor.image"), 0u);
  settings.slime.autoLevel = true;
  EXPECT_EQ(offeredKeys("slime", settings).count("slime.level"), 0u);
  settings.slime.shape = "sphere";
  EXPECT_EQ(offeredKeys("slime", settings).count("slime.autoLevel"), 0u);
  settings.floor.pattern = "image";
  EXPECT_EQ(offeredKeys("floor", settings).count("floor.image"), 1u);
  // Settings of other groups and of both models are always offered.
  EXPECT_EQ(offeredKeys("slime", settings).count("slime.friction"), 1u);
  EXPECT_EQ(offeredKeys("render", settings).size(),
            static_cast<std::size_t>(std::count_if(panelFields().begin(), panelFields().end(),
                                                   [](const PanelField& f) { return f.setting.group() == "render"; })));
}

TEST(PanelOffer, LabelsAreLowerCaseWordsNotKeys) {
  for (const PanelField& field : panelFields()) {
    const std::string& label = field.label;
    EXPECT_FALSE(label.empty()) << field.setting.key;
    if (field.widget != Widget::Checkbox) {  // a checkbox's label starts at its box, not after a widget
      EXPECT_LE(label.size() + (field.appliesOnReload ? 2 : 0), 15u) << field.setting.key << ": '" << label
                                                                   << "' does not fit beside its widget";
    }
    // No camelCase key name: a capital only starts a word ("Poisson ratio", "colour A").
    for (std::size_t i = 1; i < label.size(); ++i)
      EXPECT_FALSE(std::isupper(static_cast<unsigned char>(label[i])) && label[i - 1] != ' ')
          << field.setting.key << " is labelled '" << label << "'";
  }
  EXPECT_EQ(fieldOf("slime.longTerm").label, "long-term part");
  EXPECT_EQ(fieldOf("slime.relaxation").label, "relaxation time");
  EXPECT_EQ(fieldOf("slime.autoLevel").label, "automatic level");
}

}  // namespace
}  // namespace slime
