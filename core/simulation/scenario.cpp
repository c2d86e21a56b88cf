#include "core/simulation/scenario.h"

#include "core/settings/settings_io.h"
#include "core/simulation/simulation.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

namespace slime {
namespace {

using nlohmann::json;

constexpr double kTimeTolerance = 1e-9;  // simulated time is a sum of steps; fire events due within this

struct EventReader {
  const std::string& origin;
  std::size_t index;

  [[noreturn]] void fail(const std::string& what) const {
    throw SettingsError("scenario " + origin + ": event " + std::to_string(index) + ": " + what);
  }
  double number(const json& object, const char* action, const char* key, double fallback, bool required,
                double minimum) const {
    if (!object.contains(key)) {
      if (required) fail(std::string(action) + "." + key + " is missing");
      return fallback;
    }
    const json& value = object.at(key);
    if (!value.is_number() || !std::isfinite(value.get<double>()))
      fail(std::string(action) + "." + key + " must be a finite number, got " + value.dump());
    const double number = value.get<double>();
    if (number < minimum)
      fail(std::string(action) + "." + key + " must be at least " + std::to_string(minimum) + ", got " + value.dump());
    return number;
  }
  glm::dvec3 vector(const json& object, const char* action, const char* key) const {
    if (!object.contains(key)) fail(std::string(action) + "." + key + " is missing");
    const json& value = object.at(key);
    if (!value.is_array() || value.size() != 3)
      fail(std::string(action) + "." + key + " must be an array of 3 numbers, got " + value.dump());
    glm::dvec3 result;
    for (int i = 0; i < 3; ++i) {
      if (!value[i].is_number() || !std::isfinite(value[i].get<double>()))
        fail(std::string(action) + "." + key + " must be an array of 3 finite numbers, got " + value.dump());
      result[i] = value[i].get<double>();
    }
    return result;
  }
  void allowOnly(const json& object, const char* action, std::initializer_list<const char*> keys) const {
    if (!object.is_object()) fail(std::string(action) + " must be an object, got " + object.dump());
    for (const auto& entry : object.items())
      if (const std::string& key = entry.key();
          std::none_of(keys.begin(), keys.end(), [&](const char* k) { return key == k; }))
        fail("unknown field \"" + key + "\" in " + action);
  }
};

ScenarioEvent readEvent(const json& item, const EventReader& reader) {
  if (!item.is_object()) reader.fail("must be an object, got " + item.dump());
  ScenarioEvent event;
  event.time = reader.number(item, "event", "t", 0.0, true, 0.0);
  const char* actions[] = {"grab", "drag", "release", "press", "set", "orbit"};
  int found = 0;
  for (const auto& entry : item.items()) {
    const std::string& key = entry.key();  // not a structured binding: clang 14 cannot capture those
    if (key == "t" || key == "hand") continue;
    if (std::none_of(std::begin(actions), std::end(actions), [&](const char* a) { return key == a; }))
      reader.fail("unknown action \"" + key + "\" (grab, drag, release, press, set, orbit)");
    ++found;
  }
  if (found != 1) reader.fail("needs exactly one action of grab, drag, release, press, set, orbit");
  if (item.contains("hand")) {
    if (item.contains("set") || item.contains("orbit"))
      reader.fail("\"hand\" is not allowed with set or orbit (grab, drag, release, press take it)");
    const json& hand = item["hand"];
    if (!hand.is_number_integer() || hand.get<std::int64_t>() < 0 || hand.get<std::int64_t>() >= kHands)
      reader.fail("hand must be 0 or 1, got " + hand.dump());
    event.hand = hand.get<int>();
  }
  if (item.contains("grab")) {
    const json& grab = item["grab"];
    reader.allowOnly(grab, "grab", {"point", "radius", "grip"});
    event.kind = ScenarioEvent::Kind::Grab;
    event.point = reader.vector(grab, "grab", "point");
    event.radius = reader.number(grab, "grab", "radius", kDefaultGrabRadius, false, 1e-6);
    if (grab.contains("grip")) {
      const json& grip = grab["grip"];
      if (grip == "fist") event.grip = Grip::Fist;
      else if (grip != "pinch") reader.fail("grab.grip must be \"pinch\" or \"fist\", got " + grip.dump());
    }
  } else if (item.contains("drag")) {
    const json& drag = item["drag"];
    reader.allowOnly(drag, "drag", {"to", "duration"});
    event.kind = ScenarioEvent::Kind::Drag;
    event.to = reader.vector(drag, "drag", "to");
    event.duration = reader.number(drag, "drag", "duration", 0.0, false, 0.0);
  } else if (item.contains("release")) {
    reader.allowOnly(item["release"], "release", {});
    event.kind = ScenarioEvent::Kind::Release;
  } else if (item.contains("press")) {
    const json& press = item["press"];
    reader.allowOnly(press, "press", {"point", "direction", "depth", "duration", "hold", "radius"});
    event.kind = ScenarioEvent::Kind::Press;
    event.point = reader.vector(press, "press", "point");
    event.direction = reader.vector(press, "press", "direction");
    const double length = glm::length(event.direction);
    if (!(length > 0.0)) reader.fail("press.direction must not be zero");
    event.direction /= length;
    event.depth = reader.number(press, "press", "depth", 0.0, true, 0.0);
    event.duration = reader.number(press, "press", "duration", 0.0, false, 0.0);
    event.hold = reader.number(press, "press", "hold", 0.0, false, 0.0);
    event.radius = reader.number(press, "press", "radius", kDefaultGrabRadius, false, 1e-6);
  } else if (item.contains("orbit")) {
    const json& orbit = item["orbit"];
    reader.allowOnly(orbit, "orbit", {"yaw", "pitch", "duration"});
    event.kind = ScenarioEvent::Kind::Orbit;
    event.yaw = reader.number(orbit, "orbit", "yaw", 0.0, false, -1e6);
    event.pitch = reader.number(orbit, "orbit", "pitch", 0.0, false, -1e6);
    event.duration = reader.number(orbit, "orbit", "duration", 0.0, false, 0.0);
    if (event.yaw == 0.0 && event.pitch == 0.0) reader.fail("orbit needs a yaw or a pitch (degrees) that is not zero");
  } else {
    const json& values = item["set"];
    if (!values.is_object() || values.empty()) reader.fail("set must be an object of \"key\": value");
    Settings probe;  // check every key and value now, not when the event fires
    for (const auto& [key, value] : values.items()) {
      try {
        setSetting(probe, key, value);
      } catch (const SettingsError& error) {
        reader.fail(std::string("set: ") + error.what());
      }
    }
    event.kind = ScenarioEvent::Kind::Set;
    event.values = values;
  }
  return event;
}

}  // namespace

Scenario parseScenario(const json& document, const std::string& origin) {
  if (!document.is_object() || !document.contains("events") || !document["events"].is_array())
    throw SettingsError("scenario " + origin + ": expected an object {\"events\": [...]}");
  for (const auto& [key, value] : document.items())
    if (key != "events") throw SettingsError("scenario " + origin + ": unknown top-level key \"" + key + "\"");
  Scenario scenario;
  const json& events = document["events"];
  for (std::size_t i = 0; i < events.size(); ++i)
    scenario.events.push_back(readEvent(events[i], EventReader{origin, i}));
  std::stable_sort(scenario.events.begin(), scenario.events.end(),
                   [](const ScenarioEvent& a, const ScenarioEvent& b) { return a.time < b.time; });
  return scenario;
}

Scenario loadScenario(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw SettingsError("scenario " + path + ": cannot open the file");
  json document;
  try {
    document = json::parse(file);
  } catch (const json::parse_error& error) {
    throw SettingsError("scenario " + path + ": not valid JSON: " + error.what());
  }
  return parseScenario(document, path);
}

glm::dvec2 orbitAt(const Scenario& scenario, double t) {
  glm::dvec2 turned{0.0};
  for (const ScenarioEvent& event : scenario.events) {
    if (event.kind != ScenarioEvent::Kind::Orbit || event.time > t + kTimeTolerance) continue;
    const double done = event.duration > 0.0 ? std::clamp((t - event.time) / event.duration, 0.0, 1.0) : 1.0;
    turned += done * glm::dvec2(event.yaw, event.pitch);
  }
  return turned;
}

ScenarioPlayer::ScenarioPlayer(Scenario scenario) : scenario_(std::move(scenario)) {}

bool ScenarioPlayer::finished() const {
  return next_ >= scenario_.events.size() && !motion_[0].active && !motion_[1].active;
}

void ScenarioPlayer::fire(const ScenarioEvent& event, Simulation& simulation, Settings& settings) {
  Motion& motion = motion_[event.hand];
  switch (event.kind) {
    case ScenarioEvent::Kind::Grab:
      motion.active = false;
      simulation.grab(event.point, event.radius, event.hand, event.grip);
      break;
    case ScenarioEvent::Kind::Drag:
      if (!simulation.grabbing(event.hand)) break;
      motion = Motion{true, false, event.time, event.duration, 0.0, simulation.grabTarget(event.hand), event.to};
      break;
    case ScenarioEvent::Kind::Release:
      motion.active = false;
      simulation.release(event.hand);
      break;
    case ScenarioEvent::Kind::Press:
      motion.active = false;
      if (!simulation.grab(event.point, event.radius, event.hand)) break;
      motion = Motion{true, true, event.time, event.duration, event.hold, simulation.grabTarget(event.hand),
                      simulation.grabTarget(event.hand) + event.depth * event.direction};
      break;
    case ScenarioEvent::Kind::Set:
      for (const auto& [key, value] : event.values.items()) setSetting(settings, key, value);
      validateSettings(settings);
      simulation.applySettings(settings);
      break;
    case ScenarioEvent::Kind::Orbit:  // the viewer's camera (orbitAt), not the simulation's
      break;
  }
}

void ScenarioPlayer::advanceTo(double t, Simulation& simulation, Settings& settings) {
  while (next_ < scenario_.events.size() && scenario_.events[next_].time <= t + kTimeTolerance)
    fire(scenario_.events[next_++], simulation, settings);
  for (int hand = 0; hand < kHands; ++hand) {
    Motion& motion = motion_[hand];
    if (!motion.active) continue;
    const double progress =
        motion.duration > 0.0 ? std::clamp((t - motion.start) / motion.duration, 0.0, 1.0) : 1.0;
    simulation.dragTo(motion.from + progress * (motion.to - motion.from), hand);
    // A press stays at its depth for its hold, then lets go.
    if (progress >= 1.0 && t >= motion.start + motion.duration + motion.hold - kTimeTolerance) {
      motion.active = false;
      if (motion.releaseAtEnd) simulation.release(hand);
    }
  }
}

}  // namespace slime
