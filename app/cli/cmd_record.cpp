// `slime record -o clip.mp4 --scenario FILE --seconds S [--fps 30] [--size WxH] [--ui]`: replays a
// scenario headless and encodes it (video_encoder.h). Frames are taken on the simulation clock:
// frame k shows the slime at t = k / fps, however long the machine takes to compute it, so the same
// inputs always give the same clip.
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>

#include "app/cli/commands.h"
#include "app/cli/snapshot.h"
#include "app/cli/video_encoder.h"
#include "app/viewer/ui_snapshot.h"
#include "core/simulation/scenario.h"
#include "core/settings/settings_io.h"
#include "core/simulation/simulation.h"
#include "render/image/image_io.h"
#include "render/trace/renderer.h"

namespace slime {
namespace {

struct RecordOptions {
  SceneOptions scene;
  std::string output;
  double seconds = 0.0;
  int fps = 30;
  std::string size;
  bool ui = false;
  std::string gl = "auto";
};

constexpr double kLongestClipSeconds = 600.0;
constexpr int kFastestFps = 120;

volatile std::sig_atomic_t interrupted = 0;

// The traced image alone, as `slime snapshot` draws it.
class TracedFrames {
 public:
  explicit TracedFrames(const Settings& settings) : renderer_(settings), simulation_(settings) {}
  Simulation& simulation() { return simulation_; }
  std::vector<std::uint8_t> draw(const Settings& settings) {
    renderer_.updateSlime(simulation_.surfaces());
    image_.resize(settings.camera.width, settings.camera.height);
    renderer_.render(settings, image_);
    return toSrgb8(image_);
  }

 private:
  Renderer renderer_;
  Simulation simulation_;
  Image image_;
};

void checkOptions(const RecordOptions& options) {
  if (!std::isfinite(options.seconds) || options.seconds <= 0.0 || options.seconds > kLongestClipSeconds)
    throw SettingsError("--seconds " + std::to_string(options.seconds) +
                        ": expected a duration above 0 and at most " +
                        std::to_string(static_cast<int>(kLongestClipSeconds)) + " s");
  if (options.fps < 1 || options.fps > kFastestFps)
    throw SettingsError("--fps " + std::to_string(options.fps) + ": expected 1 to " +
                        std::to_string(kFastestFps) + " frames per second");
  clipFormatOf(options.output);
}

void showProgress(int done, int total) {
  constexpr int kBarWidth = 40;
  const int filled = total > 0 ? done * kBarWidth / total : kBarWidth;
  std::fprintf(stderr, "\rrecording [%.*s%*s] %d/%d frames", filled,
               "########################################", kBarWidth - filled, "", done, total);
  if (done == total) std::fprintf(stderr, "\n");
}

void runRecord(const RecordOptions& options) {
  checkOptions(options);
  const HeadlessApi api = headlessApiNamed(options.gl);
  Settings settings = loadSettings(options.scene);
  if (!options.size.empty()) applyImageSize(settings, options.size);
  validateSettings(settings);
  std::optional<ScenarioPlayer> player;
  if (!options.scene.scenarioFile.empty()) player.emplace(loadScenario(options.scene.scenarioFile));

  VideoEncoder encoder({options.output, settings.camera.width, settings.camera.height, options.fps});
  std::unique_ptr<TracedFrames> traced;
  std::unique_ptr<UiFrames> ui;
  if (options.ui)
    ui = std::make_unique<UiFrames>(settings, api);
  else
    traced = std::make_unique<TracedFrames>(settings);
  Simulation& simulation = ui ? ui->simulation() : traced->simulation();

  interrupted = 0;
  const auto previousHandler = std::signal(SIGINT, [](int) { interrupted = 1; });
  const bool progress = isatty(STDERR_FILENO) != 0;
  const int frames = static_cast<int>(std::lround(options.seconds * options.fps));
  try {
    for (int frame = 0; frame < frames; ++frame) {
      if (interrupted) throw std::runtime_error("interrupted; no clip written");
      // Frame k is the state at t = k / fps: the steps that bring the clock there, the scenario's
      // events fired on the way exactly as `slime sim` and `slime snapshot` fire them.
      const auto steps = static_cast<std::int64_t>(std::llround(frame / (options.fps * settings.sim.dt)));
      while (simulation.stepCount() < steps) {
        if (player) player->advanceTo(simulation.time(), simulation, settings);
        simulation.step();
      }
      encoder.write(ui ? ui->draw() : traced->draw(settings));
      if (progress) showProgress(frame + 1, frames);
    }
    encoder.finish();
  } catch (...) {
    std::signal(SIGINT, previousHandler);
    throw;
  }
  std::signal(SIGINT, previousHandler);
  std::printf("wrote %s: %d frames, %dx%d, %d fps, %.3f s simulated\n", options.output.c_str(), frames,
              settings.camera.width, settings.camera.height, options.fps, simulation.time());
}

}  // namespace

void registerRecordCommand(CLI::App& root, int& exitCode) {
  auto options = std::make_shared<RecordOptions>();
  auto* command = root.add_subcommand(
      "record",
      "Replay a scenario headless and encode it with ffmpeg: .mp4, .gif or .webp, frame k at t = k/fps");
  command->add_option("-o,--output", options->output, "Clip to write: .mp4 (H.264), .gif or .webp")
      ->required();
  command->add_option("--seconds", options->seconds, "Simulated seconds to record (above 0, at most 600)")
      ->required();
  command->add_option("--fps", options->fps, "Frames per simulated second (1..120, default 30)");
  command->add_option("--size", options->size,
                      "Frame size WxH in pixels, default camera.width x camera.height");
  auto* ui = command->add_flag("--ui", options->ui,
                    "Record the whole viewer (image and panels), drawn headless");
  command->add_option("--gl", options->gl,
                      "With --ui, the headless GL: egl, osmesa, or auto (EGL, else OSMesa; the default)")
      ->needs(ui);
  addSceneOptions(*command, options->scene);
  command->callback([options, &exitCode] {
    runRecord(*options);
    exitCode = 0;
  });
}

}  // namespace slime
