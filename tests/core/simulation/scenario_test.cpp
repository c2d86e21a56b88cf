// Scenario files: valid ones parse and replay; every kind of bad file is a SettingsError that says
// what is wrong.
#include "core/simulation/scenario.h"
#include "core/settings/settings_io.h"
#include "core/simulation/simulation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace slime {
namespace {

using nlohmann::json;

TEST(Scenario, ParsesEveryEventKindAndSortsByTime) {
  const json document = json::parse(R"({"events":[
    {"t":1.5,"press":{"point":[0,0,0.1],"direction":[0,0,-2],"depth":0.02,"duration":0.3}},
    {"t":0.5,"grab":{"point":[0,0,0.2],"radius":0.01}},
    {"t":0.5,"drag":{"to":[0,0,0.1],"duration":0.3}},
    {"t":1.2,"release":{}},
    {"t":2.0,"set":{"slime.stiffness":80}}]})");
  const Scenario scenario = parseScenario(document, "test");
  ASSERT_EQ(scenario.events.size(), 5u);
  EXPECT_EQ(scenario.events[0].kind, ScenarioEvent::Kind::Grab);  // same time: file order kept
  EXPECT_EQ(scenario.events[1].kind, ScenarioEvent::Kind::Drag);
  EXPECT_EQ(scenario.events[2].kind, ScenarioEvent::Kind::Release);
  EXPECT_EQ(scenario.events[3].kind, ScenarioEvent::Kind::Press);
  EXPECT_DOUBLE_EQ(scenario.events[3].direction.z, -1.0);  // normalised
  EXPECT_DOUBLE_EQ(scenario.events[0].radius, 0.01);
  EXPECT_EQ(scenario.events[4].kind, ScenarioEvent::Kind::Set);
}

void expectError(const std::string& text, const std::string& expected) {
  json document;
  try {
    document = json::parse(text);
  } catch (...) {
    FAIL() << "test JSON does not parse: " << text;
  }
  try {
    parseScenario(document, "bad.json");
    FAIL() << "accepted: " << text;
  } catch (const SettingsError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(expected), std::string::npos) << message;
    EXPECT_NE(message.find("bad.json"), std::string::npos) << message;
  }
}

// A grab's grip: a pinch unless it says "fist"; anything else is an error naming the two.
TEST(Scenario, AGrabHoldsWithAPinchOrAFist) {
  const Scenario scenario = parseScenario(json::parse(R"({"events":[
    {"t":1,"grab":{"point":[0,0,0],"radius":0.04,"grip":"fist"}},
    {"t":1,"hand":1,"grab":{"point":[0,0,0],"grip":"pinch"}},
    {"t":2,"grab":{"point":[0,0,0]}}]})"), "test");
  ASSERT_EQ(scenario.events.size(), 3u);
  EXPECT_EQ(scenario.events[0].grip, Grip::Fist);
  EXPECT_EQ(scenario.events[1].grip, Grip::Pinch);
  EXPECT_EQ(scenario.events[2].grip, Grip::Pinch);
  expectError(R"({"events":[{"t":1,"grab":{"point":[0,0,0],"grip":"claw"}}]})",
              "grab.grip must be \"pinch\" or \"fist\", got \"claw\"");
}

TEST(Scenario, BadFilesAreSettingsErrorsThatNameTheProblem) {
  expectError(R"([1,2])", "expected an object");
  expectError(R"({"evnts":[]})", "expected an object");
  expectError(R"({"events":[], "extra":1})", "unknown top-level key");
  expectError(R"({"events":[{"grab":{"point":[0,0,0]}}]})", "t is missing");
  expectError(R"({"events":[{"t":-1,"release":{}}]})", "at least");
  expectError(R"({"events":[{"t":"soon","release":{}}]})", "finite number");
  expectError(R"({"events":[{"t":1,"jump":{}}]})", "unknown action \"jump\"");
  expectError(R"({"events":[{"t":1,"release":{},"grab":{"point":[0,0,0]}}]})", "exactly one action");
  expectError(R"({"events":[{"t":1}]})", "exactly one action");
  expectError(R"({"events":[{"t":1,"grab":{"point":[0,0]}}]})", "grab.point must be an array of 3 numbers");
  expectError(R"({"events":[{"t":1,"grab":{"point":[0,0,0],"radius":0}}]})", "grab.radius");
  expectError(R"({"events":[{"t":1,"grab":{"point":[0,0,0],"size":2}}]})", "unknown field \"size\" in grab");
  expectError(R"({"events":[{"t":1,"drag":{"duration":1}}]})", "drag.to is missing");
  expectError(R"({"events":[{"t":1,"press":{"point":[0,0,0],"direction":[0,0,0],"depth":0.01}}]})",
              "direction must not be zero");
  expectError(R"({"events":[{"t":1,"press":{"point":[0,0,0],"direction":[0,0,1]}}]})", "press.depth is missing");
  expectError(R"({"events":[{"t":1,"press":{"point":[0,0,0],"direction":[0,0,1],"depth":0.01,"hold":-1}}]})",
              "press.hold must be at least 0");
  expectError(R"({"events":[{"t":1,"set":{"slime.stifness":80}}]})", "slime.stifness");
  expectError(R"({"events":[{"t":1,"set":{"slime.level":99}}]})", "slime.level");
  expectError(R"({"events":[{"t":1,"set":{}}]})", "set must be an object");
  expectError(R"({"events":[3]})", "event 0: must be an object");
}

TEST(Scenario, OrbitsTurnTheCameraLinearlyOverTheirDurationAndAddUp) {
  const Scenario scenario = parseScenario(json::parse(R"({"events":[
    {"t":1.0,"orbit":{"yaw":90,"duration":2}},
    {"t":2.0,"orbit":{"yaw":-30,"pitch":10}}]})"), "test");
  ASSERT_EQ(scenario.events.size(), 2u);
  EXPECT_EQ(scenario.events[0].kind, ScenarioEvent::Kind::Orbit);
  EXPECT_EQ(orbitAt(scenario, 0.5), glm::dvec2(0.0, 0.0));
  EXPECT_NEAR(orbitAt(scenario, 1.5).x, 22.5, 1e-12);
  EXPECT_NEAR(orbitAt(scenario, 2.0).x, 45.0 - 30.0, 1e-12);  // the second at once
  EXPECT_NEAR(orbitAt(scenario, 2.0).y, 10.0, 1e-12);
  EXPECT_NEAR(orbitAt(scenario, 9.0).x, 60.0, 1e-12);
  expectError(R"({"events":[{"t":1,"orbit":{"duration":1}}]})", "orbit needs a yaw or a pitch");
  expectError(R"({"events":[{"t":1,"orbit":{"yaw":10,"roll":1}}]})", "unknown field \"roll\" in orbit");
  expectError(R"({"events":[{"t":1,"hand":1,"orbit":{"yaw":10}}]})", "not allowed with set or orbit");
  expectError(R"({"events":[{"t":1,"orbit":{"yaw":10,"duration":-1}}]})", "orbit.duration must be at least 0");
}

TEST(Scenario, MissingOrBrokenFileIsASettingsError) {
  EXPECT_THROW(loadScenario("/nonexistent/scenario.json"), SettingsError);
}

TEST(ScenarioPlayer, PressPushesInThenLetsGoAndSetChangesTheSimulation) {
  Settings settings = defaultSettings();
  settings.slime.level = 3;
  // The player's press and set, on the floor without adhesion: 0.6 s after the drop the sticky
  // default's (8000 Pa) base is held where it landed and the 15 mm press moves the top only 5 mm
  // (5.31 cm against 5.83 cm before).
  settings.slime.adhesion = 0.0;
  Simulation simulation(settings);
  const Scenario scenario = parseScenario(json::parse(R"({"events":[
    {"t":0.6,"press":{"point":[0,0,0.2],"direction":[0,0,-1],"depth":0.015,"duration":0.2}},
    {"t":1.0,"set":{"slime.stiffness":150}}]})"),
                                          "test");
  ScenarioPlayer player(scenario);
  double topBefore = 0.0, topPressed = 0.0;
  while (simulation.time() < 1.2 - 1e-9) {
    player.advanceTo(simulation.time(), simulation, settings);
    if (std::abs(simulation.time() - 0.6) < 5e-4) topBefore = simulation.metrics().height;
    if (std::abs(simulation.time() - 0.79) < 5e-4) {
      EXPECT_TRUE(simulation.grabbing());
      topPressed = simulation.metrics().height;
    }
    simulation.step();
  }
  EXPECT_LT(topPressed, topBefore - 0.01);  // pushed in by most of the 15 mm
  EXPECT_FALSE(simulation.grabbing());      // let go at the end of the press
  EXPECT_DOUBLE_EQ(simulation.settings().slime.stiffness, 150.0);
  EXPECT_DOUBLE_EQ(settings.slime.stiffness, 150.0);
  EXPECT_TRUE(player.finished());
  EXPECT_TRUE(simulation.divergences().empty());
}

}  // namespace
}  // namespace slime
