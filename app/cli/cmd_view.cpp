// `slime view` (and `slime` alone): the interactive window. Besides the scene options it takes the
// camera options of `snapshot`, and a few for tests and scripts: --frames, --screenshot-on-exit, --report.
#include "app/cli/commands.h"
#include "app/cli/snapshot.h"
#include "app/viewer/viewer.h"
#include "app/viewer/window.h"
#include "core/camera.h"
#include "core/scenario.h"
#include "core/settings_io.h"


namespace slime {
namespace {

struct ViewCommandOptions {
  SceneOptions scene;
  std::string size;                  // WxH
  std::vector<double> viewPoint;     // --vp x y z
  std::vector<double> viewInterest;  // --vi x y z
  double fov = 0.0;                  // --fov degrees; 0 = the scene's
  ViewerOptions viewer;
};

// --size, --vp, --vi and --fov on top of the scene; validated again afterwards.
void applyCameraOptions(const ViewCommandOptions& options, Settings& settings) {
  if (!options.size.empty()) applyImageSize(settings, options.size);  // the window size, as snapshot --size
  if (!options.viewPoint.empty())
    settings.camera.position = {options.viewPoint[0], options.viewPoint[1], options.viewPoint[2]};
  if (!options.viewInterest.empty()) {
    const glm::dvec3 target{options.viewInterest[0], options.viewInterest[1], options.viewInterest[2]};
    if (target == settings.camera.position) throw SettingsError("--vi must differ from the eye position");
    lookAt(settings.camera, settings.camera.position, target);
  }
  if (options.fov != 0.0) settings.camera.fov = options.fov;
  validateSettings(settings);
}

}  // namespace

void registerViewCommand(CLI::App& root, int& exitCode) {
  auto options = std::make_shared<ViewCommandOptions>();
  auto* command = root.add_subcommand("view", "Open the interactive viewer (what `slime` alone does)");
  addSceneOptions(*command, options->scene);
  command->add_option("--size", options->size, "Window size WIDTHxHEIGHT (default: camera.width x camera.height)");
  command->add_option("--vp", options->viewPoint, "Eye position x y z, m")->expected(3);
  command->add_option("--vi", options->viewInterest, "Point to look at x y z, m")->expected(3);
  command->add_option("--fov", options->fov, "Vertical field of view, degrees");
  command->add_option("--frames", options->viewer.maxFrames, "Quit after N frames (for scripts and tests)")
      ->check(CLI::NonNegativeNumber);
  command->add_option("--screenshot-on-exit", options->viewer.screenshotOnExit, "Write the last frame to this PNG");
  command->add_option("--report", options->viewer.reportPath, "Write a JSON summary (frames, fps, metrics, settings) at exit");
  command->add_option("--screenshot-prefix", options->viewer.screenshotPrefix, "F12 writes <prefix>-<n>.png");
  command->callback([options, &exitCode] {
    Settings settings = loadSettings(options->scene);
    applyCameraOptions(*options, settings);
    if (!options->scene.scenarioFile.empty()) options->viewer.scenario = loadScenario(options->scene.scenarioFile);
    Window window("Slime", settings.camera.width, settings.camera.height);
    Viewer viewer(window, settings, options->viewer);
    exitCode = viewer.run();
  });
}

}  // namespace slime
