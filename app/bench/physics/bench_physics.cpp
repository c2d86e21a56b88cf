#include "app/bench/physics/bench_physics.h"

#include "app/bench/physics/bench_peers.h"
#include "app/bench/report/bench_progress.h"
#include "app/bench/report/bench_report.h"
#include "app/bench/physics/bench_stability.h"
#include "app/bench/report/bench_timing.h"
#include "app/bench/physics/bench_trajectory_error.h"
#include "core/integrators/integrators.h"
#include "core/simulation/simulation.h"
#include "core/integrators/stability.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <thread>
#include <tuple>

namespace slime {
namespace {

using nlohmann::json;

constexpr int kMaxCostRepeats = 25;
// The reference run's RK4 substep: a fifth of the smallest substep tried, but no smaller than these.
constexpr double kBulkReferenceStep = 1e-5;      // s, the bulk body's (its RK4 substep costs 0.4 ms)
constexpr double kMembraneReferenceStep = 2e-5;  // s, the membrane's (the previous charts' reference)
constexpr double kReferenceRatio = 5.0;
const std::vector<double> kErrorTargets{0.01, 0.03, 0.1, 0.3, 1.0, 3.0};  // mm RMS, for the integrator choice

// Jolt Physics's soft body (skin + pressure) on the same ball, kept round (aspect 0.85–0.90), one core:
// ms per 1 ms simulated, as SPEC §9 and issue 14 quote them (measured 2026-11-23, not by this bench).
struct QuotedFigure {
  int level;
  int vertices;
  double low, high;  // ms per 1 ms simulated
};
constexpr QuotedFigure kJolt[] = {{3, 642, 0.027, 0.027}, {4, 2562, 0.214, 0.214}, {5, 10242, 1.72, 1.72},
                                  {6, 40962, 12.2, 13.5}};

// Jolt Physics on the bulk body's own tetrahedra (one edge and one volume constraint per element, 60 Hz
// steps, the fewest iterations that keep it stable and uninverted), one thread, on an AMD EPYC family 23:
// ms per 1 ms simulated, as issue 27 quotes them (measured 2026-11-26, not by this bench).
struct JoltTetFigure {
  int resolution, nodes, iterations;
  double msPerMs;
};
constexpr JoltTetFigure kJoltTets[] = {{1, 85, 4, 0.006}, {2, 487, 8, 0.066}, {3, 3211, 26, 1.51}, {4, 23059, 62, 28.0}};

// ---- Cost -------------------------------------------------------------------------------------------

struct CostFigure {
  TimingSummary cpuMsPerSecond;  // CPU ms per simulated second, over the repeats
  double wallMsPerSecond = 0.0;  // median
  int substeps = 1;
  std::size_t simulatedPoints = 0, drawnVertices = 0;
  bool stable = true;
};

// The drop-and-grab with the program's automatic substeps, repeated for `seconds` of wall time (at
// least once): landing, floor contact, a grab, a drag and a release, as a person's first seconds.
CostFigure measureCost(const Settings& settings, double seconds) {
  CostFigure figure;
  std::vector<double> cpu, wall;
  const Stopwatch total;
  do {
    const Trajectory run = runDropAndGrab(settings, {.automaticSubsteps = true, .keepSamples = false});
    figure.substeps = run.substeps;
    figure.simulatedPoints = run.simulatedPoints;
    figure.drawnVertices = run.drawnVertices;
    if (!run.stable || run.simulatedSeconds <= 0.0) {
      figure.stable = false;
      break;
    }
    cpu.push_back(1e3 * run.cpuSeconds / run.simulatedSeconds);
    wall.push_back(1e3 * run.wallSeconds / run.simulatedSeconds);
  } while (total.milliseconds() < seconds * 1e3 && static_cast<int>(cpu.size()) < kMaxCostRepeats);
  figure.cpuMsPerSecond = summarize(cpu);
  figure.wallMsPerSecond = summarize(wall).median;
  return figure;
}

// ---- Accuracy ---------------------------------------------------------------------------------------

struct AccuracyRun {
  std::string integrator;
  double h = 0.0;
  bool automatic = false;
};

json accuracyEntry(const std::string& model, const AccuracyRun& spec, const Settings& settings, const Trajectory& run,
                   const Trajectory& reference, CsvTable& table) {
  const double simulated = run.simulatedSeconds;
  const double cpuPerSecond = simulated > 0.0 ? run.cpuSeconds / simulated : 0.0;
  const double wallPerSecond = simulated > 0.0 ? run.wallSeconds / simulated : 0.0;
  // The substep asked for; the automatic runs' is what stability chose. (After a blow-up the guard's
  // refinement would show in run.substeps: not the setting that was measured.)
  const int substeps = spec.automatic ? run.substeps : settings.sim.substeps;
  const double h = settings.sim.dt / substeps;
  json entry = {{"model", model}, {"integrator", spec.integrator}, {"h", h}, {"dt", settings.sim.dt},
                {"substeps", substeps}, {"automatic", spec.automatic}, {"stable", run.stable},
                {"finished", run.finished}, {"cpu_s_per_simulated_s", cpuPerSecond},
                {"wall_s_per_simulated_s", wallPerSecond}};
  const std::string series = model + ":" + spec.integrator + (spec.automatic ? ":automatic" : "");
  if (run.stable && run.finished) {
    const TrajectoryError error = compareTrajectories(run, reference);
    entry["rms_error_mm"] = error.rmsMillimetres;
    entry["max_error_mm"] = error.maxMillimetres;
    entry["rms_error_mm_before_grab"] = error.rmsBeforeGrabMillimetres;
    table.add({series, model, spec.integrator, h, settings.sim.dt, substeps, spec.automatic ? 1 : 0, 1,
               error.rmsMillimetres, error.maxMillimetres, cpuPerSecond, wallPerSecond, error.rmsBeforeGrabMillimetres});
    std::printf("accuracy  %-8s %-17s h %.1e s%s  RMS error %9.4f mm (before the grab %9.4f)  max %8.3f mm  %7.3f CPU s "
                "per simulated s\n", model.c_str(), spec.integrator.c_str(), h, spec.automatic ? " (auto)" : "       ",
                error.rmsMillimetres, error.rmsBeforeGrabMillimetres, error.maxMillimetres, cpuPerSecond);
  } else {
    table.add({series, model, spec.integrator, h, settings.sim.dt, substeps, spec.automatic ? 1 : 0, 0, json(),
               json(), cpuPerSecond, wallPerSecond, json()});
    std::printf("accuracy  %-8s %-17s h %.1e s%s  %s\n", model.c_str(), spec.integrator.c_str(), h,
                spec.automatic ? " (auto)" : "       ", run.stable ? "too slow" : "unstable");
  }
  return entry;
}

// The accuracy runs of one model: a small-step RK4 reference (and its own error, against a run of
// twice its step), then every integrator at every substep h, and at the program's automatic substeps.
json accuracyForModel(const Settings& base, const std::string& model, const std::vector<std::string>& integrators,
                      const PhysicsBenchOptions& options, BenchProgress& progress, CsvTable& table) {
  const double programStep = base.sim.dt;
  const double smallest = options.steps.empty() ? programStep : *std::min_element(options.steps.begin(), options.steps.end());
  const double wanted = std::max(model == "bulk" ? kBulkReferenceStep : kMembraneReferenceStep, smallest / kReferenceRatio);
  const long referenceSubsteps = std::max(2L, static_cast<long>(std::ceil(programStep / wanted - 1e-9)));
  const double referenceStep = programStep / static_cast<double>(referenceSubsteps);
  const Settings plain = physicsSettings(base, model, options.accuracyLevel, "rk4", programStep);
  progress.advance(0.0, model + " reference trajectory (rk4)");
  const double unlimited = std::numeric_limits<double>::infinity();
  const DropAndGrabOptions referenceOptions{.inTheAir = true, .maxCpuSeconds = unlimited};
  const Trajectory reference = runDropAndGrab(withSubstep(plain, referenceStep, programStep), referenceOptions);
  const double checkStep = programStep / static_cast<double>(referenceSubsteps / 2);
  const Trajectory check = runDropAndGrab(withSubstep(plain, checkStep, programStep), referenceOptions);
  const TrajectoryError floor = compareTrajectories(check, reference);
  std::printf("accuracy  %-8s reference rk4 h %.1e s: %.1f CPU s; against h %.1e s it moves %.2e mm RMS\n",
              model.c_str(), referenceStep, reference.cpuSeconds, checkStep, floor.rmsMillimetres);
  // The same two steps on the drop and grab: how far apart the landing's contact decisions put them.
  const DropAndGrabOptions landingOptions{.maxCpuSeconds = unlimited};
  const TrajectoryError landing =
      compareTrajectories(runDropAndGrab(withSubstep(plain, checkStep, programStep), landingOptions),
                          runDropAndGrab(withSubstep(plain, referenceStep, programStep), landingOptions));
  std::printf("accuracy  %-8s drop and grab: rk4 at h %.1e s and %.1e s end %.3f mm RMS apart (%.3f before the grab)\n",
              model.c_str(), referenceStep, checkStep, landing.rmsMillimetres, landing.rmsBeforeGrabMillimetres);
  progress.advance(5.0, model + " reference done");

  std::vector<AccuracyRun> specs;
  for (const std::string& integrator : integrators) {
    for (double h : options.steps) specs.push_back({integrator, h, false});
    specs.push_back({integrator, programStep, true});
  }
  json runs = json::array();
  std::map<std::string, double> predictedLimit;  // per integrator, s: what the automatic substeps use
  for (const std::string& integrator : integrators)
    predictedLimit[integrator] =
        Simulation(physicsSettings(base, model, options.accuracyLevel, integrator, programStep)).largestStableStep();
  for (const AccuracyRun& spec : specs) {
    Settings settings = physicsSettings(base, model, options.accuracyLevel, spec.integrator, programStep);
    if (!spec.automatic) settings = withSubstep(settings, spec.h, programStep);
    const Trajectory run = runDropAndGrab(settings, {.inTheAir = true, .automaticSubsteps = spec.automatic});
    json entry = accuracyEntry(model, spec, settings, run, reference, table);
    const double limit = predictedLimit[spec.integrator];
    entry["predicted_limit"] = std::isfinite(limit) ? json(limit) : json();
    entry["within_predicted_limit"] = entry["h"].get<double>() <= kStabilitySafety * limit * (1.0 + 1e-9);
    runs.push_back(std::move(entry));
    progress.advance(1.0, model + " " + spec.integrator);
  }
  return {{"model", model}, {"level", options.accuracyLevel},
          {"resolution", model == "bulk" ? json(base.slime.resolution) : json()},
          {"reference", {{"integrator", "rk4"}, {"h", referenceStep}, {"cpu_seconds", reference.cpuSeconds},
                         {"check_h", checkStep}, {"rms_error_mm_of_the_check", floor.rmsMillimetres}}},
          {"scenario", "pinch in the air (no contact; bench_trajectory_error.h)"},
          {"scenario_seconds", kScenarioSeconds}, {"runs", runs},
          {"landing", {{"scenario", "drop and grab"}, {"h", {referenceStep, checkStep}},
                       {"rms_apart_mm", landing.rmsMillimetres}, {"rms_apart_mm_before_grab", landing.rmsBeforeGrabMillimetres},
                       {"note", "two RK4 runs of the drop and grab that differ only in their small substep: the "
                                "contact's discrete decisions set this floor under any integrator's error"}}},
          {"choice", cheapestForAccuracy(runs, kErrorTargets, true)},
          {"choice_any_stable_run", cheapestForAccuracy(runs, kErrorTargets, false)},
          {"choice_rule", "the cheapest run within each RMS error target among the runs the program would make "
                          "(h within kStabilitySafety = 0.8 of the integrator's predicted limit); "
                          "choice_any_stable_run: among every run that did not blow up"}};
}

// ---- Stability --------------------------------------------------------------------------------------

json stabilityPoint(const Settings& settings, const std::string& model, double parameter, BenchProgress& progress,
                    CsvTable& table) {
  const std::string& integrator = settings.sim.integrator;
  const StabilityResult result = findLargestStableStep(settings, progress);
  progress.advance(13.0 - result.runs, integrator);
  const bool predicted = std::isfinite(result.predictedStep);
  const bool membrane = model == "membrane";
  json point = {{"model", model}, {"integrator", integrator}, {"level", settings.slime.level},
                {membrane ? "stiffness" : "modulus", parameter}, {"largest_stable_dt", result.largestStableStep},
                {"bounded", result.boundedAbove}, {"omega_max", result.omegaMax},
                {"predicted_dt", predicted ? json(result.predictedStep) : json()},
                {"measured_over_predicted", predicted ? json(result.largestStableStep / result.predictedStep) : json()},
                {"runs", result.runs}};
  if (!membrane) point["resolution"] = settings.slime.resolution;
  const double estimate = membrane ? 2.0 / result.omegaEstimate : 0.0;
  if (membrane) point["estimate_dt"] = estimate;
  table.add({model + ":" + integrator, model, integrator, parameter, result.largestStableStep, result.boundedAbove ? 1 : 0,
             predicted ? json(result.predictedStep) : json(), result.omegaMax, membrane ? json(estimate) : json()});
  std::printf("stability %-8s %-17s %s %8.1f %s  largest stable dt %.3e s%s  predicted %.3e s\n", model.c_str(),
              integrator.c_str(), membrane ? "k" : "G", parameter, membrane ? "N/m" : "Pa ", result.largestStableStep,
              result.boundedAbove ? "" : " (never blew up)", predicted ? result.predictedStep : 0.0);
  return point;
}

// ---- Rest -------------------------------------------------------------------------------------------

// Roundness of the settled ball: aspect = height / width and the spread of the drawn vertices'
// distances from their centroid (standard deviation / mean; 0 for a sphere).
json roundnessAtRest(const Settings& settings, double seconds) {
  Simulation simulation(settings);
  const double cpuStart = processCpuSeconds();
  while (simulation.time() < seconds) simulation.step();
  const double cpuMsPerSecond = 1e3 * (processCpuSeconds() - cpuStart) / simulation.time();
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
  return {{"model", settings.slime.model}, {"level", settings.slime.level}, {"vertices", positions.size()},
          {"integrator", settings.sim.integrator}, {"seconds", seconds}, {"cpu_ms_per_simulated_s", cpuMsPerSecond},
          {"aspect", metrics.aspect}, {"volume_ratio", metrics.volumeRatio},
          {"radius_spread", std::sqrt(std::max(0.0, sumSquares / n - mean * mean)) / mean},
          {"kinetic_energy", metrics.kineticEnergy}};
}

}  // namespace

Settings physicsSettings(const Settings& base, const std::string& model, int level, const std::string& integrator,
                         double dt) {
  Settings settings = base;
  settings.slime.model = model;
  settings.slime.level = level;
  settings.sim.integrator = integrator;
  settings.sim.dt = dt;
  settings.sim.substeps = 1;
  return settings;
}

std::vector<std::string> bulkIntegrators(const std::vector<std::string>& requested) {
  std::vector<std::string> bulk;
  for (const std::string& name : requested)
    if (name == "symplectic_euler" || name == "explicit_euler" || name == "rk4" || name == "projective")
      bulk.push_back(name);
  return bulk;
}

json cheapestForAccuracy(const json& runs, const std::vector<double>& targetsMillimetres, bool runnableOnly) {
  json choices = json::array();
  for (double target : targetsMillimetres) {
    json byIntegrator = json::object(), best = nullptr;
    for (const json& run : runs) {
      if (!run.value("stable", false) || !run.value("finished", false) || !run.contains("rms_error_mm")) continue;
      if (runnableOnly && !run.value("within_predicted_limit", true)) continue;
      if (run["rms_error_mm"].get<double>() > target) continue;
      const std::string integrator = run["integrator"];
      const double cost = run["cpu_s_per_simulated_s"];
      if (!byIntegrator.contains(integrator) || cost < byIntegrator[integrator]["cpu_s_per_simulated_s"].get<double>())
        byIntegrator[integrator] = {{"cpu_s_per_simulated_s", cost}, {"h", run["h"]}, {"automatic", run["automatic"]},
                                    {"rms_error_mm", run["rms_error_mm"]}};
      if (best.is_null() || cost < best["cpu_s_per_simulated_s"].get<double>())
        best = {{"integrator", integrator}, {"cpu_s_per_simulated_s", cost}, {"h", run["h"]},
                {"automatic", run["automatic"]}, {"rms_error_mm", run["rms_error_mm"]}};
    }
    choices.push_back({{"rms_error_mm_at_most", target}, {"cheapest", best}, {"by_integrator", byIntegrator}});
  }
  return choices;
}

json runPhysicsBench(const Settings& base, const PhysicsBenchOptions& options) {
  const std::vector<std::string> integrators = options.integrators.empty() ? integratorNames() : options.integrators;
  const std::vector<std::string> bulk = bulkIntegrators(integrators);
  std::vector<std::string> membrane;  // projective is the bulk body's only
  for (const std::string& name : integrators)
    if (name != "projective") membrane.push_back(name);
  const std::string bullet = findPeerProgram(options.bulletProgram, "bullet_ball");
  const std::string bulletTets = options.bulletTetsSeconds > 0.0 ? findPeerProgram("", "bullet_tets") : "";
  const bool stability = options.stabilityLevel >= 0, accuracy = options.accuracyLevel >= 0;
  const double perIntegrator = options.steps.size() + 1.0;
  const double units =
      2.0 * options.levels.size() + options.resolutions.size() + bulk.size() +
      (bullet.empty() ? 0.0 : options.levels.size()) + (bulletTets.empty() ? 0.0 : options.resolutions.size()) +
      (stability ? 13.0 * (bulk.size() * options.moduli.size() + (options.membrane ? membrane.size() * options.stiffnesses.size() : 0)) : 0.0) +
      (accuracy ? 5.0 + bulk.size() * perIntegrator + (options.membrane ? 5.0 + membrane.size() * perIntegrator : 0.0) : 0.0) + 1.0;
  BenchProgress progress("bench physics", units);
  json report = {{"bench", "physics"}, {"date", utcNow()}, {"cores", std::thread::hardware_concurrency()}, {"machine", machineJson()},
                 {"load_average_at_start", loadAverage()}, {"dt", base.sim.dt}, {"mass", base.slime.mass},
                 {"radius", base.slime.radius}, {"default_model", base.slime.model},
                 {"default_integrator", base.sim.integrator}, {"default_level", base.slime.level},
                 {"default_resolution", base.slime.resolution}, {"modulus", base.slime.modulus},
                 {"stiffness", base.slime.stiffness}, {"damping", base.slime.damping},
                 {"time_measure", "CPU time of the whole process (every thread) per simulated second; medians over "
                                  "repeats; the machine is shared, see load_average_*"}};

  // Cost: CPU ms per simulated second of the drop-and-grab, with the program's automatic substeps.
  CsvTable costTable{{"series", "source", "model", "integrator", "level", "resolution", "simulated_points",
                      "drawn_vertices", "substeps", "cpu_ms_per_simulated_s", "cpu_ms_min", "cpu_ms_max",
                      "wall_ms_per_simulated_s", "repeats"}, {}};
  json cost = json::array();
  std::map<std::tuple<std::string, std::string, int, int>, CostFigure> measured;
  const auto costRow = [&](const std::string& series, const std::string& model, const std::string& integrator,
                           int level, int resolution) {
    const auto key = std::make_tuple(model, integrator, level, model == "bulk" ? resolution : 0);
    if (!measured.count(key)) {
      Settings settings = physicsSettings(base, model, level, integrator, base.sim.dt);
      settings.slime.resolution = resolution;
      measured[key] = measureCost(settings, options.secondsPerMeasurement);
    }
    const CostFigure& f = measured[key];
    const json resolutionValue = model == "bulk" ? json(resolution) : json();
    cost.push_back({{"series", series}, {"source", "measured"}, {"model", model}, {"integrator", integrator},
                    {"level", level}, {"resolution", resolutionValue}, {"simulated_points", f.simulatedPoints},
                    {"drawn_vertices", f.drawnVertices}, {"substeps", f.substeps}, {"stable", f.stable},
                    {"cpu_ms_per_simulated_s", toJson(f.cpuMsPerSecond)},
                    {"wall_ms_per_simulated_s", f.wallMsPerSecond}, {"grab", true}});
    costTable.add({series, "measured", model, integrator, level, resolutionValue, f.simulatedPoints, f.drawnVertices,
                   f.substeps, f.cpuMsPerSecond.median, f.cpuMsPerSecond.min, f.cpuMsPerSecond.max, f.wallMsPerSecond,
                   f.cpuMsPerSecond.samples});
    std::printf("cost      %-8s %-17s level %d%s  %6zu points %6zu drawn  %2d substeps  %9.1f CPU ms per simulated s "
                "(%d runs, %.1f-%.1f)\n", model.c_str(), integrator.c_str(), level,
                model == "bulk" ? (" res " + std::to_string(resolution)).c_str() : "      ", f.simulatedPoints,
                f.drawnVertices, f.substeps, f.cpuMsPerSecond.median, f.cpuMsPerSecond.samples, f.cpuMsPerSecond.min,
                f.cpuMsPerSecond.max);
    progress.advance(1.0, series + " level " + std::to_string(level));
    return f.cpuMsPerSecond.median;
  };
  // The bulk body's integrator in the cost table: the program's, when the bulk body takes it.
  const std::string defaultIntegrator =
      bulkIntegrators({base.sim.integrator}).empty() ? "symplectic_euler" : base.sim.integrator;
  std::map<int, double> bulkByLevel;
  for (int level : options.levels)
    bulkByLevel[level] = costRow("bulk_level", "bulk", defaultIntegrator, level, base.slime.resolution);
  for (int resolution : options.resolutions)
    costRow("bulk_resolution", "bulk", defaultIntegrator, base.slime.level, resolution);
  for (const std::string& integrator : bulk)
    if (integrator != defaultIntegrator) costRow("bulk_integrator", "bulk", integrator, base.slime.level, base.slime.resolution);
  for (int level : options.levels) costRow("membrane", "membrane", "symplectic_euler", level, 0);
  if (!bullet.empty()) {
    for (int level : options.levels) {
      const json ball = runBulletBall(bullet, level, kScenarioSeconds);
      progress.advance(1.0, "bullet level " + std::to_string(level));
      if (ball.is_null()) continue;
      const double cpu = ball["cpu_ms_per_simulated_s"];
      cost.push_back({{"series", "bullet"}, {"source", "measured: peers/bullet_ball (process CPU, set-up included; "
                                                       "a drop, no grab)"}, {"model", "bullet btSoftBody"},
                      {"level", level}, {"simulated_points", ball["vertices"]}, {"drawn_vertices", ball["vertices"]},
                      {"cpu_ms_per_simulated_s", {{"median", cpu}, {"min", cpu}, {"max", cpu}, {"samples", 1}}},
                      {"wall_ms_per_simulated_s", ball["wall_ms_per_simulated_s"]}, {"grab", false}, {"run", ball}});
      costTable.add({"bullet", "measured", "bullet", "btSoftBody", level, json(), ball["vertices"], ball["vertices"], 1,
                     cpu, cpu, cpu, ball["wall_ms_per_simulated_s"], 1});
      std::printf("cost      bullet   btSoftBody        level %d        %6d points          1 ms steps  %9.1f CPU ms "
                  "per simulated s\n", level, ball["vertices"].get<int>(), cpu);
    }
  }
  for (int resolution : bulletTets.empty() ? std::vector<int>{} : options.resolutions) {
    const json body = runBulletTets(bulletTets, resolution, options.bulletTetsSeconds);
    progress.advance(1.0, "bullet tetrahedra resolution " + std::to_string(resolution));
    if (body.is_null()) continue;
    const double cpu = body["cpu_ms_per_simulated_s"];
    cost.push_back({{"series", "bullet_tets"}, {"source", "measured: peers/bullet_tets (its CPU time, set-up "
                                                            "excluded; a drop, no grab)"},
                    {"model", "bullet FEM"}, {"resolution", resolution}, {"simulated_points", body["nodes"]},
                    {"cpu_ms_per_simulated_s", {{"median", cpu}, {"min", cpu}, {"max", cpu}, {"samples", 1}}},
                    {"grab", false}, {"run", body}});
    costTable.add({"bullet_tets", "measured", "bullet", "FEM neo-Hookean explicit", json(), resolution, body["nodes"],
                   json(), json(), cpu, cpu, cpu, json(), 1});
    std::printf("cost      bullet   FEM on our tets   res %d          %6d points  %.3g ms steps  %9.1f CPU ms per "
                "simulated s  aspect %.3f  volume %.3f  inverted %d\n", resolution, body["nodes"].get<int>(),
                1e3 * body["step"].get<double>(), cpu, body["aspect"].get<double>(), body["volume_ratio"].get<double>(),
                body["inverted"].get<int>());
  }
  if (bulletTets.empty() && options.bulletTetsSeconds > 0.0)
    report["bullet_tets"] = "not measured: peers/bullet_tets is not built (Debian's libbullet-dev)";
  for (const JoltTetFigure& jolt : kJoltTets) {
    cost.push_back({{"series", "jolt_tets"}, {"source", "quoted: issue 27, Jolt (3b47ec39) on the same tetrahedra, "
                                                         "AMD EPYC family 23, one thread, not by this bench"},
                    {"model", "jolt tetrahedral soft body"}, {"resolution", jolt.resolution},
                    {"simulated_points", jolt.nodes}, {"iterations", jolt.iterations},
                    {"cpu_ms_per_simulated_s", {{"median", 1e3 * jolt.msPerMs}, {"min", 1e3 * jolt.msPerMs},
                                                {"max", 1e3 * jolt.msPerMs}, {"samples", 0}}}});
    costTable.add({"jolt_tets", "quoted", "jolt", "tetrahedral soft body", json(), jolt.resolution, jolt.nodes, json(),
                   json(), 1e3 * jolt.msPerMs, 1e3 * jolt.msPerMs, 1e3 * jolt.msPerMs, json(), 0});
  }
  for (const QuotedFigure& jolt : kJolt) {
    const double low = 1e3 * jolt.low, high = 1e3 * jolt.high, middle = 0.5 * (low + high);
    cost.push_back({{"series", "jolt"}, {"source", "quoted: SPEC §9 and issue 14, Jolt soft body measured "
                                                   "2026-11-23, not by this bench"}, {"model", "jolt soft body"},
                    {"level", jolt.level}, {"simulated_points", jolt.vertices}, {"drawn_vertices", jolt.vertices},
                    {"cpu_ms_per_simulated_s", {{"median", middle}, {"min", low}, {"max", high}, {"samples", 0}}}});
    costTable.add({"jolt", "quoted", "jolt", "soft body", jolt.level, json(), jolt.vertices, jolt.vertices, json(),
                   middle, low, high, json(), 0});
  }
  report["cost"] = cost;
  if (bulkByLevel.count(4)) {
    json aims = {{"level4_cpu_s_per_simulated_s", 1e-3 * bulkByLevel[4]}, {"level4_aim", 0.25},
                 {"level4_met", 1e-3 * bulkByLevel[4] <= 0.25}};
    if (bulkByLevel.count(6)) {
      const double ratio = bulkByLevel[6] / bulkByLevel[4];
      aims["level6_over_level4"] = ratio;
      aims["level6_aim"] = 1.5;
      aims["level6_met"] = ratio <= 1.5;
    }
    report["aims"] = aims;
  }
  if (bullet.empty()) report["bullet"] = "not measured: peers/bullet_ball is not built (Debian's libbullet-dev)";

  // Stability maps: the bulk body's against its modulus, the membrane's against spring stiffness.
  CsvTable stabilityTable{{"series", "model", "integrator", "parameter", "largest_stable_dt", "bounded", "predicted_dt",
                           "omega_max", "estimate_dt"}, {}};
  if (stability) {
    json bulkMap = json::array(), membraneMap = json::array();
    for (const std::string& integrator : bulk) {
      for (double modulus : options.moduli) {
        Settings settings = physicsSettings(base, "bulk", options.stabilityLevel, integrator, base.sim.dt);
        settings.slime.modulus = modulus;
        bulkMap.push_back(stabilityPoint(settings, "bulk", modulus, progress, stabilityTable));
      }
    }
    if (options.membrane) {
      for (const std::string& integrator : membrane) {
        for (double stiffness : options.stiffnesses) {
          Settings settings = physicsSettings(base, "membrane", options.stabilityLevel, integrator, base.sim.dt);
          settings.slime.stiffness = stiffness;
          membraneMap.push_back(stabilityPoint(settings, "membrane", stiffness, progress, stabilityTable));
        }
      }
    }
    report["stability"] = {
        {"level", options.stabilityLevel}, {"resolution", base.slime.resolution}, {"steps", kStabilitySteps},
        {"bulk", bulkMap}, {"membrane", membraneMap},
        {"criterion", "ball started 1 mm into the floor, 400 steps of exactly dt (one substep, automatic substeps "
                      "off): blown up if the divergence guard fires (NaN/inf, speed > 50 m/s), kinetic energy > 1 J, "
                      "or volume outside [0.5, 2] V0"},
        {"predicted", "Simulation::largestStableStep(): 2/omega_max (symplectic Euler, dampers exact), "
                      "4/(c + sqrt(c^2 + 4 omega_max^2)) (explicit Euler), 2.78/(omega_max + c) (RK4); omega_max "
                      "by power iteration, c the dampers' Gershgorin rate"}};
  }

  // Accuracy against cost: the drop-and-grab against a small-step RK4 reference.
  CsvTable accuracyTable{{"series", "model", "integrator", "h", "dt", "substeps", "automatic", "stable", "rms_error_mm",
                          "max_error_mm", "cpu_s_per_simulated_s", "wall_s_per_simulated_s", "rms_error_mm_before_grab"}, {}};
  if (accuracy) {
    json models = json::object();
    if (!bulk.empty()) models["bulk"] = accuracyForModel(base, "bulk", bulk, options, progress, accuracyTable);
    if (options.membrane)
      models["membrane"] = accuracyForModel(base, "membrane", membrane, options, progress, accuracyTable);
    // Does the accuracy-for-cost chart keep the bulk body's default integrator?
    if (models.contains("bulk")) {
      json& bulkAccuracy = models["bulk"];
      json defaultRun = nullptr;
      for (const json& run : bulkAccuracy["runs"])
        if (run["integrator"] == defaultIntegrator && run["automatic"].get<bool>() && run.contains("rms_error_mm"))
          defaultRun = run;
      json verdict = {{"default", defaultIntegrator}};
      if (!defaultRun.is_null()) {
        const double error = defaultRun["rms_error_mm"];
        const json atDefault = cheapestForAccuracy(bulkAccuracy["runs"], {error * (1.0 + 1e-9)}, true)[0];
        const json anyRun = cheapestForAccuracy(bulkAccuracy["runs"], {error * (1.0 + 1e-9)}, false)[0];
        verdict["cheapest_at_the_default_accuracy_any_stable_run"] = anyRun["cheapest"];
        verdict["default_rms_error_mm"] = error;
        verdict["default_cpu_s_per_simulated_s"] = defaultRun["cpu_s_per_simulated_s"];
        verdict["cheapest_at_the_default_accuracy"] = atDefault["cheapest"];
        std::map<std::string, int> wins;
        for (const json& choice : bulkAccuracy["choice"])
          if (!choice["cheapest"].is_null()) ++wins[choice["cheapest"]["integrator"].get<std::string>()];
        verdict["wins_over_targets"] = wins;
        const std::string cheapest = atDefault["cheapest"].is_null() ? "" : atDefault["cheapest"]["integrator"].get<std::string>();
        verdict["outcome"] = cheapest == defaultIntegrator ? "confirmed" : "overturned";
        const std::string anyCheapest = anyRun["cheapest"].is_null() ? "" : anyRun["cheapest"]["integrator"].get<std::string>();
        std::printf("accuracy  bulk     the default (%s, automatic substeps) has %.4f mm RMS error at %.3f CPU s per "
                    "simulated s; cheapest for that accuracy within the predicted limits: %s → %s (among every stable "
                    "run: %s)\n", defaultIntegrator.c_str(), error, defaultRun["cpu_s_per_simulated_s"].get<double>(),
                    cheapest.c_str(), verdict["outcome"].get<std::string>().c_str(), anyCheapest.c_str());
      }
      bulkAccuracy["default_integrator"] = verdict;
    }
    report["accuracy"] = models;
  }

  // Roundness at rest of the default ball.
  if (options.settleSeconds > 0.0) {
    const Settings settings = physicsSettings(base, base.slime.model, base.slime.level, base.sim.integrator, base.sim.dt);
    report["rest"] = roundnessAtRest(settings, options.settleSeconds);
    std::printf("rest      %-8s %-17s level %d  %.1f CPU ms per simulated s  aspect %.3f  radius spread %.4f  volume %.4f\n",
                base.slime.model.c_str(), base.sim.integrator.c_str(), base.slime.level,
                report["rest"]["cpu_ms_per_simulated_s"].get<double>(), report["rest"]["aspect"].get<double>(),
                report["rest"]["radius_spread"].get<double>(), report["rest"]["volume_ratio"].get<double>());
  }
  progress.finish();
  report["load_average_at_end"] = loadAverage();

  if (!options.jsonFile.empty()) writeJsonFile(report, options.jsonFile);
  if (!options.csvFile.empty()) {
    writeCsvFile(costTable, options.csvFile);
    writeCsvFile(stabilityTable, siblingCsvPath(options.csvFile, "stability"));
    writeCsvFile(accuracyTable, siblingCsvPath(options.csvFile, "accuracy"));
  }
  return report;
}

}  // namespace slime
