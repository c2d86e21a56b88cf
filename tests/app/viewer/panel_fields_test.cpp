// The panels are generated from the table of settings: every key appears once, with the table's range
// and unit, so a slider cannot offer what validation refuses (the stiffness slider once went to
// 2000 N/m while 1000 was the limit).
#include "app/viewer/panel_fields.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <type_traits>

#include "core/settings/settings_fields.h"
#include "core/settings/settings_io.h"

namespace slime {
namespace {

TEST(PanelFields, EveryKeyOfTheTableOnceInTableOrder) {
  std::vector<std::string> keys;
  for (const PanelField& field : panelFields()) keys.push_back(field.setting.key);
  EXPECT_EQ(keys, settingKeys());
}

TEST(PanelFields, RangesAndUnitsAreTheTables) {
  const std::vector<PanelField>& fields = panelFields();
  std::size_t index = 0;
  Settings settings;
  forEachField(settings, [&](std::string_view key, auto&, const auto& allowed) {
    ASSERT_LT(index, fields.size());
    const SettingInfo& shown = fields[index++].setting;
    EXPECT_EQ(shown.key, key);
    if constexpr (std::is_same_v<std::decay_t<decltype(allowed)>, Limits>) {
      EXPECT_EQ(shown.min, allowed.min) << key;
      EXPECT_EQ(shown.max, allowed.max) << key;
      EXPECT_EQ(shown.unit, allowed.unit) << key;
    } else {
      EXPECT_EQ(shown.choices, std::vector<std::string>(allowed.begin(), allowed.end())) << key;
    }
  });
  EXPECT_EQ(index, fields.size());
}

TEST(PanelFields, EveryGroupHasAPanelSection) {
  std::set<std::string> groups;
  for (const PanelGroup& group : panelGroups()) groups.insert(group.name);
  for (const PanelField& field : panelFields())
    EXPECT_TRUE(groups.count(field.setting.group())) << field.setting.key;
}

TEST(PanelFields, SamplesPerPixelOffersOnlyWhatItCanHonour) {
  for (const PanelField& field : panelFields()) {
    if (field.setting.key != "render.spp") continue;
    EXPECT_EQ(field.widget, Widget::ValueCombo);
    for (int samples : field.setting.onlyValues) {
      Settings settings = defaultSettings();
      settings.render.spp = samples;
      EXPECT_NO_THROW(validateSettings(settings)) << samples;
      const int side = static_cast<int>(std::lround(std::sqrt(samples)));
      EXPECT_EQ(side * side, samples);
    }
    EXPECT_EQ(field.setting.onlyValues.size(), 8u);
  }
}

TEST(PanelFields, RebuildTypeSettingsWaitForReload) {
  for (const char* key : {"slime.level", "slime.radius", "slime.shape", "slime.autoLevel"}) {
    EXPECT_TRUE(appliesOnReload(key)) << key;
  }
  for (const PanelField& field : panelFields())
    EXPECT_EQ(field.appliesOnReload, appliesOnReload(field.setting.key)) << field.setting.key;
  EXPECT_FALSE(appliesOnReload("slime.stiffness"));

  Settings built = defaultSettings(), wanted = defaultSettings();
  wanted.slime.level = 2;
  wanted.slime.radius = 0.05;
  wanted.slime.stiffness = 300.0;
  Settings applied = wanted;
  copyReloadFields(built, applied);
  EXPECT_EQ(applied.slime.level, built.slime.level);
  EXPECT_EQ(applied.slime.radius, built.slime.radius);
  EXPECT_EQ(applied.slime.stiffness, 300.0);  // not rebuild-type: applies at once
  EXPECT_EQ(differingReloadFields(wanted, built), (std::vector<std::string>{"slime.radius", "slime.level"}));
}

}  // namespace
}  // namespace slime
