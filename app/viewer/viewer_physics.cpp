// The viewer's physics: the steps a frame owes the wall clock, within its budget, the hand dragged
// across them, the scenario's events fired between them, and what the frame keeps of their outcome.
#include "app/viewer/viewer.h"

#include "app/viewer/stopwatch.h"
#include "core/geometry/camera.h"

#include <algorithm>
#include <cstdio>

namespace slime {
namespace {

// ScenarioPlayer fires the events due within this of the simulated time (core/simulation/scenario.cpp).
constexpr double kScenarioTimeTolerance = 1e-9;

}  // namespace

// --- physics ---------------------------------------------------------------------------------------

void Viewer::simulationAdvanced() {
  slimeMoved_ = true;
  metrics_ = simulation_.metrics();
}

glm::dvec3 Viewer::grabTargetFor() const {
  const glm::ivec2 size = viewSize();
  return grab_.active() && size.x > 0 && size.y > 0 ? grab_.target(makeCamera(settings_.camera, size.x, size.y), size)
                                                    : grabTargetDrawn_[cursorHand_];
}

Viewer::PhysicsOutcome Viewer::stepPhysics(double wallSeconds, const glm::dvec3& target) {
  const Stopwatch physicsTime;
  PhysicsOutcome outcome;
  outcome.wallSeconds = wallSeconds;
  int steps = 0;
  if (settings_.sim.paused) {
    clock_.reset();
    steps = singleStepPending_ ? 1 : 0;
  } else {
    steps = clock_.stepsFor(wallSeconds, settings_.sim.timeScale, settings_.sim.dt);
  }
  singleStepPending_ = false;
  // Pull the grab target from where it was to where the cursor is now across this frame's steps, so
  // the slime is dragged smoothly however many steps a frame holds.
  int done = 0;
  for (; done < steps; ++done) {
    if (grab_.active()) {
      const double progress = static_cast<double>(done + 1) / steps;
      const glm::dvec3& from = grabTargetDrawn_[cursorHand_];
      simulation_.dragTo(from + (target - from) * progress, cursorHand_);
    }
    if (scenario_ && !scenario_->finished()) playScenarioAt(simulation_.time(), outcome);
    const int tears = simulation_.tears(), merges = simulation_.merges();
    simulation_.step();
    if (simulation_.tears() != tears || simulation_.merges() != merges) {
      outcome.topologyMs += simulation_.lastTopologyMilliseconds();
      // Said as it happens, so that a script driving the window can wait for it (tests/scripts).
      std::printf("slime view: %s %d at %.3f s simulated, %zu pieces\n", simulation_.tears() != tears ? "tear" : "merge",
                  simulation_.tears() != tears ? simulation_.tears() : simulation_.merges(), simulation_.time(),
                  simulation_.pieceCount());
      std::fflush(stdout);
    }
    if (physicsTime.milliseconds() > kPhysicsBudgetMs && done + 1 < steps) {  // out of time: the rest waits
      if (!settings_.sim.paused) clock_.giveBack(steps - done - 1, settings_.sim.dt);
      ++done;
      break;
    }
  }
  outcome.steps = done;
  if (grab_.active() && done > 0) grabTargetDrawn_[cursorHand_] = target;
  if (done > 0) outcome.metrics = simulation_.metrics();
  outcome.grabbing = simulation_.anyGrabbing();
  outcome.twoHands = simulation_.grabbing(0) && simulation_.grabbing(1);
  outcome.milliseconds = physicsTime.milliseconds();
  return outcome;
}

// Fires the scenario's events due at `time` and notes what the report counts: the grabs and presses
// that took hold (a grab always finds the surface point nearest to its point; a press that ends at
// once never holds), and "set" events, which change what is drawn.
void Viewer::playScenarioAt(double time, PhysicsOutcome& outcome) {
  scenario_->advanceTo(time, simulation_, settings_);
  const std::vector<ScenarioEvent>& events = options_.scenario->events;  // the player's, in its order
  for (; scenarioEventsFired_ < events.size(); ++scenarioEventsFired_) {
    const ScenarioEvent& event = events[scenarioEventsFired_];
    if (event.time > time + kScenarioTimeTolerance) break;
    const ScenarioEvent::Kind kind = event.kind;
    if (kind == ScenarioEvent::Kind::Set) outcome.settingsEdited = true;
    if ((kind == ScenarioEvent::Kind::Grab || kind == ScenarioEvent::Kind::Press) && simulation_.anyGrabbing()) {
      ++outcome.scenarioGrabs;
      outcome.heightAtGrab = simulation_.metrics().height;
    }
  }
}

bool Viewer::scenarioSetPending() const {
  if (!options_.scenario) return false;
  const std::vector<ScenarioEvent>& events = options_.scenario->events;
  return std::any_of(events.begin() + static_cast<std::ptrdiff_t>(scenarioEventsFired_), events.end(),
                     [](const ScenarioEvent& event) { return event.kind == ScenarioEvent::Kind::Set; });
}

void Viewer::applyPhysicsOutcome(const PhysicsOutcome& outcome) {
  if (outcome.steps > 0) {
    slimeMoved_ = true;
    metrics_ = outcome.metrics;
    // Touched down: the lowest point within a fiftieth of the radius of the floor (z = 0).
    if (metrics_.minZ < 0.02 * settings_.slime.radius) landed_ = true;
    if (outcome.grabbing) peakHeightWhileGrabbing_ = std::max(peakHeightWhileGrabbing_, metrics_.height);
    if (outcome.twoHands) peakWidthWhileTwoHands_ = std::max(peakWidthWhileTwoHands_, metrics_.width);
  }
  if (outcome.scenarioGrabs > 0) {
    if (widthBeforeGrabs_ < 0.0) widthBeforeGrabs_ = metrics_.width;
    grabCount_ += outcome.scenarioGrabs;
    heightAtGrab_ = outcome.heightAtGrab;
  }
  if (outcome.settingsEdited) {
    sceneChanged_ = true;
    editedFrame_ = editDrawnFrame_ = stats_.frames;
  }
  peakPieces_ = std::max(peakPieces_, simulation_.pieceCount());
  topologyMs_ = outcome.topologyMs;
  longestTopologyMs_ = std::max(longestTopologyMs_, topologyMs_);
  stats_.physicsSteps = outcome.steps;
  stats_.stages.physics = outcome.milliseconds;
  stats_.recordSimulatedTime(outcome.steps * settings_.sim.dt, outcome.wallSeconds);
}

}  // namespace slime
