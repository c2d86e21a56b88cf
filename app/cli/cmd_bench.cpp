// `slime bench render|physics|accuracy|material`: the benchmarks behind docs/bench (scripts/bench.sh
// runs them all and redraws the charts). Each prints a table, and writes every figure with --json/--csv.
#include "app/bench/render/bench_accuracy.h"
#include "app/bench/render/bench_reference.h"
#include "app/bench/render/bench_caustics.h"
#include "app/bench/material/bench_material.h"
#include "app/bench/physics/bench_front.h"
#include "app/bench/physics/bench_physics.h"
#include "app/bench/render/bench_render.h"
#include "app/bench/report/bench_report.h"
#include "app/cli/commands.h"
#include "app/viewer/viewer_bench.h"
#include "core/integrators/integrators.h"
#include "core/settings/settings_io.h"
#include "core/bulk/tet_mesh.h"

#include <memory>
#include <stdexcept>

namespace slime {
namespace {

// Parses "WxH" (each 1..8192) for --size.
void parseSize(const std::string& text, int& width, int& height) {
  const std::size_t x = text.find_first_of("xX");
  try {
    if (x == std::string::npos) throw std::invalid_argument("no x");
    std::size_t usedWidth = 0, usedHeight = 0;
    width = std::stoi(text.substr(0, x), &usedWidth);
    height = std::stoi(text.substr(x + 1), &usedHeight);
    if (usedWidth != x || usedHeight != text.size() - x - 1 || width < 1 || height < 1 || width > 8192 || height > 8192)
      throw std::invalid_argument("range");
  } catch (const std::exception&) {
    throw SettingsError("--size must be WxH with W and H whole numbers in 1..8192 pixels, got '" + text + "'");
  }
}

std::vector<int> parseList(const std::string& option, const std::string& text, int low, int high) {
  std::vector<int> values;
  try {
    values = parseIntegerList(text);
  } catch (const std::exception& e) {
    throw SettingsError(option + ": " + e.what());
  }
  for (int value : values)
    if (value < low || value > high)
      throw SettingsError(option + " values must be in " + std::to_string(low) + ".." + std::to_string(high) +
                          ", got " + std::to_string(value));
  return values;
}

struct RenderCommand {
  SceneOptions scene;
  RenderBenchOptions bench;
  std::string levels = "0-6", threads, bvhLevels = "4,6", size = "734x564", headlineSizes = "734x564,1280x720";
};

void registerRender(CLI::App& bench, int& exitCode) {
  auto options = std::make_shared<RenderCommand>();
  auto* command = bench.add_subcommand("render", "Ray-tracing throughput vs faces and threads, against the Embree-only limit and the seed's brute force");
  command->add_option("--levels", options->levels, "Subdivision levels, e.g. 0-6 or 2,4")->capture_default_str();
  command->add_option("--threads", options->threads, "Thread counts, e.g. 1,2 (default: 1 and all cores)");
  command->add_option("--frames", options->bench.frames, "Timed frames per configuration")->check(CLI::Range(1, 10000))->capture_default_str();
  command->add_option("--warmup", options->bench.warmup, "Untimed frames first")->check(CLI::Range(0, 1000))->capture_default_str();
  command->add_option("--size", options->size, "Image size WxH")->capture_default_str();
  command->add_option("--depth", options->bench.depth, "Whitted recursion depth")->check(CLI::Range(1, 16))->capture_default_str();
  command->add_option("--brute-max-level", options->bench.bruteMaxLevel, "Run the seed's brute-force tracer up to this level (-1: never)")
      ->check(CLI::Range(-1, 7))->capture_default_str();
  command->add_option("--brute-samples", options->bench.bruteSamples,
                      "Timed brute-force frames at least, after one warm-up (below 3: the headline is labelled quick)")
      ->check(CLI::Range(1, 1000))->capture_default_str();
  command->add_option("--bvh-levels", options->bvhLevels, "Levels of the refit-vs-rebuild measurement ('none' to skip)")->capture_default_str();
  command->add_option("--headline-sizes", options->headlineSizes,
                      "Sizes of the headline deforming frame, e.g. 734x564,1280x720 ('none' to skip)")->capture_default_str();
  command->add_option("--headline-level", options->bench.headlineLevel, "Subdivision level of the headline frames")
      ->check(CLI::Range(0, 7))->capture_default_str();
  command->add_option("--json", options->bench.jsonFile, "Write every figure as JSON");
  command->add_option("--csv", options->bench.csvFile, "Write the tables as CSV (FILE and FILE_bvh, FILE_seed, FILE_headline)");
  addSceneOptions(*command, options->scene);
  command->callback([options, &exitCode] {
    RenderBenchOptions bench = options->bench;
    bench.headlineSizes.clear();
    if (options->headlineSizes != "none") {
      std::string list = options->headlineSizes;
      for (std::size_t start = 0; start <= list.size();) {
        const std::size_t comma = std::min(list.find(',', start), list.size());
        int width = 0, height = 0;
        parseSize(list.substr(start, comma - start), width, height);
        bench.headlineSizes.emplace_back(width, height);
        start = comma + 1;
      }
    }
    bench.levels = parseList("--levels", options->levels, 0, 7);
    if (!options->threads.empty()) bench.threads = parseList("--threads", options->threads, 1, 1024);
    bench.bvhLevels = options->bvhLevels == "none" ? std::vector<int>{} : parseList("--bvh-levels", options->bvhLevels, 0, 7);
    parseSize(options->size, bench.width, bench.height);
    runRenderBench(loadSettings(options->scene), bench);
    exitCode = 0;
  });
}

struct PhysicsCommand {
  SceneOptions scene;
  PhysicsBenchOptions bench;
  std::string levels = "3-6";
  std::string resolutions = "1-3";
  bool front = false, quick = false;
  FrontOptions frontOptions;
  std::string frontIterations = "1,2,4,8";
};

void registerPhysics(CLI::App& bench, int& exitCode) {
  auto options = std::make_shared<PhysicsCommand>();
  PhysicsBenchOptions& b = options->bench;
  auto* command = bench.add_subcommand("physics", "Integrators: ms/step by level, stability map, accuracy against cost, roundness at rest");
  command->add_option("--levels", options->levels, "Levels of the cost table, e.g. 3-6")->capture_default_str();
  command->add_option("--integrators", b.integrators, "Integrators (default: all), e.g. rk4,xpbd")->delimiter(',')
      ->check(CLI::IsMember(integratorNames()));
  command->add_option("--seconds", b.secondsPerMeasurement, "Wall seconds spent timing each integrator and level")
      ->check(CLI::Range(0.0, 600.0))->capture_default_str();
  command->add_option("--stability-level", b.stabilityLevel, "Level of the stability map (-1: skip)")->check(CLI::Range(-1, 7))->capture_default_str();
  command->add_option("--stiffnesses", b.stiffnesses, "Stiffnesses k_e of the stability map, N/m")->delimiter(',')
      ->check(CLI::PositiveNumber);
  command->add_option("--accuracy-level", b.accuracyLevel, "Level of the accuracy run (-1: skip)")->check(CLI::Range(-1, 7))->capture_default_str();
  command->add_option("--steps", b.steps, "Time steps of the accuracy run, s (each must divide 10 ms)")->delimiter(',')
      ->check(CLI::Range(1e-6, 0.01));
  command->add_option("--resolutions", options->resolutions, "Bulk resolutions of the cost table and Bullet's FEM peer, e.g. 1-3")
      ->capture_default_str();
  command->add_option("--bullet-tets-seconds", b.bulletTetsSeconds,
                      "Simulated seconds of Bullet's FEM on the body's tetrahedra, each resolution (0: skip)")
      ->check(CLI::Range(0.0, 60.0))->capture_default_str();
  command->add_option("--settle", b.settleSeconds, "Seconds to settle for the roundness at rest (0: skip)")
      ->check(CLI::Range(0.0, 60.0))->capture_default_str();
  command->add_option("--json", b.jsonFile, "Write every figure as JSON");
  command->add_option("--csv", b.csvFile, "Write the tables as CSV (FILE and FILE_stability, FILE_theory, FILE_accuracy)");
  FrontOptions& f = options->frontOptions;
  f.outputDirectory = "front";
  command->add_flag("--front", options->front,
                    "The front instead (docs/performance.md): every bulk integrator x step x iterations x resolution, "
                    "cost against each error (Lamb's modes, numerical damping, creep, rest height), the peers beside");
  command->add_flag("--quick", options->quick, "With --front: two points at resolution 1 and short runs (CI)");
  command->add_option("--front-steps-ms", f.stepsMs, "With --front: steps, ms (the explicit methods also at automatic substeps)")
      ->delimiter(',')->check(CLI::Range(0.01, 100.0))->capture_default_str();
  command->add_option("--front-iterations", options->frontIterations, "With --front: sim.iterations of the methods that iterate")
      ->capture_default_str();
  command->add_option("--jobs", f.jobs, "With --front: points measured at once, one thread each")
      ->check(CLI::Range(1, 64))->capture_default_str();
  command->add_option("--front-dir", f.outputDirectory, "With --front: where front.json, front.md and the charts go")
      ->capture_default_str();
  addSceneOptions(*command, options->scene);
  command->callback([options, command, &exitCode] {
    if (options->front) {
      FrontOptions front = options->quick ? FrontOptions::quick() : options->frontOptions;
      if (options->quick) {
        front.jobs = options->frontOptions.jobs;
        front.outputDirectory = options->frontOptions.outputDirectory;
      } else {
        if (command->count("--resolutions") > 0)
          front.resolutions = parseList("--resolutions", options->resolutions, kMinBodyResolution, kMaxBodyResolution);
        front.iterations = parseList("--front-iterations", options->frontIterations, 1, 100);
        front.integrators = options->bench.integrators;
      }
      runFront(loadSettings(options->scene), front);
      exitCode = 0;
      return;
    }
    PhysicsBenchOptions bench = options->bench;
    bench.levels = parseList("--levels", options->levels, 0, 7);
    bench.resolutions = parseList("--resolutions", options->resolutions, kMinBodyResolution, kMaxBodyResolution);
    runPhysicsBench(loadSettings(options->scene), bench);
    exitCode = 0;
  });
}

struct AccuracyCommand {
  SceneOptions scene;
  AccuracyBenchOptions bench;
  std::string levels = "0-6", depths = "1-6", size = "734x564";
};

void registerAccuracy(CLI::App& bench, int& exitCode) {
  auto options = std::make_shared<AccuracyCommand>();
  AccuracyBenchOptions& b = options->bench;
  auto* command = bench.add_subcommand("accuracy", "Image error of the mesh slime against the analytic sphere vs frame time");
  command->add_option("--levels", options->levels, "Subdivision levels, e.g. 0-6")->capture_default_str();
  command->add_option("--depths", options->depths, "Whitted depths, e.g. 1-6 (the largest is the reference's)")->capture_default_str();
  command->add_option("--normals", b.normals, "Shading normals to compare")->delimiter(',')->check(CLI::IsMember({"flat", "smooth"}));
  command->add_option("--frames", b.frames, "Timed frames per configuration")->check(CLI::Range(1, 1000))->capture_default_str();
  command->add_option("--size", options->size, "Image size WxH")->capture_default_str();
  command->add_option("--threads", b.threads, "Render threads (0: all cores)")->check(CLI::Range(0, 1024))->capture_default_str();
  command->add_option("--images", b.imageDirectory, "Directory for the reference and per-level PNGs");
  command->add_option("--json", b.jsonFile, "Write every figure as JSON");
  command->add_option("--csv", b.csvFile, "Write the table as CSV");
  addSceneOptions(*command, options->scene);
  command->callback([options, &exitCode] {
    AccuracyBenchOptions bench = options->bench;
    bench.levels = parseList("--levels", options->levels, 0, 7);
    bench.depths = parseList("--depths", options->depths, 1, 16);
    parseSize(options->size, bench.width, bench.height);
    runAccuracyBench(loadSettings(options->scene), bench);
    exitCode = 0;
  });
}

struct MaterialCommand {
  SceneOptions scene;
  bool quick = false;
  std::string resolutions, jsonFile, csvFile;
};

void registerMaterial(CLI::App& bench, int& exitCode) {
  auto options = std::make_shared<MaterialCommand>();
  auto* command = bench.add_subcommand("material", "The bulk body against Lamb's frequencies, the material's creep time, energy drift, a tensile test, the integrators' numerical damping");
  command->add_flag("--quick", options->quick, "Resolutions 1-2 and short runs (CI)");
  command->add_option("--resolutions", options->resolutions, "Resolutions of the Lamb runs, e.g. 1-3 (default 1-3; --quick 1-2)");
  command->add_option("--json", options->jsonFile, "Write every figure as JSON");
  command->add_option("--csv", options->csvFile, "Write the Lamb table as CSV (and FILE_creep, the creep and recovery series; FILE_tensile, the uniform bar's stress-strain; FILE_tensile_bar, the meshed cylinder's; FILE_pull, the two hands' force-extension; FILE_damping, the integrators' numerical damping against the step)");
  addSceneOptions(*command, options->scene);
  command->callback([options, &exitCode] {
    MaterialBenchOptions bench = options->quick ? MaterialBenchOptions::quick() : MaterialBenchOptions{};
    if (!options->resolutions.empty())
      bench.resolutions = parseList("--resolutions", options->resolutions, kMinBodyResolution, kMaxBodyResolution);
    bench.jsonFile = options->jsonFile;
    bench.csvFile = options->csvFile;
    runMaterialBench(loadSettings(options->scene), bench);
    exitCode = 0;
  });
}

void registerCaustics(CLI::App& bench, int& exitCode) {
  struct CausticsCommand {
    SceneOptions scene;
    CausticsBenchOptions bench;
    std::string photons = "2500,5000,10000,20000,40000,80000,160000";
  };
  auto options = std::make_shared<CausticsCommand>();
  auto* command = bench.add_subcommand("caustics", "Caustic map error against photon count and time (the ball lens)");
  command->add_option("--photons", options->photons, "Photon counts, comma separated")->capture_default_str();
  command->add_option("--frames", options->bench.frames, "Timed runs per count (median)")->check(CLI::Range(1, 100))->capture_default_str();
  command->add_option("--csv", options->bench.csvFile, "Write the table as CSV");
  addSceneOptions(*command, options->scene);
  command->callback([options, &exitCode] {
    CausticsBenchOptions bench = options->bench;
    bench.photons.clear();
    std::size_t start = 0;
    const std::string& text = options->photons;
    while (start <= text.size()) {
      const std::size_t end = std::min(text.find(',', start), text.size());
      const std::string item = text.substr(start, end - start);
      char* rest = nullptr;
      const long value = std::strtol(item.c_str(), &rest, 10);
      if (item.empty() || *rest != '\0' || value < 100 || value > 10000000)
        throw CLI::ValidationError("--photons", "each count must be a whole number 100..10000000, got '" + item + "'");
      bench.photons.push_back(static_cast<int>(value));
      start = end + 1;
    }
    runCausticsBench(loadSettings(options->scene), bench);
    exitCode = 0;
  });
}

void registerViewer(CLI::App& bench, int& exitCode) {
  struct ViewerCommand {
    SceneOptions scene;
    ViewerBenchOptions bench;
    std::string size = "1280x720";
    std::string gl = "auto";
  };
  auto options = std::make_shared<ViewerCommand>();
  auto* command = bench.add_subcommand(
      "viewer", "The viewer's frame times in every phase (falling ... resting, held, stretched, orbiting, editing), "
                "headless in real time: median, 95th and 99th percentile, longest frame, the slowest 3 s window "
                "(--scenario: the phases' script, default tests/scenarios/viewer_phases.json)");
  command->add_option("--size", options->size, "Image size WIDTHxHEIGHT")->capture_default_str();
  command->add_option("--seconds", options->bench.seconds,
                      "Simulated seconds to run (0: the scenario's last event + 6 s)")->check(CLI::Range(0.0, 3600.0))->capture_default_str();
  command->add_option("--wall-seconds", options->bench.wallSeconds,
                      "Stop after this much wall time even if the simulation is behind (0: twice --seconds + 30)")->check(CLI::Range(0.0, 36000.0))->capture_default_str();
  command->add_option("--gl", options->gl, "Headless GL: egl, osmesa or auto")->capture_default_str();
  command->add_option("--csv", options->bench.csvPath, "Write every frame (the frame log) as CSV");
  command->add_option("--json", options->bench.jsonPath, "Write the table as JSON");
  addSceneOptions(*command, options->scene);
  command->callback([options, &exitCode] {
    ViewerBenchOptions bench = options->bench;
    parseSize(options->size, bench.width, bench.height);
    bench.api = headlessApiNamed(options->gl);
    if (!options->scene.scenarioFile.empty()) bench.scenarioPath = options->scene.scenarioFile;
    exitCode = runViewerBench(loadSettings(options->scene), bench);
  });
}

void registerReference(CLI::App& bench, int& exitCode) {
  auto options = std::make_shared<ReferenceBenchOptions>();
  auto* command = bench.add_subcommand(
      "reference", "Our linear frame against a path tracer's (scripts/reference/render.sh): PSNR over the slime, its shadow and the floor, the shadow's gain");
  command->add_option("--ours", options->ours, "Our frame, linear floats (slime snapshot --linear F.pfm)")->required();
  command->add_option("--reference", options->reference, "The path tracer's frame (PFM)")->required();
  command->add_option("--masks", options->masks, "The regions (PFM: R slime, G shadow, B lit floor)")->required();
  command->add_option("--ours-bare", options->oursBare, "Our frame with no slime in the light's way (PFM)");
  command->add_option("--reference-bare", options->referenceBare, "The path tracer's frame without the slime (PFM)");
  command->add_option("--haze", options->haze, "What the haze adds to each floor pixel (PFM; the masks' NAME_haze.pfm), taken from both before the gain");
  command->add_option("--picture", options->picture, "Write ours | reference | difference x4 as a PNG");
  command->add_option("--label", options->label, "A name for the printed row");
  command->callback([options, &exitCode] {
    if (options->oursBare.empty() != options->referenceBare.empty())
      throw CLI::ValidationError("--ours-bare", "the shadow's gain needs both --ours-bare and --reference-bare");
    runReferenceBench(*options);
    exitCode = 0;
  });
}

}  // namespace

void registerBenchCommand(CLI::App& root, int& exitCode) {
  auto* bench = root.add_subcommand("bench", "Benchmarks: render throughput, physics cost and stability, image accuracy, material oracles");
  bench->require_subcommand(1);
  registerRender(*bench, exitCode);
  registerPhysics(*bench, exitCode);
  registerAccuracy(*bench, exitCode);
  registerMaterial(*bench, exitCode);
  registerCaustics(*bench, exitCode);
  registerViewer(*bench, exitCode);
  registerReference(*bench, exitCode);
}

}  // namespace slime
