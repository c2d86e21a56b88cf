// `slime sim`: run the physics headless for a number of simulated seconds, print a one-line summary
// and optionally write a JSON report. The same inputs give a bitwise identical report, apart from the
// timing fields (ms_per_step, wall_seconds).
#include "app/cli/commands.h"
#include "core/export/mesh_exporter.h"
#include "core/settings/file_output.h"
#include "core/integrators/integrators.h"
#include "core/simulation/scenario.h"
#include "core/settings/settings_io.h"
#include "core/simulation/simulation.h"
#include "core/geometry/strand_profile.h"

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <optional>

namespace slime {
namespace {

using nlohmann::json;

constexpr double kMaxSeconds = 3600.0;    // simulated seconds a run may ask for
constexpr double kSeriesInterval = 0.01;  // s between series samples
constexpr std::size_t kMaxRollbacks = 20; // give up after this many divergences

struct SimOptions {
  SceneOptions scene;
  double seconds = 3.0;
  std::string reportFile;
  std::string exportMesh;     // --export-mesh PATTERN (core/export/mesh_exporter.h)
  double exportEvery = -1.0;  // --export-every S, s of simulated time
  std::string objUp;          // --obj-up y|z: an .obj's axes (empty: y, OBJ's convention)
};

void checkSeconds(double seconds) {
  if (!std::isfinite(seconds) || seconds <= 0.0 || seconds > kMaxSeconds) {
    char text[160];
    std::snprintf(text, sizeof text, "--seconds: %g is not allowed; expected a number greater than 0 and at most %g (s)",
                  seconds, kMaxSeconds);
    throw SettingsError(text);
  }
}

glm::dvec3 centroid(const std::vector<glm::dvec3>& positions) {
  glm::dvec3 sum(0.0);
  for (const glm::dvec3& p : positions) sum += p;
  return sum / static_cast<double>(positions.size());
}

// The figures of the simulated bodies alone, as SlimeMetrics gives them: the summed volume over the
// summed rest volume, and the fastest point.
struct BodyFigures {
  double volumeRatio = 0.0, maxSpeed = 0.0;
};

BodyFigures bodyFiguresOf(const Simulation& simulation) {
  double volume = 0.0, rest = 0.0, fastest = 0.0;
  for (std::size_t k = 0; k < simulation.pieceCount(); ++k) {
    const Piece& piece = simulation.piece(k);
    volume += piece.volume();
    rest += piece.restVolume();
    for (const glm::dvec3& v : piece.state().velocities) fastest = std::max(fastest, glm::dot(v, v));
  }
  return {volume / rest, std::sqrt(fastest)};
}

// CPU time of this thread: ms per step stays meaningful on a machine shared with other jobs.
double threadSeconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// One point of the report's series: kept as plain numbers while the run goes, turned into
// JSON once at the end, so a long run's memory grows by its data and not by JSON nodes.
// Each hand: whether it holds, where its part of the surface is (m) and its force on the body (N).
struct HandSample {
  bool holding = false;
  glm::dvec3 position{0.0}, force{0.0};
};

// While both hands hold: the drawn body's thickness across the line between them at ¼, ½ and ¾ of
// the way (strandThickness), m — whether a strand thins in the middle.
constexpr double kStrandFractions[3] = {0.25, 0.5, 0.75};

struct SeriesSample {
  double t, volumeRatio, height, width, kineticEnergy;
  HandSample hands[kHands];
  double strand[3] = {-1.0, -1.0, -1.0};  // −1: not both hands holding
  std::vector<EnclosedSolid> pieces;      // each piece's drawn volume and centroid
};

// The report's "pieces": how many, the total volume their drawn surfaces enclose (m³), and each
// piece's volume (m³) and centroid (m, of the enclosed solid), in the order Simulation::surfaces gives.
json piecesJson(const std::vector<EnclosedSolid>& pieces) {
  json each = json::array();
  double total = 0.0;
  for (const EnclosedSolid& piece : pieces) {
    total += piece.volume;
    each.push_back({{"volume", piece.volume}, {"centroid", {piece.centroid.x, piece.centroid.y, piece.centroid.z}}});
  }
  return {{"count", pieces.size()}, {"total_volume", total}, {"each", each}};
}

SeriesSample metricsSample(double t, const SlimeMetrics& metrics, const Simulation& simulation) {
  SeriesSample sample{t, metrics.volumeRatio, metrics.height, metrics.width, metrics.kineticEnergy, {}, {-1.0, -1.0, -1.0},
                      simulation.pieceSolids()};
  for (int hand = 0; hand < kHands; ++hand)
    if (simulation.grabbing(hand))
      sample.hands[hand] = {true, simulation.grabbedPoint(hand), simulation.handForce(hand)};
  if (sample.hands[0].holding && sample.hands[1].holding)
    for (int i = 0; i < 3; ++i)
      sample.strand[i] = strandThickness(simulation.positions(), sample.hands[0].position, sample.hands[1].position,
                                         kStrandFractions[i]);
  return sample;
}

json seriesJson(const std::vector<SeriesSample>& series) {
  json samples = json::array();
  for (const SeriesSample& s : series) {
    json hands = json::array();
    for (const HandSample& hand : s.hands) {
      if (!hand.holding) {
        hands.push_back({{"holding", false}});
        continue;
      }
      hands.push_back({{"holding", true},
                       {"position", {hand.position.x, hand.position.y, hand.position.z}},
                       {"force", {hand.force.x, hand.force.y, hand.force.z}}});
    }
    samples.push_back({{"t", s.t}, {"volume_ratio", s.volumeRatio}, {"height", s.height}, {"width", s.width},
                       {"kinetic_energy", s.kineticEnergy}, {"hands", hands}, {"pieces", piecesJson(s.pieces)}});
    if (s.strand[0] >= 0.0) samples.back()["strand"] = {s.strand[0], s.strand[1], s.strand[2]};
  }
  return samples;
}

int runSim(const SimOptions& options) {
  checkSeconds(options.seconds);
  Settings settings = loadSettings(options.scene);
  std::optional<ScenarioPlayer> player;
  if (!options.scene.scenarioFile.empty()) player.emplace(loadScenario(options.scene.scenarioFile));

  Simulation simulation(settings);
  const double dt = settings.sim.dt;
  std::optional<MeshExporter> exporter;
  const UpAxis objUp = checkObjUp(options.objUp, options.exportMesh);
  if (!options.exportMesh.empty()) {
    if (options.exportEvery < 0.0) throw SettingsError("--export-mesh needs --export-every S (simulated seconds)");
    exporter.emplace(options.exportMesh, options.exportEvery, dt, options.seconds, objUp);
  } else if (options.exportEvery >= 0.0) {
    throw SettingsError("--export-every needs --export-mesh PATTERN");
  }
  const auto exportIfDue = [&] {
    if (exporter && exporter->due(simulation.stepCount()))
      exporter->add(simulation.time(), simulation.surfaces(),
                    exportMaterialOf(settings.slime));  // the scene's optics, as a scenario left them
  };
  exportIfDue();
  const auto totalSteps = static_cast<std::int64_t>(std::llround(options.seconds / dt));
  const auto sampleEvery = std::max<std::int64_t>(1, std::llround(kSeriesInterval / dt));

  SlimeMetrics metrics = simulation.metrics();
  double volumeMin = metrics.volumeRatio, volumeMax = metrics.volumeRatio;
  double minZ = metrics.minZ, maxSpeed = metrics.maxSpeed;
  std::vector<SeriesSample> series;
  series.reserve(static_cast<std::size_t>(totalSteps / sampleEvery) + 2);
  series.push_back(metricsSample(0.0, metrics, simulation));
  std::int64_t stepsRun = 0;
  double stepSeconds = 0.0;  // thread CPU time inside step()
  double tearMilliseconds = 0.0, mergeMilliseconds = 0.0;  // the dearest tear and merge (wall time inside its step)
  double tearCpuMilliseconds = 0.0, mergeCpuMilliseconds = 0.0;  // ... and in the thread's CPU time
  const auto wallStart = std::chrono::steady_clock::now();
  while (simulation.stepCount() < totalSteps && simulation.divergences().size() <= kMaxRollbacks) {
    if (player) player->advanceTo(simulation.time(), simulation, settings);
    const double start = threadSeconds();
    const int tearsBefore = simulation.tears(), mergesBefore = simulation.merges();
    simulation.step();
    stepSeconds += threadSeconds() - start;
    ++stepsRun;
    if (simulation.tears() != tearsBefore) {
      tearMilliseconds = std::max(tearMilliseconds, simulation.lastTopologyMilliseconds());
      tearCpuMilliseconds = std::max(tearCpuMilliseconds, simulation.lastTopologyCpuMilliseconds());
    }
    if (simulation.merges() != mergesBefore) {
      mergeMilliseconds = std::max(mergeMilliseconds, simulation.lastTopologyMilliseconds());
      mergeCpuMilliseconds = std::max(mergeCpuMilliseconds, simulation.lastTopologyCpuMilliseconds());
    }
    exportIfDue();
    // Every step, what the step itself holds (the bodies' volume, the points' speed); the shape, which
    // places the drawn surface (for the bulk body the smooth map, twice a step's cost at level 4), at
    // the series' samples.
    const BodyFigures body = bodyFiguresOf(simulation);
    volumeMin = std::min(volumeMin, body.volumeRatio);
    volumeMax = std::max(volumeMax, body.volumeRatio);
    maxSpeed = std::max(maxSpeed, body.maxSpeed);
    if (simulation.stepCount() % sampleEvery == 0) {
      metrics = simulation.metrics();
      minZ = std::min(minZ, metrics.minZ);
      series.push_back(metricsSample(static_cast<double>(simulation.stepCount()) * dt, metrics, simulation));
    }
  }
  const double wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wallStart).count();
  if (exporter) {
    exporter->finish();
    std::printf("exported %d frames of the surface to %s\n", exporter->frames(), options.exportMesh.c_str());
  }
  metrics = simulation.metrics();
  minZ = std::min(minZ, metrics.minZ);
  const bool nan = !std::isfinite(metrics.volumeRatio) || !std::isfinite(metrics.kineticEnergy) ||
                   std::any_of(simulation.divergences().begin(), simulation.divergences().end(),
                               [](const DivergenceEvent& e) { return e.what.find("NaN") != std::string::npos; });
  const double msPerStep = stepsRun > 0 ? 1000.0 * stepSeconds / static_cast<double>(stepsRun) : 0.0;
  const std::size_t rollbacks = simulation.divergences().size();

  std::printf("sim: %.3f s, %lld steps of %g s, %s, %s, level %d (%zu vertices drawn, %zu simulated), %.4f ms/step, "
              "volume %.4f, aspect %.3f, min z %.2e m, KE %.2e J, rollbacks %zu%s\n",
              simulation.time(), static_cast<long long>(simulation.stepCount()), dt,
              simulation.settings().slime.model.c_str(), integratorName(simulation.integrator()).c_str(),
              simulation.settings().slime.level, simulation.positions().size(), simulation.state().size(), msPerStep,
              metrics.volumeRatio, metrics.aspect, metrics.minZ, metrics.kineticEnergy, rollbacks,
              nan ? ", NaN" : "");

  if (!options.reportFile.empty()) {
    const glm::dvec3 finalCentroid = centroid(simulation.positions());
    json divergences = json::array();
    for (const DivergenceEvent& e : simulation.divergences())
      divergences.push_back({{"step", e.step}, {"time", e.time}, {"integrator", e.integrator}, {"what", e.what}});
    json report = {
        {"seconds", options.seconds},
        {"steps", simulation.stepCount()},
        {"steps_run", stepsRun},
        {"dt", dt},
        {"substeps", simulation.substepsPerStep()},
        {"integrator", settings.sim.integrator},
        {"integrator_used", integratorName(simulation.integrator())},  // auto resolved (integrator_choice.h)
        {"level", simulation.settings().slime.level},
        {"model", simulation.settings().slime.model},
        {"vertices", simulation.positions().size()},
        {"simulated_points", simulation.state().size()},
        {simulation.bulk() ? "tetrahedra" : "springs", simulation.elementCount()},
        {"ms_per_step", msPerStep},
        {"cpu_seconds", stepSeconds},
        // The simulating thread's CPU ms per simulated ms (1.0: real time on one core), whatever sim.dt is.
        {"cpu_per_simulated", stepsRun > 0 ? stepSeconds / (static_cast<double>(stepsRun) * dt) : 0.0},
        {"wall_seconds", wallSeconds},
        {"nan", nan},
        {"rollbacks", rollbacks},
        {"divergences", divergences},
        // slime.tearing and slime.mergeTime: how many tears and merges, and the dearest of each, wall ms.
        {"tears", simulation.tears()},
        {"merges", simulation.merges()},
        {"tear_ms_max", tearMilliseconds},
        {"merge_ms_max", mergeMilliseconds},
        {"tear_cpu_ms_max", tearCpuMilliseconds},
        {"merge_cpu_ms_max", mergeCpuMilliseconds},
        {"final", {{"volume_ratio", metrics.volumeRatio}, {"height", metrics.height}, {"width", metrics.width},
                   {"aspect", metrics.aspect}, {"min_z", metrics.minZ}, {"kinetic_energy", metrics.kineticEnergy},
                   {"max_speed", metrics.maxSpeed},
                   // Counted at the end only: counted at the series' samples, between the timed steps, it
                   // made resolution 4's measured step 5-10 % dearer (AMD EPYC, shared; not understood).
                   {"inverted_elements", simulation.invertedElements()},
                   {"centroid", {finalCentroid.x, finalCentroid.y, finalCentroid.z}},
                   {"pieces", piecesJson(simulation.pieceSolids())}}},
        {"range", {{"volume_ratio_min", volumeMin}, {"volume_ratio_max", volumeMax}, {"min_z", minZ},
                   {"max_speed", maxSpeed}}},
        {"series", seriesJson(series)},
    };
    try {
      writeFileAtomically(options.reportFile, report.dump(2) + "\n");
    } catch (const std::runtime_error& e) {
      throw SettingsError(std::string("--report: ") + e.what());
    }
  }
  return rollbacks > kMaxRollbacks ? 1 : 0;
}

}  // namespace

void registerSimCommand(CLI::App& root, int& exitCode) {
  auto options = std::make_shared<SimOptions>();
  std::string integrators;
  for (const std::string& name : integratorNames()) integrators += (integrators.empty() ? "" : ", ") + name;
  auto* command = root.add_subcommand(
      "sim", "Run the physics headless and report shape, volume and energy (integrators: " + integrators +
                 "; choose with --set sim.integrator=NAME)");
  command->add_option("--seconds", options->seconds, "Simulated seconds to run (> 0, at most 3600)")
      ->capture_default_str();
  command->add_option("--report", options->reportFile, "Write a JSON report to this file");
  command->add_option("--export-mesh", options->exportMesh,
                      "Write the slime's surface: PATTERN.ply or .obj with a frame number (out/slime_%04d.ply), "
                      "or one animated FILE.glb; each carries the slime's material (an .obj in a .mtl beside it)");
  command->add_option("--obj-up", options->objUp,
                      "Up axis of an exported .obj: y (OBJ's convention, the default) or z (the simulation's)");
  command->add_option("--export-every", options->exportEvery,
                      "Simulated seconds between exported surfaces, from t = 0 (at least sim.dt)");
  addSceneOptions(*command, options->scene);
  command->callback([options, &exitCode] { exitCode = runSim(*options); });
}

}  // namespace slime
