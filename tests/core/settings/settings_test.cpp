#include "core/settings/default_scene.h"
#include "core/settings/setting_info.h"
#include "core/settings/settings_io.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>

namespace slime {
namespace {

using nlohmann::json;

// The message of the SettingsError that `action` throws ("" when it throws none).
template <class Action>
std::string errorOf(Action&& action) {
  try {
    action();
  } catch (const SettingsError& e) {
    return e.what();
  }
  return "";
}

TEST(Settings, EmbeddedDefaultSceneMatchesTheStructDefaults) {
  // assets/default.json and the in-class defaults of core/settings/settings.h must say the same thing.
  EXPECT_EQ(settingsToJson(defaultSettings()), settingsToJson(Settings{}));
}

TEST(Settings, EmbeddedDefaultSceneSetsEveryKey) {
  const json scene = json::parse(defaultSceneJson());
  for (const std::string& key : settingKeys()) {
    if (key == "slime.autoLevel") continue;  // written as slime.level = "auto"
    std::string pointer = "/" + key;
    std::replace(pointer.begin(), pointer.end(), '.', '/');
    EXPECT_TRUE(scene.contains(json::json_pointer(pointer))) << key << " missing from assets/default.json";
  }
}

TEST(Settings, OverridesSetNumbersVectorsStringsAndBooleans) {
  Settings settings = defaultSettings();
  applyOverride(settings, "slime.level=5");
  applyOverride(settings, "slime.color=0.2,0.8,0.3");
  applyOverride(settings, "sim.integrator=rk4");
  applyOverride(settings, "render.shadows=false");
  applyOverride(settings, "slime.mass=0.5");
  EXPECT_EQ(settings.slime.level, 5);
  EXPECT_EQ(settings.slime.color, glm::dvec3(0.2, 0.8, 0.3));
  EXPECT_EQ(settings.sim.integrator, "rk4");
  EXPECT_FALSE(settings.render.shadows);
  EXPECT_DOUBLE_EQ(settings.slime.mass, 0.5);
  EXPECT_NO_THROW(validateSettings(settings));
}

TEST(Settings, LevelAutoIsAccepted) {
  Settings settings = defaultSettings();
  applyOverride(settings, "slime.level=auto");
  EXPECT_TRUE(settings.slime.autoLevel);
  applyOverride(settings, "slime.level=3");
  EXPECT_FALSE(settings.slime.autoLevel);
  EXPECT_EQ(settings.slime.level, 3);
}

TEST(Settings, OutOfRangeValueNamesKeyValueAndRange) {
  Settings settings = defaultSettings();
  const std::string message = errorOf([&] { applyOverride(settings, "slime.level=12"); });
  EXPECT_NE(message.find("slime.level"), std::string::npos) << message;
  EXPECT_NE(message.find("12"), std::string::npos) << message;
  EXPECT_NE(message.find("0 to 7"), std::string::npos) << message;
  EXPECT_EQ(settings.slime.level, 4) << "a rejected value must leave the setting unchanged";
}

// The bulk material's settings: each value just outside its range is refused with the key, the
// value and the range; the model must be one of its two words.
TEST(Settings, BulkMaterialSettingsAreRangeChecked) {
  const struct {
    const char* assignment;
    const char* range;
  } cases[] = {{"slime.modulus=49", "50 to 100000"},    {"slime.longTerm=0", "0.01 to 1"},
               {"slime.relaxation=0.001", "0.01 to 1000"}, {"slime.poisson=0.5", "0 to 0.49"},
               {"slime.viscosity=-1", "0 to 100"},      {"slime.resolution=5", "1 to 4"},
               {"slime.yieldStretch=1.05", "1.1 to 10"}, {"slime.flowTime=0", "0.01 to 1000"},
               {"slime.recoveryTime=-1", "0 to 1000"}, {"slime.plastic=sometimes", "true"},
               {"slime.model=jelly", "bulk, membrane"}};
  for (const auto& c : cases) {
    Settings settings = defaultSettings();
    const std::string message = errorOf([&] { applyOverride(settings, c.assignment); });
    const std::string key = std::string(c.assignment).substr(0, std::string(c.assignment).find('='));
    EXPECT_NE(message.find(key), std::string::npos) << message;
    EXPECT_NE(message.find(c.range), std::string::npos) << message;
  }
}

TEST(Settings, RejectsWrongTypesNaNAndInfinity) {
  Settings settings = defaultSettings();
  for (const char* bad : {"slime.mass=heavy", "slime.mass=nan", "slime.mass=inf", "slime.mass=-1",
                          "slime.level=2.5", "slime.color=1,2", "slime.color=0.1,0.2,nan",
                          "slime.color=0.1,0.2,0.3,0.4", "render.shadows=maybe", "sim.integrator=verlet",
                          "camera.width=0", "camera.width=100000", "sim.dt=0", "render.spp=0"}) {
    EXPECT_FALSE(errorOf([&] { applyOverride(settings, bad); }).empty()) << bad;
  }
  EXPECT_EQ(settingsToJson(settings), settingsToJson(defaultSettings()));
}

TEST(Settings, UnknownKeySuggestsTheNearestOne) {
  Settings settings = defaultSettings();
  const std::string message = errorOf([&] { applyOverride(settings, "slime.stifness=10"); });
  EXPECT_NE(message.find("did you mean 'slime.stiffness'"), std::string::npos) << message;
}

TEST(Settings, MalformedOverrideIsRejected) {
  Settings settings = defaultSettings();
  EXPECT_FALSE(errorOf([&] { applyOverride(settings, "slime.level"); }).empty());
  EXPECT_FALSE(errorOf([&] { applyOverride(settings, "=3"); }).empty());
}

TEST(Settings, CrossFieldRulesAreValidated) {
  Settings settings = defaultSettings();
  settings.render.spp = 5;
  EXPECT_NE(errorOf([&] { validateSettings(settings); }).find("render.spp"), std::string::npos);
  settings = defaultSettings();
  settings.slime.position.z = 0.01;
  EXPECT_NE(errorOf([&] { validateSettings(settings); }).find("slime.position"), std::string::npos);
  settings = defaultSettings();
  settings.slime.mass = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(errorOf([&] { validateSettings(settings); }).find("slime.mass"), std::string::npos);
}

TEST(Settings, SceneFileAppliesNestedKeysAndReportsItsErrors) {
  const std::string path = std::string(SLIME_TEST_OUTPUT_DIR) + "/scene_test.json";
  std::ofstream(path) << R"({"slime": {"level": 2, "color": [1, 0, 0]}, "sim": {"dt": 0.0005}})";
  Settings settings = defaultSettings();
  applySceneFile(settings, path);
  EXPECT_EQ(settings.slime.level, 2);
  EXPECT_EQ(settings.slime.color, glm::dvec3(1, 0, 0));
  EXPECT_DOUBLE_EQ(settings.sim.dt, 0.0005);

  std::ofstream(path) << R"({"slime": {"levle": 2}})";
  EXPECT_NE(errorOf([&] { applySceneFile(settings, path); }).find("did you mean 'slime.level'"), std::string::npos);
  std::ofstream(path) << "{ not json";
  EXPECT_NE(errorOf([&] { applySceneFile(settings, path); }).find("not valid JSON"), std::string::npos);
  std::ofstream(path) << "[1, 2]";
  EXPECT_NE(errorOf([&] { applySceneFile(settings, path); }).find("JSON object"), std::string::npos);
  std::remove(path.c_str());
  EXPECT_NE(errorOf([&] { applySceneFile(settings, path); }).find("cannot open"), std::string::npos);
}

// One table, one meaning per key: every line of settings_fields.h carries its one-line help.
TEST(Settings, EveryKeyIsDescribedWithItsMeaning) {
  const std::vector<SettingInfo> described = describeSettings(defaultSettings());
  std::vector<std::string> keys;
  for (const SettingInfo& info : described) {
    keys.push_back(info.key);
    EXPECT_FALSE(info.help.empty()) << info.key << " has no help in core/settings/settings_fields.h";
    EXPECT_EQ(info.value, settingValue(defaultSettings(), info.key)) << info.key;
  }
  EXPECT_EQ(keys, settingKeys());
}

TEST(Settings, SamplesPerPixelOffersOnlyTheSquaresValidationAccepts) {
  for (const SettingInfo& info : describeSettings(defaultSettings())) {
    if (info.key == "render.spp") {
      EXPECT_EQ(info.onlyValues, (std::vector<int>{1, 4, 9, 16, 25, 36, 49, 64}));
    } else if (info.key == "slime.level") {
      EXPECT_TRUE(info.onlyValues.empty()) << "every level 0..7 is valid";
    }
  }
  Settings settings = defaultSettings();
  settings.render.spp = 2;
  const std::string error = errorOf([&] { validateSettings(settings); });
  EXPECT_NE(error.find("render.spp"), std::string::npos) << error;
  EXPECT_NE(error.find("1, 4, 9, 16"), std::string::npos) << error;
}

// Save then load (the viewer's Ctrl+S and Ctrl+O, `--scene`) gives back every key, each set to a
// value other than its default so that a key the writer or reader dropped shows.
TEST(Settings, SaveAndLoadRoundTripEveryKey) {
  Settings changed = defaultSettings();
  for (const SettingInfo& info : describeSettings(changed)) {
    json value;
    switch (info.type) {
      case SettingType::Number: value = info.min + (info.max - info.min) * 0.37; break;
      case SettingType::Integer:
        value = info.onlyValues.empty() ? static_cast<int>(info.min + (info.max - info.min) / 3) : info.onlyValues[2];
        if (value == info.value) value = static_cast<int>(info.max);  // a third of the way is the default
        break;
      case SettingType::Vector: value = json::array({info.min + 0.1 * (info.max - info.min), 0.5 * (info.min + info.max), info.max}); break;
      case SettingType::Choice: value = info.choices.back() == info.value ? info.choices.front() : info.choices.back(); break;
      case SettingType::Text: value = "some/floor.png"; break;
      case SettingType::Boolean: value = !info.value.get<bool>(); break;
    }
    if (info.key == "slime.position") value = json::array({0.01, -0.02, 0.5});  // above the floor: z >= radius
    if (info.key == "floor.pattern") value = "checker";                         // no image file needed
    if (info.key == "sim.integrator") value = "rk4";  // valid for both models (projective, the last, is bulk only)
    setSetting(changed, info.key, value);
    EXPECT_NE(settingValue(changed, info.key), settingValue(defaultSettings(), info.key)) << info.key;
  }
  ASSERT_NO_THROW(validateSettings(changed));
  const std::string path = std::string(SLIME_TEST_OUTPUT_DIR) + "/round_trip_scene.json";
  {
    std::ofstream file(path);
    file << settingsToJson(changed).dump(2);
  }
  Settings loaded = defaultSettings();
  applySceneFile(loaded, path);
  for (const std::string& key : settingKeys())
    EXPECT_EQ(settingValue(loaded, key), settingValue(changed, key)) << key << " did not survive save and load";
  EXPECT_EQ(settingsToJson(loaded), settingsToJson(changed));
}

}  // namespace
}  // namespace slime
