#include "app/bench/physics/bench_front.h"

#include "app/bench/material/bench_damping.h"
#include "app/bench/material/bench_material.h"
#include "app/bench/physics/bench_front_report.h"
#include "app/bench/physics/bench_peers.h"
#include "app/bench/report/bench_report.h"
#include "app/bench/report/bench_timing.h"
#include "core/bulk/bulk_body.h"
#include "core/bulk/lamb_sphere.h"
#include "core/integrators/integrators.h"
#include "core/settings/setting_info.h"
#include "core/simulation/simulation.h"

#include <glm/geometric.hpp>
#include <tbb/task_arena.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>
#include <thread>

namespace slime {
namespace {

using nlohmann::json;

// m: a node this low has landed (projective holds its nodes on the drawn surface's floor, a little above 0)
constexpr double kLandedHeight = 2e-3;
// Of the rest height: below it the floor holds the body up, directly or through the drawn surface's
// points that ride on the elements there, so the static residual takes only the horizontal part there.
constexpr double kSupportedShare = 0.25;
constexpr double kStaticChunk = 0.25;         // s: the static solve runs until a chunk changes its height
constexpr double kStaticConverged = 1e-5;     // by less than this share
constexpr double kRestWindow = 0.3;         // of the rest run, its last part averaged

double threadCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

double topHeight(const Simulation& simulation) {
  double top = -std::numeric_limits<double>::infinity();
  for (const glm::dvec3& x : simulation.state().positions) top = std::max(top, x.z);
  return top;
}

double lowestHeight(const Simulation& simulation) {
  double low = std::numeric_limits<double>::infinity();
  for (const glm::dvec3& x : simulation.state().positions) low = std::min(low, x.z);
  return low;
}

Settings pointSettings(const Settings& base, const FrontPoint& point) {
  Settings settings = base;
  settings.slime.model = "bulk";
  settings.slime.resolution = point.resolution;
  settings.sim.integrator = point.integrator;
  settings.sim.substeps = 1;
  settings.sim.dt = point.stepMs > 0.0 ? 1e-3 * point.stepMs : base.sim.dt;
  if (point.iterations > 0) settings.sim.iterations = point.iterations;
  return settings;
}

// The rest-height scene: the ball purely elastic on a frictionless floor that does not stick, so its
// equilibrium does not depend on how it landed.
Settings restSettings(Settings settings) {
  settings.slime.longTerm = 1.0;
  settings.slime.friction = 0.0;
  settings.slime.adhesion = 0.0;
  settings.slime.plastic = false;
  settings.slime.tearing = false;
  return settings;
}

// ---- The runs of one point -------------------------------------------------------------------------

// The scene's slime dropped from its start: thread CPU time per simulated time, rollbacks, the mean step.
json dropRun(const Settings& settings, bool automatic, double seconds) {
  Simulation simulation(settings);
  simulation.setAutomaticSubsteps(automatic);
  double landed = -1.0;
  long substeps = 0, steps = 0;
  const double start = threadCpuSeconds();
  while (simulation.time() < seconds - 0.5 * settings.sim.dt) {
    simulation.step();
    substeps += simulation.substepsPerStep();
    ++steps;
    if (!automatic && !simulation.divergences().empty()) break;
    if (landed < 0.0 && lowestHeight(simulation) <= kLandedHeight) landed = simulation.time();
  }
  const double cpu = threadCpuSeconds() - start;
  const double simulated = simulation.time();
  return {{"cpu_s", cpu}, {"simulated_s", simulated},
          {"cost_ms_per_ms", simulated > 0.0 ? json(cpu / simulated) : json()},
          {"landed_s", landed >= 0.0 ? json(landed) : json()},
          {"contact_s", landed >= 0.0 ? json(simulated - landed) : json()},
          {"mean_step_ms", steps > 0 ? json(1e3 * settings.sim.dt * steps / substeps) : json()},
          {"rollbacks", simulation.divergences().size()},
          {"first_rollback", simulation.divergences().empty() ? json() : json(simulation.divergences()[0].what)}};
}

// The elastic ball set down touching the frictionless floor (the scene's dampers: the oracle does not
// change the step's stability): its top node's height averaged over the run's last kRestWindow (the
// bounce's remains average out).
json restRun(const Settings& settings, bool automatic, double seconds) {
  Settings rest = restSettings(settings);
  rest.slime.position.z = rest.slime.radius;
  Simulation simulation(rest);
  simulation.setAutomaticSubsteps(automatic);
  double sum = 0.0;
  int samples = 0;
  const double from = (1.0 - kRestWindow) * seconds;
  while (simulation.time() < seconds - 0.5 * settings.sim.dt) {
    simulation.step();
    if (!automatic && !simulation.divergences().empty()) break;
    if (simulation.time() >= from) {
      sum += topHeight(simulation);
      ++samples;
    }
  }
  const bool clean = simulation.divergences().empty() || automatic;
  return {{"rest_height_m", clean && samples > 0 ? json(sum / samples) : json()},
          {"simulated_s", simulation.time()}, {"rollbacks", simulation.divergences().size()}};
}

json modeRun(const Settings& settings, bool automatic, bool spheroidal, const FrontOptions& options) {
  return measureModeDamping(settings, spheroidal, options.modePeriods, options.modeSpeed, automatic);
}

json creepRun(const Settings& settings, bool automatic, const FrontOptions& options) {
  MaterialBenchOptions creep;
  creep.settleSeconds = options.creepSettleSeconds;
  creep.creepSeconds = options.creepSeconds;
  creep.recovery = false;
  creep.settleViscosity = settings.slime.viscosity;  // the scene's: the oracle does not change the step's stability
  creep.automaticSubsteps = automatic;
  CsvTable series;
  return measureCreep(settings, creep, series)["creep"];
}

double relativeError(double measured, double truth) { return std::abs(measured / truth - 1.0); }

// Every run of one point, and its errors.
json measurePoint(const Settings& base, const FrontPoint& point, const FrontOptions& options,
                  const std::map<int, json>& statics) {
  const Settings settings = pointSettings(base, point);
  const bool automatic = point.stepMs <= 0.0;
  const double cpuStart = threadCpuSeconds();
  json result = {{"integrator", point.integrator},
                 {"step_ms", automatic ? json("auto") : json(point.stepMs)},
                 {"iterations", point.iterations > 0 ? json(point.iterations) : json()},
                 {"resolution", point.resolution}};
  const json drop = dropRun(settings, automatic, options.dropSeconds);
  result["drop"] = drop;
  result["cost_ms_per_ms"] = drop["cost_ms_per_ms"];
  std::size_t rollbacks = drop["rollbacks"].get<std::size_t>();
  json errors = {{"torsional", nullptr}, {"spheroidal", nullptr}, {"damping", nullptr}, {"creep", nullptr},
                 {"rest_height", nullptr}};
  if (!automatic && rollbacks > 0) {
    result["stable"] = false;
    result["rollbacks"] = rollbacks;
    result["errors"] = errors;
    result["note"] = "unstable at this step: the divergence guard rolled back the drop (" +
                     drop["first_rollback"].get<std::string>() + ")";
    result["cpu_s_all_runs"] = threadCpuSeconds() - cpuStart;
    return result;
  }
  const json torsional = modeRun(settings, automatic, false, options);
  const json spheroidal = modeRun(settings, automatic, true, options);
  const json rest = restRun(settings, automatic, options.restSeconds);
  const json creep = creepRun(settings, automatic, options);
  result["modes"] = {{"torsional", torsional}, {"spheroidal", spheroidal}};
  result["rest"] = rest;
  result["creep"] = creep;
  bool clean = true;
  for (const json* run : {&torsional, &spheroidal, &rest, &creep}) {
    const std::size_t count = (*run)["rollbacks"].get<std::size_t>();
    rollbacks += count;
    if (!automatic && count > 0) clean = false;
  }
  const auto modeError = [&](const json& mode) -> json {
    if (!automatic && mode["rollbacks"].get<std::size_t>() > 0) return nullptr;
    // A mode that no longer swings (fewer than three zero crossings) is measured at 0 Hz: error 1.
    const double measured = mode["measured_hz"];
    return relativeError(std::max(measured, 0.0), mode["theory_hz"]);
  };
  errors["torsional"] = modeError(torsional);
  errors["spheroidal"] = modeError(spheroidal);
  if (automatic || (torsional["rollbacks"] == 0 && spheroidal["rollbacks"] == 0))
    errors["damping"] = std::max(std::abs(torsional["damping_ratio"].get<double>()),
                                 std::abs(spheroidal["damping_ratio"].get<double>()));
  if (automatic || creep["rollbacks"] == 0) errors["creep"] = std::abs(creep["error"].get<double>());
  const auto oracle = statics.find(point.resolution);
  if (!rest["rest_height_m"].is_null() && oracle != statics.end())
    errors["rest_height"] = relativeError(rest["rest_height_m"], oracle->second["rest_height_m"]);
  result["errors"] = errors;
  result["damping_ratio"] = {{"torsional", torsional["damping_ratio"]}, {"spheroidal", spheroidal["damping_ratio"]}};
  result["rollbacks"] = rollbacks;
  result["stable"] = clean;
  if (!clean) result["note"] = "unstable at this step: a rollback in an oracle's run (its error left out)";
  result["guide"] = meetsGuideAccuracy(errors) && clean;
  result["cpu_s_all_runs"] = threadCpuSeconds() - cpuStart;
  return result;
}

// ---- The static solve ------------------------------------------------------------------------------

// The residual of the static equations at the state: internal forces (no dampers) + weight + the
// volume constraint's pressure λ ∇V (λ by least squares), over every node off the floor and the
// horizontal part of those on it (the floor is frictionless); its RMS over the total weight.
json staticResidual(const Simulation& simulation) {
  const BulkBody& body = simulation.bulkBody();
  const std::vector<glm::dvec3>& x = simulation.state().positions;
  const std::vector<glm::dvec3> still(x.size(), glm::dvec3(0.0));
  std::vector<glm::dvec3> force;
  bulkInternalForces(body, x, still, force, false);
  std::vector<glm::dvec3> gradient(x.size(), glm::dvec3(0.0));  // ∇V: Σ over surface triangles of x_b × x_c / 6
  for (const Triangle& t : body.mesh.surface) {
    gradient[t[0]] += glm::cross(x[t[1]], x[t[2]]) / 6.0;
    gradient[t[1]] += glm::cross(x[t[2]], x[t[0]]) / 6.0;
    gradient[t[2]] += glm::cross(x[t[0]], x[t[1]]) / 6.0;
  }
  const double g = simulation.settings().sim.gravity;
  const double supported = kSupportedShare * topHeight(simulation);
  const auto freePart = [&](std::size_t i, glm::dvec3 v) {
    if (x[i].z <= supported) v.z = 0.0;
    return v;
  };
  double rg = 0.0, gg = 0.0, weight = 0.0;
  std::vector<glm::dvec3> residual(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double mass = 1.0 / body.freeInverseMasses[i];
    weight += mass * g;
    residual[i] = freePart(i, force[i] + glm::dvec3(0.0, 0.0, -mass * g));
    const glm::dvec3 n = freePart(i, gradient[i]);
    rg += glm::dot(residual[i], n);
    gg += glm::dot(n, n);
  }
  const double pressure = gg > 0.0 ? -rg / gg : 0.0;
  double sum = 0.0, largest = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const glm::dvec3 r = residual[i] + pressure * freePart(i, gradient[i]);
    sum += glm::dot(r, r);
    largest = std::max(largest, glm::length(r));
  }
  return {{"rms_residual_over_weight", std::sqrt(sum) / weight}, {"largest_node_residual_n", largest},
          {"weight_n", weight}, {"pressure_pa", pressure}, {"kinetic_energy_j", simulation.metrics().kineticEnergy}};
}

// The converged static solve of the rest-height scene at one resolution, by dynamic relaxation with
// kinetic damping (Cundall 1971; Topping & Khan 1996): symplectic_euler at its automatic substeps (the
// program's step cut to its stability limit), every velocity zeroed each time the kinetic energy passes
// a peak, so the body comes to rest at the static equilibrium of the same forces and floor. It runs in
// chunks of kStaticChunk until one changes the top node's height by less than kStaticConverged of it
// (or `seconds` have passed): that height, the last chunk's change and the force residual.
json staticSolve(const Settings& base, int resolution, double seconds) {
  FrontPoint point{"symplectic_euler", 0.0, 0, resolution};
  const Settings settings = restSettings(pointSettings(base, point));
  Simulation simulation(settings);
  const std::vector<glm::dvec3> still(simulation.state().size(), glm::dvec3(0.0));
  double previous = topHeight(simulation), change = 1.0, kinetic = 0.0;
  int resets = 0;
  const double start = threadCpuSeconds();
  while (simulation.time() < seconds - 0.5 * settings.sim.dt && change >= kStaticConverged) {
    const double end = simulation.time() + kStaticChunk;
    while (simulation.time() < end - 0.5 * settings.sim.dt) {
      simulation.step();
      const double now = simulation.metrics().kineticEnergy;
      if (now < kinetic && lowestHeight(simulation) <= kLandedHeight) {  // past a peak, once on the floor
        simulation.setVelocities(still);
        ++resets;
        kinetic = 0.0;
      } else {
        kinetic = now;
      }
    }
    const double height = topHeight(simulation);
    change = std::abs(height / previous - 1.0);
    previous = height;
  }
  return {{"resolution", resolution}, {"rest_height_m", previous}, {"change_over_the_last_chunk", change},
          {"chunk_s", kStaticChunk}, {"converged", change < kStaticConverged}, {"simulated_s", simulation.time()},
          {"kinetic_damping_resets", resets}, {"substeps", simulation.substepsPerStep()},
          {"rollbacks", simulation.divergences().size()}, {"cpu_s", threadCpuSeconds() - start},
          {"residual", staticResidual(simulation)}};
}

// ---- Integrators from the settings table -----------------------------------------------------------

// A small free ball started in the spheroidal mode, stepped a few times: its final positions.
std::vector<glm::dvec3> probeSteps(const Settings& base, const std::string& integrator, int iterations) {
  Settings settings = base;
  settings.slime.model = "bulk";
  settings.slime.resolution = 1;
  settings.slime.level = 2;
  settings.sim.integrator = integrator;
  settings.sim.dt = 0.002;
  settings.sim.substeps = 1;
  settings.sim.iterations = iterations;
  settings.sim.gravity = 0.0;
  settings.slime.position.z = 2.0 * settings.slime.radius;
  Simulation simulation(settings);
  simulation.setAutomaticSubsteps(false);
  const double eta = lambRoot(2, true, settings.slime.poisson);
  std::vector<glm::dvec3> velocities = simulation.state().velocities;
  const std::vector<glm::dvec3>& rest = simulation.bulkBody().mesh.positions;
  for (std::size_t i = 0; i < velocities.size(); ++i)
    velocities[i] = 0.05 * spheroidalModeShape(rest[i] - settings.slime.position, settings.slime.radius, eta,
                                               settings.slime.poisson);
  simulation.setVelocities(velocities);
  for (int k = 0; k < 5; ++k) simulation.step();
  return simulation.state().positions;
}

std::vector<std::string> integratorChoices(const Settings& settings) {
  for (const SettingInfo& info : describeSettings(settings))
    if (info.key == "sim.integrator") return info.choices;
  return integratorNames();
}

// ---- Peers -----------------------------------------------------------------------------------------

std::string joined(const std::vector<int>& values) {
  std::string text;
  for (int v : values) {
    if (!text.empty()) text += ',';
    text += std::to_string(v);
  }
  return text;
}

std::string joined(const std::vector<double>& values) {
  std::string text;
  for (double v : values) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", v);
    if (!text.empty()) text += ',';
    text += buffer;
  }
  return text;
}

json runPeers(const FrontOptions& options, const std::map<int, json>& statics) {
  json peers = json::array();
  std::vector<std::string> programs = options.peerPrograms;
  const bool configured = !programs.empty();
  if (!configured) programs = {"jolt_tets", "bullet_tets"};
  for (const std::string& name : programs) {
    const std::string program = configured ? (access(name.c_str(), X_OK) == 0 ? name : "") : findPeerProgram("", name);
    const std::string label = std::filesystem::path(name).filename().string();
    if (program.empty()) {
      peers.push_back({{"program", label}, {"status", "not built"}});
      std::printf("front     peer %-12s not built\n", label.c_str());
      continue;
    }
    std::printf("front     peer %-12s running (%s)\n", label.c_str(), program.c_str());
    std::fflush(stdout);
    // Each peer's stiffness is fitted to the same static sag its rest height is then measured against:
    // our static solve's at each resolution.
    std::vector<std::string> arguments = {"--front", "--resolutions", joined(options.resolutions), "--steps-ms",
                                          joined(options.stepsMs), "--iterations", joined(options.iterations),
                                          "--seconds", std::to_string(options.peerSeconds)};
    std::vector<double> targets;
    for (int resolution : options.resolutions) {
      const auto oracle = statics.find(resolution);
      if (oracle != statics.end() && oracle->second["rest_height_m"].is_number())
        targets.push_back(oracle->second["rest_height_m"].get<double>());
    }
    if (targets.size() == options.resolutions.size()) {
      arguments.push_back("--target-rest-height");
      arguments.push_back(joined(targets));
    }
    const json report = runPeerFront(program, arguments);
    if (!report.is_object() || !report.contains("points")) {
      peers.push_back({{"program", label}, {"status", "failed: no front points written"}});
      std::printf("front     peer %-12s failed: no front points written\n", label.c_str());
      continue;
    }
    json points = json::array();
    for (const json& point : report["points"]) {
      const int resolution = point.value("resolution", 0);
      const auto oracle = statics.find(resolution);
      points.push_back(peerPointErrors(point, oracle != statics.end() ? oracle->second["rest_height_m"].get<double>() : 0.0));
    }
    peers.push_back({{"program", label}, {"status", "measured"}, {"peer", report.value("peer", label)},
                     {"processor", report.value("processor", "")}, {"points", points}});
  }
  return peers;
}

// ---- Running many points on a few threads ----------------------------------------------------------

// Runs task(k) for k in [0, count) on `jobs` threads, each task alone in a one-thread arena (its thread's
// CPU time is all its work).
template <typename Task>
void runOnThreads(std::size_t count, int jobs, Task task) {
  std::atomic<std::size_t> next{0};
  const auto worker = [&] {
    tbb::task_arena arena(1);
    for (std::size_t k = next++; k < count; k = next++) arena.execute([&] { task(k); });
  };
  std::vector<std::thread> threads;
  for (int j = 0; j < std::max(1, jobs); ++j) threads.emplace_back(worker);
  for (std::thread& thread : threads) thread.join();
}

std::vector<FrontPoint> gridPoints(const FrontOptions& options, const json& integrators, const Settings& base) {
  if (!options.points.empty()) return options.points;
  std::vector<FrontPoint> points;
  const std::vector<std::string> iterating = integrators["iterating"];
  for (int resolution : options.resolutions)
    for (const std::string& integrator : integrators["bulk"].get<std::vector<std::string>>()) {
      if (!options.integrators.empty() &&
          std::find(options.integrators.begin(), options.integrators.end(), integrator) == options.integrators.end())
        continue;
      const bool iterates = std::find(iterating.begin(), iterating.end(), integrator) != iterating.end();
      std::vector<int> counts = iterates ? options.iterations : std::vector<int>{0};
      std::vector<double> steps = options.stepsMs;
      // The program's automatic substeps, for a method with a stability limit (the explicit ones).
      Settings probeSettings = pointSettings(base, {integrator, 0.0, 0, 1});
      probeSettings.slime.level = 2;
      if (std::isfinite(Simulation(probeSettings).largestStableStep())) steps.push_back(0.0);
      for (double step : steps)
        for (int count : counts) points.push_back({integrator, step, count, resolution});
    }
  // The costliest first, so that the two threads finish together.
  std::stable_sort(points.begin(), points.end(),
                   [](const FrontPoint& a, const FrontPoint& b) { return a.resolution > b.resolution; });
  return points;
}

}  // namespace

FrontOptions FrontOptions::quick() {
  FrontOptions options;
  options.resolutions = {2};
  options.points = {{"symplectic_euler", 1.0, 0, 2}, {"projective", 16.7, 4, 2}};
  options.dropSeconds = 0.45;
  options.restSeconds = 0.6;
  options.modePeriods = 4.0;
  options.creepSettleSeconds = 0.3;
  options.creepSeconds = 1.5;
  options.staticSeconds = 4.0;
  options.peerSeconds = 0.5;
  return options;
}

json bulkFrontIntegrators(const Settings& settings) {
  json bulk = json::array(), iterating = json::array(), notBulk = json::array();
  const std::vector<glm::dvec3> reference = probeSteps(settings, "symplectic_euler", 1);
  for (const std::string& name : integratorChoices(settings)) {
    if (name == "auto") continue;
    const std::vector<glm::dvec3> once = probeSteps(settings, name, 1);
    if (name != "symplectic_euler" && once == reference) {
      notBulk.push_back(name);
      continue;
    }
    bulk.push_back(name);
    if (probeSteps(settings, name, 2) != once) iterating.push_back(name);
  }
  return {{"bulk", bulk}, {"iterating", iterating}, {"not_bulk", notBulk},
          {"how", "a free resolution-1 ball in Lamb's spheroidal mode, 5 steps of 2 ms: a method that leaves it "
                  "exactly where symplectic_euler does is not a bulk method (the bulk body steps it as "
                  "symplectic_euler); one whose result changes with sim.iterations iterates"}};
}

std::vector<std::size_t> paretoFront(const std::vector<std::pair<double, double>>& errorAndCost) {
  std::vector<std::size_t> order(errorAndCost.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return errorAndCost[a].second != errorAndCost[b].second ? errorAndCost[a].second < errorAndCost[b].second
                                                            : errorAndCost[a].first < errorAndCost[b].first;
  });
  std::vector<std::size_t> front;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t k : order)
    if (errorAndCost[k].first < best) {
      front.push_back(k);
      best = errorAndCost[k].first;
    }
  return front;
}

json peerPointErrors(const json& point, double staticRestHeight) {
  json result = point;
  const auto number = [&](const char* key) { return point.contains(key) && point[key].is_number() ? point[key].get<double>() : -1.0; };
  const double modulus = number("shear_modulus_pa"), density = number("density_kg_m3"), radius = number("radius_m");
  const double poisson = std::max(0.0, number("poisson"));
  json errors = {{"torsional", nullptr}, {"spheroidal", nullptr}, {"damping", nullptr}, {"creep", nullptr},
                 {"rest_height", nullptr}};
  const bool diverged = point.value("diverged", false);
  if (!diverged && modulus > 0.0 && density > 0.0 && radius > 0.0) {
    const double shearSpeed = std::sqrt(modulus / density);
    for (const bool spheroidal : {false, true}) {
      const char* key = spheroidal ? "spheroidal_hz" : "torsional_hz";
      const double theory = lambRoot(2, spheroidal, poisson) * shearSpeed / (2.0 * std::numbers::pi * radius);
      result[spheroidal ? "spheroidal_theory_hz" : "torsional_theory_hz"] = theory;
      if (number(key) > 0.0) errors[spheroidal ? "spheroidal" : "torsional"] = relativeError(number(key), theory);
    }
  }
  if (!diverged && point.contains("damping_ratio") && point["damping_ratio"].is_number())
    errors["damping"] = std::abs(point["damping_ratio"].get<double>());
  if (!diverged && number("rest_height_m") > 0.0 && staticRestHeight > 0.0) {
    errors["rest_height"] = relativeError(number("rest_height_m"), staticRestHeight);
    result["static_rest_height_m"] = staticRestHeight;
  }
  result["errors"] = errors;
  result["stable"] = !diverged;
  result["guide"] = !diverged && meetsGuideAccuracy(errors);
  return result;
}

bool meetsGuideAccuracy(const json& errors) {
  const auto within = [&](const char* key, double bound) {
    return errors.contains(key) && errors[key].is_number() && errors[key].get<double>() <= bound;
  };
  return within("torsional", 0.05) && within("spheroidal", 0.05) && within("damping", 0.02) &&
         within("rest_height", 0.02);
}

json runFront(const Settings& base, const FrontOptions& options) {
  const Stopwatch watch;
  json report = {{"bench", "physics front"}, {"date", utcNow()}, {"machine", machineJson()},
                 {"jobs", options.jobs}};
  const json integrators = bulkFrontIntegrators(base);
  report["integrators"] = integrators;
  std::printf("front     bulk integrators: %s (iterating: %s; not bulk methods: %s)\n", integrators["bulk"].dump().c_str(),
              integrators["iterating"].dump().c_str(), integrators["not_bulk"].dump().c_str());
  std::vector<int> resolutions = options.resolutions;
  for (const FrontPoint& point : options.points)
    if (std::find(resolutions.begin(), resolutions.end(), point.resolution) == resolutions.end())
      resolutions.push_back(point.resolution);
  const std::vector<FrontPoint> points = gridPoints(options, integrators, base);
  std::printf("front     %zu points at resolutions %s on %d threads\n", points.size(), joined(resolutions).c_str(),
              options.jobs);
  std::fflush(stdout);

  // The static solves, one per resolution, then every point.
  std::mutex print;
  std::vector<json> staticList(resolutions.size());
  runOnThreads(resolutions.size(), options.jobs, [&](std::size_t k) {
    staticList[k] = staticSolve(base, resolutions[k], options.staticSeconds);
    const std::lock_guard<std::mutex> lock(print);
    std::printf("front     static solve res %d: rest height %.5f m after %.2f s (the last %.2f s changed it by %.1e), "
                "residual %.2e of the weight, %.1f CPU s\n", resolutions[k], staticList[k]["rest_height_m"].get<double>(),
                staticList[k]["simulated_s"].get<double>(), kStaticChunk,
                staticList[k]["change_over_the_last_chunk"].get<double>(),
                staticList[k]["residual"]["rms_residual_over_weight"].get<double>(), staticList[k]["cpu_s"].get<double>());
    std::fflush(stdout);
  });
  std::map<int, json> statics;
  for (std::size_t k = 0; k < resolutions.size(); ++k) statics[resolutions[k]] = staticList[k];

  std::vector<json> results(points.size());
  std::atomic<std::size_t> done{0};
  runOnThreads(points.size(), options.jobs, [&](std::size_t k) {
    results[k] = measurePoint(base, points[k], options, statics);
    const std::lock_guard<std::mutex> lock(print);
    std::printf("front     [%3zu/%zu] %s\n", ++done, points.size(), frontRowText(results[k]).c_str());
    std::fflush(stdout);
  });
  json ours = json::array();
  for (json& result : results) ours.push_back(std::move(result));
  report["points"] = ours;
  json staticJson = json::array();
  for (const json& solve : staticList) staticJson.push_back(solve);
  report["static_solves"] = staticJson;
  report["peers"] = runPeers(options, statics);
  report["guide"] = guideSummary(ours, base);
  report["durations"] = {{"drop_s", options.dropSeconds}, {"rest_s", options.restSeconds},
                         {"mode_periods", options.modePeriods}, {"creep_settle_s", options.creepSettleSeconds},
                         {"creep_s", options.creepSeconds}, {"static_s_at_most", options.staticSeconds},
                         {"peer_s", options.peerSeconds}};
  report["wall_s"] = 1e-3 * watch.milliseconds();
  report["load_average_at_end"] = loadAverage();
  printGuide(report["guide"]);
  report["peer_dominance"] = peerDominance(ours, report["peers"]);
  printPeerDominance(report["peer_dominance"]);
  if (!options.outputDirectory.empty()) writeFrontFiles(report, options.outputDirectory);
  std::printf("front     %zu points in %.0f s wall\n", points.size(), report["wall_s"].get<double>());
  return report;
}

}  // namespace slime
