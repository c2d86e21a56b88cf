#include "app/bench/physics/bench_trajectory_error.h"

#include "app/bench/report/bench_timing.h"
#include "core/simulation/scenario.h"
#include "core/simulation/simulation.h"

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <stdexcept>

namespace slime {
namespace {

constexpr double kDropHeight = 0.02;  // m between the floor and the ball's bottom at t = 0
constexpr double kAirHeight = 1.5;    // m, the pinch in the air: out of the floor's reach for 0.5 s

// The grab at kGrabTime of the top of the landed ball, or at t = 0 of the top of the ball in the air;
// the same pull and release for both.
Scenario dropAndGrab(const Settings& settings, bool inTheAir) {
  const double radius = settings.slime.radius;
  const glm::dvec3 top{settings.slime.position.x, settings.slime.position.y,
                       inTheAir ? settings.slime.position.z + radius : 2.0 * radius};
  const nlohmann::json document = {
      {"events",
       {{{"t", inTheAir ? 0.0 : kGrabTime}, {"grab", {{"point", {top.x, top.y, top.z}}, {"radius", 0.015}}}},
        {{"t", kGrabTime}, {"drag", {{"to", {top.x + 0.01, top.y, top.z + 0.03}}, {"duration", 0.15}}}},
        {{"t", 0.4}, {"release", nlohmann::json::object()}}}}};
  return parseScenario(document, "bench drop and grab");
}

bool divides(double step, double interval) {
  const long count = std::lround(interval / step);
  return count >= 1 && std::abs(count * step - interval) < 1e-9 * interval;
}

}  // namespace

double processCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

Settings withSubstep(Settings settings, double h, double programStep) {
  if (h <= programStep && divides(h, programStep)) {
    settings.sim.dt = programStep;
    settings.sim.substeps = static_cast<int>(std::lround(programStep / h));
  } else if (divides(h, kSampleInterval)) {
    settings.sim.dt = h;
    settings.sim.substeps = 1;
  } else {
    throw std::invalid_argument("bench physics: a substep of " + std::to_string(h) + " s must divide sim.dt (" +
                                std::to_string(programStep) + " s) or 10 ms");
  }
  return settings;
}

Trajectory runDropAndGrab(const Settings& base, const DropAndGrabOptions& options) {
  Settings settings = base;
  settings.slime.position.z = settings.slime.radius + (options.inTheAir ? kAirHeight : kDropHeight);
  if (!divides(settings.sim.dt, kSampleInterval))
    throw std::invalid_argument("bench physics: dt " + std::to_string(settings.sim.dt) + " s must divide 10 ms");
  const long stepsPerSample = std::lround(kSampleInterval / settings.sim.dt);
  const long samples = std::lround(kScenarioSeconds / kSampleInterval);

  Trajectory trajectory;
  ScenarioPlayer player(dropAndGrab(settings, options.inTheAir));
  Simulation simulation(settings);
  simulation.setAutomaticSubsteps(options.automaticSubsteps);
  trajectory.samples.push_back(simulation.positions());
  trajectory.simulatedPoints = simulation.state().size();
  trajectory.drawnVertices = simulation.positions().size();
  const Stopwatch watch;
  const double cpuStart = processCpuSeconds();
  const auto stop = [&] {
    trajectory.wallSeconds = watch.milliseconds() / 1e3;
    trajectory.cpuSeconds = processCpuSeconds() - cpuStart;
    trajectory.simulatedSeconds = simulation.time();
    trajectory.substeps = simulation.substepsPerStep();
  };
  for (long sample = 1; sample <= samples; ++sample) {
    for (long step = 0; step < stepsPerSample; ++step) {
      player.advanceTo(simulation.time(), simulation, settings);
      simulation.step();
      ++trajectory.steps;
      if (!simulation.divergences().empty()) {
        trajectory.stable = false;
        stop();
        return trajectory;
      }
    }
    // The drawn surface is placed here, every 10 ms, as a viewer does once per frame.
    const std::vector<glm::dvec3>& drawn = simulation.positions();
    if (options.keepSamples) trajectory.samples.push_back(drawn);
    if (processCpuSeconds() - cpuStart > options.maxCpuSeconds) {
      trajectory.finished = false;
      break;
    }
  }
  stop();
  return trajectory;
}

TrajectoryError compareTrajectories(const Trajectory& run, const Trajectory& reference) {
  TrajectoryError error;
  const std::size_t samples = std::min(run.samples.size(), reference.samples.size());
  const std::size_t samplesBeforeGrab = static_cast<std::size_t>(std::lround(kGrabTime / kSampleInterval));
  double sumSquares = 0.0, sumSquaresBeforeGrab = 0.0;
  std::size_t count = 0, countBeforeGrab = 0;
  for (std::size_t s = 0; s < samples; ++s) {
    const auto& a = run.samples[s];
    const auto& b = reference.samples[s];
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
      const double distance = glm::length(a[i] - b[i]);
      sumSquares += distance * distance;
      error.maxMillimetres = std::max(error.maxMillimetres, 1e3 * distance);
      ++count;
      if (s < samplesBeforeGrab) {
        sumSquaresBeforeGrab += distance * distance;
        ++countBeforeGrab;
      }
    }
  }
  error.rmsMillimetres = count ? 1e3 * std::sqrt(sumSquares / count) : 0.0;
  error.rmsBeforeGrabMillimetres = countBeforeGrab ? 1e3 * std::sqrt(sumSquaresBeforeGrab / countBeforeGrab) : 0.0;
  return error;
}

}  // namespace slime
