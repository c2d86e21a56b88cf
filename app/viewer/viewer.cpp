#include "app/viewer/viewer.h"

#include "app/viewer/gl.h"
#include "app/viewer/screenshot.h"
#include "core/camera.h"
#include "core/level_of_detail.h"
#include "core/settings_io.h"

#include <backends/imgui_impl_opengl3.h>
#include <imgui.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <thread>

namespace slime {
namespace {

class Stopwatch {
 public:
  double milliseconds() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace

Viewer::Viewer(ViewerBackend& backend, const Settings& settings, ViewerOptions options)
    : backend_(backend),
      options_(std::move(options)),
      settings_(settings),
      draft_(settings),
      builtSlime_(settings.slime),
      simulation_(settings),
      renderer_(settings) {
  if (options_.scenario) scenario_.emplace(*options_.scenario);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // the same layout every run: tests click known places
  ImGui::StyleColorsDark();
  backend_.initImGuiPlatform();
  ImGui_ImplOpenGL3_Init("#version 330 core");
  metrics_ = simulation_.metrics();
}

Viewer::~Viewer() {
  ImGui_ImplOpenGL3_Shutdown();
  backend_.shutdownImGuiPlatform();
  ImGui::DestroyContext();
}

bool Viewer::frame() {
  const Stopwatch frameTime;
  const FrameInput input = readInput();
  handleInput(input);
  if (options_.maxFrames > 0 && stats_.frames + 1 >= options_.maxFrames) quit_ = true;
  if (quit_ && !options_.screenshotOnExit.empty()) requestScreenshot(options_.screenshotOnExit);
  // Physics runs beside the panels: this frame traces the slime as the last frame's steps left it,
  // then this frame's steps run on a second thread while the main thread draws the panels and
  // presents. The trace has both cores to itself; the panels are mostly one thread's work (measured:
  // 28.5 fps with the physics beside the trace, 29.6 beside the panels). So that nothing is shared
  // meanwhile, the steps hand back what they did (PhysicsOutcome) and the panels' requests wait;
  // both are applied after the join. A scenario's "set" events edit the settings the trace reads, so
  // with a scenario playing the steps run first, alone.
  refitSlime();
  const glm::dvec3 target = grabTargetFor();
  PanelRequests requests;
  if (scenario_ && !scenario_->finished()) {
    applyPhysicsOutcome(stepPhysics(input.elapsedSeconds, target));
    refitSlime();
    traceImage();
    uploadImage();
    requests = drawPanelsAndOverlay(grabbedCentre());
    present();
  } else {
    traceImage();
    uploadImage();
    const glm::dvec3 held = grabbedCentre();
    PhysicsOutcome outcome;
    std::thread physics([this, &input, &target, &outcome] { outcome = stepPhysics(input.elapsedSeconds, target); });
    requests = drawPanelsAndOverlay(held);
    present();
    physics.join();
    applyPhysicsOutcome(outcome);
  }
  applyPanelRequests(requests);
  stats_.recordStages(imageTraced_);
  stats_.recordFrame(frameTime.milliseconds());
  return !quit_;
}

int Viewer::run() {
  const auto start = std::chrono::steady_clock::now();
  while (frame()) {
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("slime view: %lld frames in %.1f s (%.1f fps), simulated %.2f s, %lld steps\n",
              static_cast<long long>(stats_.frames), seconds, seconds > 0.0 ? stats_.frames / seconds : 0.0,
              simulation_.time(), static_cast<long long>(simulation_.stepCount()));
  writeReport();
  return 0;
}

// --- input -----------------------------------------------------------------------------------------

FrameInput Viewer::readInput() {
  FrameInput input = backend_.pollInput();
  backend_.newImGuiPlatformFrame();
  ImGui_ImplOpenGL3_NewFrame();
  ImGui::NewFrame();
  const ImGuiIO& io = ImGui::GetIO();
  input.mouseCapturedByUi = io.WantCaptureMouse;
  input.keyboardCapturedByUi = io.WantCaptureKeyboard;
  wallClock_ += input.elapsedSeconds;
  return input;
}

void Viewer::handleInput(const FrameInput& input) {
  if (input.closeRequested || (input.escapePressed && !input.keyboardCapturedByUi)) quit_ = true;
  if (input.screenshotRequested)
    requestScreenshot(options_.screenshotPrefix + "-" + std::to_string(++screenshotCount_) + ".png");
  if (!input.keyboardCapturedByUi && cameraController_.applyKeys(input, settings_.camera)) {
    sceneChanged_ = true;
    lastInteraction_ = wallClock_;
  }
  for (const MouseButtonEvent& event : input.buttons) handleButton(event, input);

  const Camera camera = makeCamera(settings_.camera, input.windowSize.x, input.windowSize.y);
  double wheel = input.mouseCapturedByUi && !grab_.active() ? 0.0 : input.wheel;
  if (grab_.active()) {
    const glm::dvec3 before = grab_.target(camera, input.windowSize);
    grab_.moveCursor(input.cursor, input.shift, camera, input.windowSize);
    grab_.pressBy(wheel);  // the wheel presses while grabbing instead of zooming
    wheel = 0.0;
    if (grab_.target(camera, input.windowSize) != before) lastInteraction_ = wallClock_;
  }
  if (cameraController_.applyMouse(input.cursor, input.windowSize, wheel, slimeCentre(), settings_.camera)) {
    sceneChanged_ = true;
    lastInteraction_ = wallClock_;
  }
}

void Viewer::handleButton(const MouseButtonEvent& event, const FrameInput& input) {
  if (!event.pressed) {  // a release always ends what its press started, over a panel or not
    if (event.button == MouseButton::Left && grab_.active()) {
      grab_.end();
      simulation_.release();
    }
    cameraController_.handleButton(event);
    return;
  }
  if (input.mouseCapturedByUi) return;  // the press belongs to a panel
  if (event.button != MouseButton::Left) {
    cameraController_.handleButton(event);
    return;
  }
  // Grab: the surface point under the cursor, through the same camera the image is traced with.
  const glm::ivec2 size = input.windowSize;
  if (size.x <= 0 || size.y <= 0) return;
  const std::optional<glm::dvec3> hit =
      renderer_.pick(frameSettings(size), event.position.x / size.x, event.position.y / size.y);
  if (!hit) return;
  const double radius = GrabInteraction::kRadiusFraction * settings_.slime.radius;
  if (!simulation_.grab(*hit, radius)) return;
  grab_.begin(*hit, makeCamera(settings_.camera, size.x, size.y), event.position);
  grabTargetDrawn_ = *hit;
  ++grabCount_;
  heightAtGrab_ = metrics_.height;
  lastInteraction_ = wallClock_;
}

// --- physics ---------------------------------------------------------------------------------------

void Viewer::simulationAdvanced() {
  slimeMoved_ = true;
  metrics_ = simulation_.metrics();
}

glm::dvec3 Viewer::grabTargetFor() const {
  const glm::ivec2 size = backend_.windowSize();
  return grab_.active() && size.x > 0 && size.y > 0 ? grab_.target(makeCamera(settings_.camera, size.x, size.y), size)
                                                    : grabTargetDrawn_;
}

Viewer::PhysicsOutcome Viewer::stepPhysics(double wallSeconds, const glm::dvec3& target) {
  const Stopwatch physicsTime;
  PhysicsOutcome outcome;
  outcome.wallSeconds = wallSeconds;
  int steps = 0;
  if (settings_.sim.paused) {
    clock_.reset();
    steps = singleStepPending_ ? 1 : 0;
  } else {
    steps = clock_.stepsFor(wallSeconds, settings_.sim.timeScale, settings_.sim.dt);
  }
  singleStepPending_ = false;
  // Pull the grab target from where it was to where the cursor is now across this frame's steps, so
  // the slime is dragged smoothly however many steps a frame holds.
  int done = 0;
  for (; done < steps; ++done) {
    if (grab_.active()) {
      const double progress = static_cast<double>(done + 1) / steps;
      simulation_.dragTo(grabTargetDrawn_ + (target - grabTargetDrawn_) * progress);
    }
    if (scenario_ && !scenario_->finished()) {
      scenario_->advanceTo(simulation_.time(), simulation_, settings_);
      sceneChanged_ = true;  // a "set" event may have changed what is drawn
    }
    simulation_.step();
    if (physicsTime.milliseconds() > kPhysicsBudgetMs) {  // out of time: give up the rest of the backlog
      clock_.reset();
      ++done;
      break;
    }
  }
  outcome.steps = done;
  if (grab_.active() && done > 0) grabTargetDrawn_ = target;
  if (done > 0) outcome.metrics = simulation_.metrics();
  outcome.milliseconds = physicsTime.milliseconds();
  return outcome;
}

void Viewer::applyPhysicsOutcome(const PhysicsOutcome& outcome) {
  if (outcome.steps > 0) {
    slimeMoved_ = true;
    metrics_ = outcome.metrics;
    if (grab_.active()) peakHeightWhileGrabbing_ = std::max(peakHeightWhileGrabbing_, metrics_.height);
  }
  stats_.physicsSteps = outcome.steps;
  stats_.stages.physics = outcome.milliseconds;
  stats_.recordSimulatedTime(outcome.steps * settings_.sim.dt, outcome.wallSeconds);
}

// --- refit, trace, upload --------------------------------------------------------------------------

// The slime is drawn again when the scene changed anyway or its motion since it was last drawn
// would show (kInvisibleMotionPixels); slow creep is traced once it adds up.
void Viewer::refitSlime() {
  const Stopwatch refitTime;
  if (slimeMoved_ && (sceneChanged_ || motionWouldShow())) {
    renderer_.updateSlime(simulation_.positions(), simulation_.triangles());
    drawnPositions_ = simulation_.positions();
    slimeMoved_ = false;
    sceneChanged_ = true;
  }
  stats_.stages.refit = refitTime.milliseconds();
}

bool Viewer::motionWouldShow() const {
  const glm::ivec2 size = tracedImageSize();
  return size.y <= 0 || largestMotionPixels(drawnPositions_, simulation_.positions(), settings_.camera.position,
                                            settings_.camera.fov, size.y) >= kInvisibleMotionPixels;
}

glm::ivec2 Viewer::tracedImageSize() const {
  const glm::ivec2 framebuffer = backend_.framebufferSize();
  if (framebuffer.x <= 0 || framebuffer.y <= 0) return {0, 0};  // minimised: nothing to show
  // A coarser image while the user moves things keeps the window responsive; the full one when still.
  const double scale = settings_.render.scale * (interacting() ? kInteractiveScale : 1.0);
  return {std::max(1, static_cast<int>(std::lround(framebuffer.x * scale))),
          std::max(1, static_cast<int>(std::lround(framebuffer.y * scale)))};
}

void Viewer::traceImage() {
  imageTraced_ = false;
  const glm::ivec2 size = tracedImageSize();
  if (size.x <= 0) return;
  if (!sceneChanged_ && size == glm::ivec2(image_.width, image_.height)) return;  // nothing new to see
  const Stopwatch traceTime;
  image_.resize(size.x, size.y);
  const RenderStats render = renderer_.render(frameSettings(size), image_, &imageBytes_, /*buffersKept=*/true);
  stats_.stages.trace = traceTime.milliseconds();
  stats_.stages.refit += render.refitMs;
  stats_.rays = render.rays.total();
  stats_.megaraysPerSecond = render.traceMs > 0.0 ? static_cast<double>(stats_.rays) / (render.traceMs * 1e3) : 0.0;
  stats_.reusedFraction = static_cast<double>(render.reusedPixels) / (static_cast<double>(size.x) * size.y);
  stats_.traceThreads = render.threads;
  stats_.threadUse = render.traceMs > 0.0 && render.threads > 0 ? render.busyMs / (render.traceMs * render.threads) : 0.0;
  stats_.imageWidth = size.x;
  stats_.imageHeight = size.y;
  sceneChanged_ = false;
  imageTraced_ = true;
}

void Viewer::uploadImage() {
  const Stopwatch uploadTime;
  if (imageTraced_) blit_.upload(imageBytes_, image_.width, image_.height);
  stats_.stages.upload = uploadTime.milliseconds();
}

// --- panels ----------------------------------------------------------------------------------------

PanelRequests Viewer::drawPanelsAndOverlay(const glm::dvec3& heldCentre) {
  const Stopwatch uiTime;
  // The panels edit a draft; while an invalid edit is shown the draft keeps it, but the camera is
  // always the live one.
  if (editError_.empty()) draft_ = settings_;
  else draft_.camera = settings_.camera;
  const bool reloadPending = builtSlime_.level != settings_.slime.level || builtSlime_.radius != settings_.slime.radius;
  const PanelRequests requests =
      drawPanels(draft_, PanelView{stats_, metrics_, editError_, errorPanel_, reloadPending});

  // The grab spot: a ring at the grab target, a line from where the grabbed points are.
  const glm::ivec2 size = backend_.windowSize();
  if (grab_.active() && size.x > 0 && size.y > 0) {
    const Camera camera = makeCamera(settings_.camera, size.x, size.y);
    ImDrawList* overlay = ImGui::GetForegroundDrawList();
    const auto target = projectToWindow(camera, grab_.target(camera, size), size);
    const auto held = projectToWindow(camera, heldCentre, size);
    if (target && held)
      overlay->AddLine(ImVec2(float(held->x), float(held->y)), ImVec2(float(target->x), float(target->y)),
                       IM_COL32(255, 255, 255, 160), 1.5f);
    if (target) {
      overlay->AddCircle(ImVec2(float(target->x), float(target->y)), 9.0f, IM_COL32(255, 230, 80, 255), 24, 2.0f);
      overlay->AddCircleFilled(ImVec2(float(target->x), float(target->y)), 2.5f, IM_COL32(255, 230, 80, 255));
    }
  }
  ImGui::Render();
  stats_.stages.ui = uiTime.milliseconds();
  return requests;
}

void Viewer::applyPanelRequests(const PanelRequests& requests) {
  if (requests.edited != Panel::None) applyEdit(requests.edited);
  if (requests.reloadSlime) reloadSlime();
  if (requests.singleStep) singleStepPending_ = true;
}

void Viewer::applyEdit(Panel panel) {
  try {
    validateSettings(draft_);
  } catch (const SettingsError& error) {
    editError_ = error.what();  // shown in the panel; the settings keep their last valid value
    errorPanel_ = panel;
    return;
  }
  editError_.clear();
  errorPanel_ = Panel::None;
  settings_ = draft_;
  simulation_.applySettings(settings_);
  sceneChanged_ = true;
}

void Viewer::reloadSlime() {
  if (grab_.active()) grab_.end();
  simulation_.reload(settings_);
  builtSlime_ = settings_.slime;
  clock_.reset();
  slimeMoved_ = true;
  drawnPositions_.clear();  // a new mesh: draw it whatever it moved
  metrics_ = simulation_.metrics();
}

// --- present ---------------------------------------------------------------------------------------

void Viewer::present() {
  const Stopwatch presentTime;
  const glm::ivec2 framebuffer = backend_.framebufferSize();
  if (framebuffer.x > 0 && framebuffer.y > 0) {
    blit_.draw(framebuffer);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
    for (const std::string& path : screenshotPaths_) {
      writeFramebufferPng(framebuffer, path);
      std::printf("slime: wrote %s\n", path.c_str());
      screenshotsWritten_.push_back(path);
    }
    screenshotPaths_.clear();
  }
  backend_.present();
  stats_.stages.ui += presentTime.milliseconds();
}

// --- helpers ---------------------------------------------------------------------------------------

Settings Viewer::frameSettings(glm::ivec2 imageSize) const {
  Settings frame = settings_;
  frame.camera.width = imageSize.x;
  frame.camera.height = imageSize.y;
  return frame;
}

glm::dvec3 Viewer::grabbedCentre() const { return simulation_.grabbedPoint(); }

glm::dvec3 Viewer::slimeCentre() const {
  const std::vector<glm::dvec3>& positions = simulation_.positions();
  if (positions.empty()) return settings_.slime.position;
  glm::dvec3 sum(0.0);
  for (const glm::dvec3& position : positions) sum += position;
  return sum / static_cast<double>(positions.size());
}

void Viewer::writeReport() const {
  if (options_.reportPath.empty()) return;
  const glm::ivec2 framebuffer = backend_.framebufferSize();
  const StageTimes meanStages = stats_.meanStages();
  const nlohmann::json report = {
      {"frames", stats_.frames},
      {"fps", stats_.fps},
      {"mean_fps", stats_.meanFps()},
      {"median_frame_ms_recent", stats_.medianRecentFrameMs()},
      {"traced_frames", stats_.tracedFrames},
      {"mean_stage_ms",
       {{"physics", meanStages.physics}, {"refit", meanStages.refit}, {"trace", meanStages.trace},
        {"upload", meanStages.upload}, {"ui", meanStages.ui}}},
      {"framebuffer", {framebuffer.x, framebuffer.y}},
      {"simulated_seconds", simulation_.time()},
      {"steps", simulation_.stepCount()},
      {"dropped_seconds", clock_.droppedSeconds()},
      {"grabs", grabCount_},
      {"grabbing", grab_.active()},
      {"height_at_grab", heightAtGrab_},
      {"peak_height_while_grabbing", peakHeightWhileGrabbing_},
      {"metrics",
       {{"volume_ratio", metrics_.volumeRatio}, {"height", metrics_.height}, {"width", metrics_.width},
        {"aspect", metrics_.aspect}, {"min_z", metrics_.minZ}}},
      {"edit_error", editError_},
      {"screenshots", screenshotsWritten_},
      {"settings", settingsToJson(settings_)}};
  std::ofstream file(options_.reportPath);
  file << report.dump(2) << '\n';
  if (!file) std::fprintf(stderr, "slime view: cannot write %s\n", options_.reportPath.c_str());
}

}  // namespace slime
