#include "app/bench/bench_physics.h"

#include "app/bench/bench_progress.h"
#include "app/bench/bench_report.h"
#include "app/bench/bench_stability.h"
#include "app/bench/bench_timing.h"
#include "app/bench/bench_trajectory_error.h"
#include "core/integrators.h"
#include "core/simulation.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>

namespace slime {
namespace {

using nlohmann::json;

constexpr int kWarmupSteps = 5;
constexpr int kMinTimedSteps = 3;

struct StepCost {
  double msPerStep = 0.0;
  int substeps = 1;
  long steps = 0;
};

// The ball starts 2 mm above the floor so that the timed steps include landing and contact.
StepCost timeSteps(const Settings& settings, double seconds) {
  Settings start = settings;
  start.slime.position.z = start.slime.radius + 0.002;
  Simulation simulation(start);
  for (int i = 0; i < kWarmupSteps; ++i) simulation.step();
  StepCost cost;
  cost.substeps = simulation.substepsPerStep();
  const Stopwatch watch;
  while (cost.steps < kMinTimedSteps || watch.milliseconds() < seconds * 1e3) {
    simulation.step();
    ++cost.steps;
  }
  cost.msPerStep = watch.milliseconds() / static_cast<double>(cost.steps);
  return cost;
}

// Roundness of the settled ball: aspect = height / width and the spread of the vertices' distances
// from their centroid (standard deviation / mean; 0 for a sphere).
json roundnessAtRest(const Settings& settings, double seconds) {
  Simulation simulation(settings);
  const Stopwatch watch;
  while (simulation.time() < seconds) simulation.step();
  const double msPerStep = watch.milliseconds() / static_cast<double>(std::max<std::int64_t>(1, simulation.stepCount()));
  const auto& positions = simulation.positions();
  glm::dvec3 centroid(0.0);
  for (const glm::dvec3& p : positions) centroid += p;
  centroid /= static_cast<double>(positions.size());
  double sum = 0.0, sumSquares = 0.0;
  for (const glm::dvec3& p : positions) {
    const double r = glm::length(p - centroid);
    sum += r;
    sumSquares += r * r;
  }
  const double n = static_cast<double>(positions.size());
  const double mean = sum / n;
  const SlimeMetrics metrics = simulation.metrics();
  return {{"level", settings.slime.level}, {"vertices", positions.size()}, {"integrator", settings.sim.integrator},
          {"seconds", seconds}, {"ms_per_step", msPerStep}, {"aspect", metrics.aspect},
          {"volume_ratio", metrics.volumeRatio}, {"radius_spread", std::sqrt(std::max(0.0, sumSquares / n - mean * mean)) / mean},
          {"kinetic_energy", metrics.kineticEnergy}};
}

}  // namespace

Settings physicsSettings(const Settings& base, int level, const std::string& integrator, double dt) {
  Settings settings = base;
  settings.slime.level = level;
  settings.sim.integrator = integrator;
  settings.sim.dt = dt;
  settings.sim.substeps = 1;
  return settings;
}

json runPhysicsBench(const Settings& base, const PhysicsBenchOptions& options) {
  const std::vector<std::string> integrators = options.integrators.empty() ? integratorNames() : options.integrators;
  const double units = integrators.size() * (options.levels.size() + 2.0 + options.stiffnesses.size() * 13.0 +
                                             options.steps.size()) + 2.0;
  BenchProgress progress("bench physics", units);
  json report = {{"bench", "physics"}, {"dt", base.sim.dt}, {"mass", base.slime.mass}, {"radius", base.slime.radius},
                 {"stiffness", base.slime.stiffness}, {"damping", base.slime.damping}};

  // Cost: ms per step of sim.dt with the substeps each integrator needs at each level.
  CsvTable costTable{{"integrator", "level", "vertices", "ms_per_step", "substeps", "ms_per_substep", "wall_per_simulated_s"}, {}};
  json cost = json::array();
  for (const std::string& integrator : integrators) {
    for (int level : options.levels) {
      const Settings settings = physicsSettings(base, level, integrator, base.sim.dt);
      const StepCost measured = timeSteps(settings, options.secondsPerMeasurement);
      const int vertices = 10 * (1 << (2 * level)) + 2;
      const double wallPerSecond = measured.msPerStep / (1e3 * base.sim.dt);
      cost.push_back({{"integrator", integrator}, {"level", level}, {"vertices", vertices},
                      {"ms_per_step", measured.msPerStep}, {"substeps", measured.substeps},
                      {"ms_per_substep", measured.msPerStep / measured.substeps}, {"steps_timed", measured.steps},
                      {"wall_per_simulated_s", wallPerSecond}});
      costTable.add({integrator, level, vertices, measured.msPerStep, measured.substeps,
                     measured.msPerStep / measured.substeps, wallPerSecond});
      std::printf("cost      %-17s level %d  %9.3f ms/step (%d substeps)  %7.3f s per simulated s\n", integrator.c_str(),
                  level, measured.msPerStep, measured.substeps, wallPerSecond);
      progress.advance(1.0, integrator + " level " + std::to_string(level));
    }
  }
  report["cost"] = cost;

  // Stability map: largest stable dt against stiffness, with the theory for the same mesh.
  CsvTable stabilityTable{{"integrator", "stiffness", "largest_stable_dt", "bounded", "omega_max"}, {}};
  CsvTable theoryTable{{"stiffness", "omega_max", "omega_estimate", "dt_symplectic", "dt_rk4", "dt_estimate"}, {}};
  json stability = json::array(), theory = json::array();
  if (options.stabilityLevel >= 0) {
    for (const std::string& integrator : integrators) {
      for (double stiffness : options.stiffnesses) {
        Settings settings = physicsSettings(base, options.stabilityLevel, integrator, base.sim.dt);
        settings.slime.stiffness = stiffness;
        const StabilityResult result = findLargestStableStep(settings, progress);
        progress.advance(13.0 - result.runs, integrator);
        stability.push_back({{"integrator", integrator}, {"level", options.stabilityLevel}, {"stiffness", stiffness},
                             {"largest_stable_dt", result.largestStableStep}, {"bounded", result.boundedAbove},
                             {"omega_max", result.omegaMax}, {"omega_dt", result.omegaMax * result.largestStableStep},
                             {"runs", result.runs}});
        stabilityTable.add({integrator, stiffness, result.largestStableStep, result.boundedAbove, result.omegaMax});
        std::printf("stability %-17s k %7.1f N/m  largest stable dt %.3e s%s  (omega_max dt = %.2f)\n", integrator.c_str(),
                    stiffness, result.largestStableStep, result.boundedAbove ? "" : " (never blew up)",
                    result.omegaMax * result.largestStableStep);
        if (integrator == integrators.front()) {
          theory.push_back({{"stiffness", stiffness}, {"omega_max", result.omegaMax}, {"omega_estimate", result.omegaEstimate},
                            {"dt_symplectic", 2.0 / result.omegaMax}, {"dt_rk4", 2.83 / result.omegaMax},
                            {"dt_estimate", 2.0 / result.omegaEstimate}});
          theoryTable.add({stiffness, result.omegaMax, result.omegaEstimate, 2.0 / result.omegaMax, 2.83 / result.omegaMax,
                           2.0 / result.omegaEstimate});
        }
      }
    }
  }
  report["stability"] = {{"level", options.stabilityLevel}, {"steps", kStabilitySteps}, {"map", stability},
                         {"theory", theory},
                         {"criterion", "ball started 1 mm into the floor, 400 steps of exactly dt: blown up if the "
                                       "divergence guard fires (NaN/inf, speed > 50 m/s), kinetic energy > 1 J, or "
                                       "volume outside [0.5, 2] V0"}};

  // Accuracy against cost: drop and grab against a small-step RK4 reference.
  CsvTable accuracyTable{{"integrator", "dt", "stable", "rms_error_mm", "max_error_mm", "wall_per_simulated_s"}, {}};
  json accuracy = json::array();
  if (options.accuracyLevel >= 0) {
    progress.advance(0.0, "reference trajectory (rk4)");
    const Trajectory reference = runDropAndGrab(physicsSettings(base, options.accuracyLevel, "rk4", kReferenceStep));
    progress.advance(2.0, "reference done");
    for (const std::string& integrator : integrators) {
      for (double dt : options.steps) {
        const Trajectory run = runDropAndGrab(physicsSettings(base, options.accuracyLevel, integrator, dt));
        const double simulated = run.steps * dt;
        const double wallPerSecond = simulated > 0.0 ? run.wallSeconds / simulated : 0.0;
        json entry = {{"integrator", integrator}, {"dt", dt}, {"stable", run.stable}, {"finished", run.finished},
                      {"wall_per_simulated_s", wallPerSecond}, {"ms_per_step", 1e3 * run.wallSeconds / std::max(1L, run.steps)}};
        if (run.stable && run.finished) {
          const TrajectoryError error = compareTrajectories(run, reference);
          entry["rms_error_mm"] = error.rmsMillimetres;
          entry["max_error_mm"] = error.maxMillimetres;
          accuracyTable.add({integrator, dt, 1, error.rmsMillimetres, error.maxMillimetres, wallPerSecond});
          std::printf("accuracy  %-17s dt %.0e s  RMS error %8.4f mm  max %8.3f mm  %8.3f s per simulated s\n",
                      integrator.c_str(), dt, error.rmsMillimetres, error.maxMillimetres, wallPerSecond);
        } else {
          accuracyTable.add({integrator, dt, 0, json(), json(), wallPerSecond});
          std::printf("accuracy  %-17s dt %.0e s  %s\n", integrator.c_str(), dt, run.stable ? "too slow" : "unstable");
        }
        accuracy.push_back(std::move(entry));
        progress.advance(1.0, integrator + " dt " + std::to_string(dt));
      }
    }
    report["accuracy"] = {{"level", options.accuracyLevel}, {"reference", {{"integrator", "rk4"}, {"dt", kReferenceStep},
                          {"wall_seconds", reference.wallSeconds}}}, {"scenario_seconds", kScenarioSeconds},
                          {"runs", accuracy}};
  }

  // Roundness at rest of the default integrator's ball, to set beside Bullet's (peers/bullet_ball.cpp).
  if (options.settleSeconds > 0.0) {
    Settings settings = physicsSettings(base, 4, base.sim.integrator, base.sim.dt);
    report["rest"] = roundnessAtRest(settings, options.settleSeconds);
    std::printf("rest      %-17s level 4  %.3f ms/step  aspect %.3f  radius spread %.4f  volume %.4f\n",
                base.sim.integrator.c_str(), report["rest"]["ms_per_step"].get<double>(), report["rest"]["aspect"].get<double>(),
                report["rest"]["radius_spread"].get<double>(), report["rest"]["volume_ratio"].get<double>());
  }
  progress.finish();

  if (!options.jsonFile.empty()) writeJsonFile(report, options.jsonFile);
  if (!options.csvFile.empty()) {
    writeCsvFile(costTable, options.csvFile);
    writeCsvFile(stabilityTable, siblingCsvPath(options.csvFile, "stability"));
    writeCsvFile(theoryTable, siblingCsvPath(options.csvFile, "theory"));
    writeCsvFile(accuracyTable, siblingCsvPath(options.csvFile, "accuracy"));
  }
  return report;
}

}  // namespace slime
