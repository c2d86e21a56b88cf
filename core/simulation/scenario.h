// Scripted interaction: a scenario file (JSON) of timed events that `slime sim`, `snapshot` and the
// viewer replay with --scenario FILE:
//   {"events":[{"t":0.5,"grab":{"point":[x,y,z],"radius":0.015}},
//              {"t":0.5,"drag":{"to":[x,y,z],"duration":0.3}},
//              {"t":1.2,"release":{}},
//              {"t":1.5,"press":{"point":[x,y,z],"direction":[0,0,-1],"depth":0.02,"duration":0.3}},
//              {"t":2.0,"set":{"slime.stiffness":60}},
//              {"t":3.0,"orbit":{"yaw":90,"pitch":10,"duration":3}}]}
// Grab, drag, release and press take an optional "hand": 0 or 1 beside "t" (default 0), which of the
// two hands acts: {"t":4.0,"hand":1,"grab":{...}}; each hand has its own drag or press in progress.
// `point` means the surface point nearest to it. A grab's optional "grip" is "pinch" (the default) or
// "fist" (grab.h: a bulk slime's held wad goes with the hand whole instead of drawing out). A press grabs the region within `radius` (default
// 0.015 m) of that point, pushes it `depth` along `direction` over `duration`, holds it there for
// `hold` s (default 0), then lets go.
// An orbit turns the viewer's camera about the slime by `yaw` degrees (counter-clockwise about +z,
// seen from above) and `pitch` degrees (up) over `duration` s of simulated time, as a right-drag does:
// the viewer's alone (`slime sim` and `snapshot` have no moving camera and pass over it), so that the
// orbiting phase of the viewer's frames can be measured without a mouse (`slime bench viewer`).
// A bad file is a SettingsError that names the file, the event and what is wrong.
#pragma once

#include "core/hands/grab.h"
#include "core/settings/settings.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace slime {

class Simulation;

constexpr double kDefaultGrabRadius = 0.015;  // m

struct ScenarioEvent {
  enum class Kind { Grab, Drag, Release, Press, Set, Orbit };
  double time = 0.0;        // s
  Kind kind = Kind::Release;
  glm::dvec3 point{0.0};    // grab, press: near the surface point to take
  double radius = kDefaultGrabRadius;
  glm::dvec3 to{0.0};       // drag: where the grab target goes
  glm::dvec3 direction{0.0, 0.0, -1.0};  // press: unit direction
  double depth = 0.0;       // press: m
  double duration = 0.0;    // drag, press, orbit: s (0 = at once)
  double yaw = 0.0;         // orbit: degrees about +z
  double pitch = 0.0;       // orbit: degrees up
  double hold = 0.0;        // press: s held at its depth before letting go
  nlohmann::json values;    // set: {"dotted.key": value, ...}
  int hand = 0;             // grab, drag, release, press: which hand (0 or 1)
  Grip grip = Grip::Pinch;  // grab
};

struct Scenario {
  std::vector<ScenarioEvent> events;  // sorted by time; events at the same time keep file order
};

// `origin` names the source in messages (the file path).
Scenario parseScenario(const nlohmann::json& document, const std::string& origin);
Scenario loadScenario(const std::string& path);

// The camera's turn by the scenario's orbits up to simulated time t: (yaw, pitch) in degrees, summed
// over the orbits begun, each its fraction done (linear over its duration).
glm::dvec2 orbitAt(const Scenario& scenario, double t);

// Replays a scenario: call advanceTo(sim.time(), ...) before every step.
class ScenarioPlayer {
 public:
  explicit ScenarioPlayer(Scenario scenario);

  // Fires the events due by time t and moves the current drag/press along.
  void advanceTo(double t, Simulation& simulation, Settings& settings);
  bool finished() const;

 private:
  struct Motion {  // a drag or press in progress: the grab target moves from `from` to `to`
    bool active = false;
    bool releaseAtEnd = false;
    double start = 0.0, duration = 0.0;
    double hold = 0.0;  // a press: s kept at `to` before the release
    glm::dvec3 from{0.0}, to{0.0};
  };
  void fire(const ScenarioEvent& event, Simulation& simulation, Settings& settings);

  Scenario scenario_;
  std::size_t next_ = 0;
  Motion motion_[2];  // per hand
};

}  // namespace slime
