// Accuracy against cost of the integrators on one fixed scenario, a drop and a grab: the ball falls
// 2 cm onto the floor, its top is grabbed at 0.2 s and pulled up 3 cm and sideways 1 cm over
// 0.15 s, released at 0.4 s; 0.5 s in all. The error of a run is the distance of every vertex from
// where a reference run puts it (RK4 with a step of kReferenceStep, automatic substeps off), sampled
// every 10 ms: its RMS over vertices and samples, and its maximum. The cost is wall-clock seconds per
// simulated second. Every run takes exactly its dt (no automatic substeps): a run that blows up has
// no error, only the mark "unstable".
#pragma once

#include "app/bench/bench_progress.h"
#include "core/settings.h"

#include <glm/vec3.hpp>

#include <string>
#include <vector>

namespace slime {

constexpr double kReferenceStep = 2e-5;      // s
constexpr double kScenarioSeconds = 0.5;     // s
constexpr double kSampleInterval = 0.01;     // s
constexpr double kMaxRunWallSeconds = 40.0;  // a run slower than this is stopped and marked "too slow"

struct Trajectory {
  std::vector<std::vector<glm::dvec3>> samples;  // positions every kSampleInterval, from t = 0
  bool stable = true;
  bool finished = true;     // false: stopped at kMaxRunWallSeconds
  double wallSeconds = 0.0;
  long steps = 0;
};

// Runs the drop-and-grab with exactly settings.sim.dt per step (dt must divide kSampleInterval).
Trajectory runDropAndGrab(const Settings& settings);

struct TrajectoryError {
  double rmsMillimetres = 0.0;
  double maxMillimetres = 0.0;
};

TrajectoryError compareTrajectories(const Trajectory& run, const Trajectory& reference);

}  // namespace slime
