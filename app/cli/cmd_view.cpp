// `slime view` (and `slime` alone): the interactive window. Besides the scene options it takes the
// camera options of `snapshot`, and a few for tests and scripts: --frames, --screenshot-on-exit, --report,
// --frame-log, --check-every, --screenshot-at; and --target-fps, the adaptive resolution's target (off by default).
#include "app/cli/commands.h"
#include "app/cli/snapshot.h"
#include "app/viewer/viewer.h"
#include "app/viewer/window.h"
#include "core/geometry/camera.h"
#include "core/simulation/scenario.h"
#include "core/settings/settings_io.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace slime {
namespace {

struct ViewCommandOptions {
  SceneOptions scene;
  std::string size;                  // WxH
  std::vector<double> viewPoint;     // --vp x y z
  std::vector<double> viewInterest;  // --vi x y z
  double fov = 0.0;                  // --fov degrees; 0 = the scene's
  double targetFps = -1.0;           // --target-fps (render.targetFps); < 0: the scene's
  bool redrawWholeWindow = false;    // --redraw-whole-window: swap whole frames (window.h)
  ViewerOptions viewer;
};

// The window opens at 1280x720 unless --size, the scene file or a --set says otherwise.
constexpr int kDefaultWindowWidth = 1280, kDefaultWindowHeight = 720;

bool imageSizeGiven(const SceneOptions& scene) {
  for (const std::string& assignment : scene.overrides)
    if (assignment.rfind("camera.width=", 0) == 0 || assignment.rfind("camera.height=", 0) == 0) return true;
  if (scene.sceneFile.empty()) return false;
  std::ifstream file(scene.sceneFile);
  const nlohmann::json document = nlohmann::json::parse(file, nullptr, /*allow_exceptions=*/false);
  return document.is_object() && document.contains("camera") && document["camera"].is_object() &&
         (document["camera"].contains("width") || document["camera"].contains("height"));
}

// --size, --eye, --look-at and --fov on top of the scene; validated again afterwards.
void applyCameraOptions(const ViewCommandOptions& options, Settings& settings) {
  if (!options.size.empty()) applyImageSize(settings, options.size);  // the window size, as snapshot --size
  else if (!imageSizeGiven(options.scene))
    settings.camera.width = kDefaultWindowWidth, settings.camera.height = kDefaultWindowHeight;
  if (!options.viewPoint.empty())
    settings.camera.position = {options.viewPoint[0], options.viewPoint[1], options.viewPoint[2]};
  if (!options.viewInterest.empty()) {
    const glm::dvec3 target{options.viewInterest[0], options.viewInterest[1], options.viewInterest[2]};
    if (target == settings.camera.position) throw SettingsError("--look-at (--vi) must differ from the eye position");
    lookAt(settings.camera, settings.camera.position, target);
  }
  if (options.fov != 0.0) settings.camera.fov = options.fov;
  validateSettings(settings);
}

// A file the viewer writes at exit: checked before the window opens, so a typo does not cost the run.
void checkOutputFile(const char* option, const std::string& path) {
  if (path.empty()) return;
  namespace fs = std::filesystem;
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent))
    throw SettingsError(std::string(option) + " " + path + ": the directory " + parent.string() +
                        " does not exist");
  if (fs::is_directory(path))
    throw SettingsError(std::string(option) + " " + path + ": is a directory; expected a file name");
}

}  // namespace

void registerViewCommand(CLI::App& root, int& exitCode) {
  auto options = std::make_shared<ViewCommandOptions>();
  auto* command = root.add_subcommand("view", "Open the interactive viewer (what `slime` alone does)");
  addSceneOptions(*command, options->scene);
  command->add_option("--size", options->size,
                      "Window size WIDTHxHEIGHT (default: 1280x720, or the scene's camera.width x camera.height "
                      "when the scene file or --set gives them)");
  command->add_option("--eye,--vp", options->viewPoint, "Eye position x y z, m")->expected(3);
  command->add_option("--look-at,--vi", options->viewInterest, "Point to look at x y z, m (sets yaw and pitch)")->expected(3);
  command->add_option("--fov", options->fov, "Vertical field of view, degrees");
  command->add_option("--frames", options->viewer.maxFrames, "Quit after N frames (for scripts and tests)")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--screenshot-on-exit", options->viewer.screenshotOnExit, "Write the last frame to this PNG");
  command->add_option("--report", options->viewer.reportPath,
                      "Write a JSON summary (machine, frames, fps, stages, resolution, grabs, metrics, settings) "
                      "at exit");
  command->add_option("--frame-log", options->viewer.frameLogPath,
                      "Write every frame (wall time, stages, traced size, grabbed) as CSV at exit");
  command->add_option("--target-fps", options->targetFps,
                      "Adaptive resolution: trace smaller while frames miss this rate as the view moves "
                      "(0 = off, the default: always full resolution); sets render.targetFps")
      ->check(CLI::Range(0.0, AdaptiveResolution::kMaximumTargetFps));
  command->add_option("--check-every", options->viewer.checkEvery,
                      "Every K-th frame, also trace in full the image the same physics state and camera give "
                      "(what `snapshot` would write) and report the PSNR of the shown image against it in "
                      "--report's \"check\" (0 = never, the default); the checks' time is left out of the frame times")
      ->check(CLI::Range(0, 1000000));
  command->add_option("--screenshot-prefix", options->viewer.screenshotPrefix, "F12 writes <prefix>-<n>.png");
  command->add_option("--screenshot-at", options->viewer.screenshotTimes,
                      "Also write <prefix>-<n>.png when the simulation reaches each of these simulated times, s "
                      "(ascending; a scenario's moments whatever the machine's speed); --report lists them under "
                      "\"timed_screenshots\" with each piece's centroid's window pixel")
      ->check(CLI::Range(0.0, 3600.0));
  command->add_flag("--redraw-whole-window", options->redrawWholeWindow,
                    "Draw the whole window every frame and swap buffers, instead of drawing again and "
                    "showing only what changed (where GLX_MESA_copy_sub_buffer allows it); for comparison");
  command->callback([options, &exitCode] {
    Settings settings = loadSettings(options->scene);
    applyCameraOptions(*options, settings);
    if (options->targetFps >= 0.0) settings.render.targetFps = options->targetFps;
    checkOutputFile("--report", options->viewer.reportPath);
    checkOutputFile("--frame-log", options->viewer.frameLogPath);
    if (!std::is_sorted(options->viewer.screenshotTimes.begin(), options->viewer.screenshotTimes.end()))
      throw SettingsError("--screenshot-at: the times must be in ascending order");
    if (!options->scene.scenarioFile.empty()) options->viewer.scenario = loadScenario(options->scene.scenarioFile);
    Window window("Slime", settings.camera.width, settings.camera.height, !options->redrawWholeWindow);
    Viewer viewer(window, settings, options->viewer);
    exitCode = viewer.run();
  });
}

}  // namespace slime
