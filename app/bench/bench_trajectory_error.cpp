#include "app/bench/bench_trajectory_error.h"

#include "app/bench/bench_timing.h"
#include "core/scenario.h"
#include "core/simulation.h"

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace slime {
namespace {

constexpr double kDropHeight = 0.02;  // m between the floor and the ball's bottom at t = 0

Scenario dropAndGrab(const Settings& settings) {
  const double radius = settings.slime.radius;
  const glm::dvec3 top{settings.slime.position.x, settings.slime.position.y, 2.0 * radius};
  const nlohmann::json document = {
      {"events",
       {{{"t", 0.2}, {"grab", {{"point", {top.x, top.y, top.z}}, {"radius", 0.015}}}},
        {{"t", 0.2}, {"drag", {{"to", {top.x + 0.01, top.y, top.z + 0.03}}, {"duration", 0.15}}}},
        {{"t", 0.4}, {"release", nlohmann::json::object()}}}}};
  return parseScenario(document, "bench drop and grab");
}

}  // namespace

Trajectory runDropAndGrab(const Settings& base) {
  Settings settings = base;
  settings.slime.position.z = settings.slime.radius + kDropHeight;
  const long stepsPerSample = std::lround(kSampleInterval / settings.sim.dt);
  if (stepsPerSample < 1 || std::abs(stepsPerSample * settings.sim.dt - kSampleInterval) > 1e-9)
    throw std::invalid_argument("bench physics: dt " + std::to_string(settings.sim.dt) + " s must divide 10 ms");
  const long samples = std::lround(kScenarioSeconds / kSampleInterval);

  Trajectory trajectory;
  ScenarioPlayer player(dropAndGrab(settings));
  Simulation simulation(settings);
  simulation.setAutomaticSubsteps(false);
  trajectory.samples.push_back(simulation.positions());
  const Stopwatch watch;
  for (long sample = 1; sample <= samples; ++sample) {
    for (long step = 0; step < stepsPerSample; ++step) {
      player.advanceTo(simulation.time(), simulation, settings);
      simulation.step();
      ++trajectory.steps;
      if (!simulation.divergences().empty()) {
        trajectory.stable = false;
        trajectory.wallSeconds = watch.milliseconds() / 1e3;
        return trajectory;
      }
    }
    trajectory.samples.push_back(simulation.positions());
    if (watch.milliseconds() > kMaxRunWallSeconds * 1e3) {
      trajectory.finished = false;
      break;
    }
  }
  trajectory.wallSeconds = watch.milliseconds() / 1e3;
  return trajectory;
}

TrajectoryError compareTrajectories(const Trajectory& run, const Trajectory& reference) {
  TrajectoryError error;
  const std::size_t samples = std::min(run.samples.size(), reference.samples.size());
  double sumSquares = 0.0;
  std::size_t count = 0;
  for (std::size_t s = 0; s < samples; ++s) {
    const auto& a = run.samples[s];
    const auto& b = reference.samples[s];
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
      const double distance = glm::length(a[i] - b[i]);
      sumSquares += distance * distance;
      error.maxMillimetres = std::max(error.maxMillimetres, 1e3 * distance);
      ++count;
    }
  }
  error.rmsMillimetres = count ? 1e3 * std::sqrt(sumSquares / count) : 0.0;
  return error;
}

}  // namespace slime
