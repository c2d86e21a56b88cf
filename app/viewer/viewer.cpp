#include "app/viewer/viewer.h"

#include "app/viewer/gl.h"
#include "app/viewer/imgui_gl.h"
#include "app/viewer/panel_fields.h"
#include "app/viewer/screenshot.h"
#include "app/viewer/stopwatch.h"
#include "core/geometry/camera.h"
#include "core/geometry/level_of_detail.h"
#include "core/settings/settings_io.h"

#include <glm/geometric.hpp>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

namespace slime {
namespace {

// Every piece's drawn vertices into `out`, piece after piece: the order the renderer's one mesh has.
void drawnVertices(const Simulation& simulation, std::vector<glm::dvec3>& out) {
  out.clear();
  for (const SurfaceView& surface : simulation.surfaces())
    out.insert(out.end(), surface.positions.begin(), surface.positions.end());
}

}  // namespace

Viewer::Viewer(ViewerBackend& backend, const Settings& settings, ViewerOptions options)
    : backend_(backend),
      options_(std::move(options)),
      settings_(settings),
      draft_(settings),
      wanted_(settings),
      built_(settings),
      scenePath_(options_.scenePath),
      simulation_(settings),
      renderer_(settings),
      refinement_(options_.refineSamples > 1 ? std::max(options_.refineSamples, settings.render.spp) : 1),
      check_(options_.checkEvery) {
  if (options_.scenario) scenario_.emplace(*options_.scenario);
  // Caustics gathered over the frames as the image refines (a bounded budget while anything moves);
  // without refinement (snapshot --ui) the finished map at once, as `snapshot` draws it.
  renderer_.setProgressiveCaustics(options_.refineSamples > 1);
  if (options_.refineSamples > 1) renderer_.setCausticsFrameBudget(kCausticsBudgetMs);
  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // the same layout every run: tests click known places
  ImGui::StyleColorsDark();
  backend_.initImGuiPlatform();
  initImGuiGl();
  metrics_ = simulation_.metrics();
  columnWidth_ = panelColumnWidth(static_cast<float>(backend_.windowSize().x));
  followTargetFps();
  if (keepsFrameRecords() && options_.maxFrames > 0) frameRecords_.reserve(options_.maxFrames);
}

Viewer::~Viewer() {
  shutdownImGuiGl();
  backend_.shutdownImGuiPlatform();
  ImGui::DestroyContext();
}

bool Viewer::frame() {
  const Stopwatch frameTime;
  const FrameInput input = readInput();
  handleInput(input);
  requestTimedScreenshots();
  if (options_.maxFrames > 0 && stats_.frames + 1 >= options_.maxFrames) quit_ = true;
  if (options_.quitAtSimulatedSeconds > 0.0 && simulation_.time() >= options_.quitAtSimulatedSeconds) quit_ = true;
  if (options_.quitAtWallSeconds > 0.0 && stats_.totalFrameMs >= 1000.0 * options_.quitAtWallSeconds) quit_ = true;
  if (quit_ && !options_.screenshotOnExit.empty()) requestScreenshot(options_.screenshotOnExit);
  // Physics runs on a second thread, never in series with the frame's other work: this frame traces
  // the slime as the last frame's steps left it (refit first, into the renderer's own buffers), while
  // this frame's steps run beside it. Where the steps take no longer than the upload, panels and
  // present (a fast processor, or a light slime), they start after the trace instead, so the trace
  // has both cores to itself (measured on AMD family 26: 28.5 fps beside the trace, 29.6 beside the
  // panels); where they take longer (issue 28, AMD family 23/25: physics 18 ms against 3 ms of
  // panels), they start with the trace and the two share the cores. So that nothing is shared
  // meanwhile, the steps hand back what they did (PhysicsOutcome) and the panels' requests wait;
  // both are applied after the join. A scenario's "set" events edit the settings the trace reads,
  // so while one is still to come the steps run first, alone; a scenario's grabs and drags run on
  // the second thread, as the mouse's do.
  refitSlime();
  const glm::dvec3 target = grabTargetFor();
  PanelRequests requests;
  double checkMs = 0.0;
  if (scenarioSetPending()) {
    applyPhysicsOutcome(stepPhysics(input.elapsedSeconds, target));
    refitSlime();
    keepCheckState();
    traceImage();
    checkMs = checkImage();
    uploadImage();
    requests = drawPanelsAndOverlay(grabMarks());
    present();
  } else {
    const GrabMarks marks = grabMarks();
    keepCheckState();
    PhysicsOutcome outcome;
    const auto steps = [this, &input, &target, &outcome] { outcome = stepPhysics(input.elapsedSeconds, target); };
    std::thread physics;
    const bool besideTrace = physicsBesideTrace();
    if (besideTrace) physics = std::thread(steps);
    traceImage();
    checkMs = checkImage();
    if (!besideTrace) physics = std::thread(steps);
    uploadImage();
    requests = drawPanelsAndOverlay(marks);
    present();
    physics.join();
    applyPhysicsOutcome(outcome);
  }
  applyPanelRequests(requests);
  if (!rendered_ && !quit_) backend_.waitForInput(kIdleFrameSeconds - frameTime.milliseconds() / 1000.0);
  finishFrame(frameTime.milliseconds() - checkMs);
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
  if (!options_.frameLogPath.empty()) {
    if (!writeFrameLogCsv(frameRecords_, options_.frameLogPath)) {
      std::fprintf(stderr, "slime view: cannot write the frame log %s\n", options_.frameLogPath.c_str());
      return 1;
    }
    std::printf("slime view: wrote %s (%zu frames)\n", options_.frameLogPath.c_str(), frameRecords_.size());
  }
  return 0;
}

// The frame traces the slime as the last frame's steps left it, at the time the frame starts with.
void Viewer::requestTimedScreenshots() {
  const std::vector<double>& times = options_.screenshotTimes;
  const glm::ivec2 size = viewSize();
  while (timedScreenshots_.size() < times.size() && simulation_.time() + 1e-9 >= times[timedScreenshots_.size()]) {
    TimedScreenshot shot;
    shot.path = options_.screenshotPrefix + "-" + std::to_string(++screenshotCount_) + ".png";
    shot.simulatedSeconds = simulation_.time();
    const Camera camera = makeCamera(settings_.camera, std::max(size.x, 1), std::max(size.y, 1));
    for (const EnclosedSolid& solid : simulation_.pieceSolids()) {
      shot.volumes.push_back(solid.volume);
      std::optional<glm::dvec2> pixel = projectToWindow(camera, solid.centroid, size);
      if (pixel) pixel->x += std::lround(columnWidth_);
      shot.windowPixels.push_back(pixel);
    }
    requestScreenshot(shot.path);
    timedScreenshots_.push_back(std::move(shot));
  }
}

// --- input -----------------------------------------------------------------------------------------

FrameInput Viewer::readInput() {
  FrameInput input = backend_.pollInput();
  // The last frame's check is not the user's time: the physics and the clocks do not see it.
  input.elapsedSeconds = std::max(0.0, input.elapsedSeconds - checkSecondsToSkip_);
  checkSecondsToSkip_ = 0.0;
  toViewCoordinates(input);
  backend_.newImGuiPlatformFrame();
  newImGuiGlFrame();
  ImGui::NewFrame();
  const ImGuiIO& io = ImGui::GetIO();
  input.mouseCapturedByUi = io.WantCaptureMouse;
  input.keyboardCapturedByUi = io.WantCaptureKeyboard;
  wallClock_ += input.elapsedSeconds;
  return input;
}

void Viewer::handleInput(const FrameInput& input) {
  cameraMoved_ = false;
  if (input.closeRequested || (input.escapePressed && !input.keyboardCapturedByUi)) quit_ = true;
  if (input.screenshotRequested)
    requestScreenshot(options_.screenshotPrefix + "-" + std::to_string(++screenshotCount_) + ".png");
  if (input.helpKey == HelpKey::F1 || (input.helpKey == HelpKey::H && !input.keyboardCapturedByUi)) showHelp_ = !showHelp_;
  if (input.saveRequested) saveScene();
  if (input.loadRequested) loadScene();
  if (!input.keyboardCapturedByUi && cameraController_.applyKeys(input, settings_.camera)) {
    sceneChanged_ = cameraMoved_ = true;
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
    sceneChanged_ = cameraMoved_ = true;
    lastInteraction_ = wallClock_;
  }
  if (options_.scenario) {  // its orbits turn the camera as a right-drag would, by simulated time
    const glm::dvec2 orbit = orbitAt(*options_.scenario, simulation_.time());
    if (orbit != orbitApplied_) {
      CameraController::orbit(orbit.x - orbitApplied_.x, orbit.y - orbitApplied_.y, slimeCentre(), settings_.camera);
      orbitApplied_ = orbit;
      sceneChanged_ = cameraMoved_ = true;
      lastInteraction_ = wallClock_;
    }
  }
}

void Viewer::handleButton(const MouseButtonEvent& event, const FrameInput& input) {
  if (!event.pressed) {  // a release always ends what its press started, over a panel or not
    if (event.button == MouseButton::Left && grab_.active()) {
      grab_.end();
      // The second hand stays where the drag left it, holding, until Ctrl+click off the slime or
      // the Hands section's release button lets it go.
      if (cursorHand_ == 0) simulation_.release(0);
    }
    cameraController_.handleButton(event);
    return;
  }
  if (input.mouseCapturedByUi) return;  // the press belongs to a panel
  if (event.button != MouseButton::Left) {
    cameraController_.handleButton(event);
    return;
  }
  if (grab_.active()) return;  // one cursor moves one hand at a time
  // Grab: the surface point under the cursor, through the same camera the image is traced with.
  // Left: hand 0; Ctrl+left: hand 1, which keeps holding after the button is released.
  const int hand = event.control ? 1 : 0;
  const glm::ivec2 size = input.windowSize;
  if (size.x <= 0 || size.y <= 0) return;
  const std::optional<glm::dvec3> hit =
      renderer_.pick(frameSettings(size), event.position.x / size.x, event.position.y / size.y);
  if (!hit) {
    if (hand == 1) simulation_.release(1);  // Ctrl+click off the slime lets the second hand go
    return;
  }
  const double radius = GrabInteraction::kRadiusFraction * settings_.slime.radius;
  if (!simulation_.grab(*hit, radius, hand)) return;
  cursorHand_ = hand;
  grab_.begin(*hit, makeCamera(settings_.camera, size.x, size.y), event.position);
  grabTargetDrawn_[hand] = *hit;
  ++grabCount_;
  heightAtGrab_ = metrics_.height;
  if (widthBeforeGrabs_ < 0.0) widthBeforeGrabs_ = metrics_.width;
  lastInteraction_ = wallClock_;
}

// --- refit, trace, upload --------------------------------------------------------------------------

// The slime is drawn again when the scene changed anyway or its motion since it was last drawn would
// show (kStillMotionPixels). drawnPositions_ is the state the image shows, the one its refinement
// started from: creep is measured against it, not against the last frame, so it cannot add up unseen;
// once it crosses the threshold the slime is traced again, in its footprint (its shadow and caustic
// included; the rest of the image is copied: RenderStats::reusedPixels), and the refinement restarts.
// With pieces (slime.tearing) every piece's vertices are compared, piece after piece: a piece that moves
// alone is drawn, and a tear or a merge (the vertex count changes) always is.
void Viewer::refitSlime() {
  const Stopwatch refitTime;
  if (slimeMoved_) {
    // One piece (the slime untorn) is compared where it lies, without a copy each frame.
    const bool onePiece = simulation_.pieceCount() == 1;
    if (!onePiece) drawnVertices(simulation_, positionsNow_);
    const std::vector<glm::dvec3>& now = onePiece ? simulation_.positions() : positionsNow_;
    if (sceneChanged_ || motionWouldShow(now)) {
      renderer_.updateSlime(simulation_.surfaces());
      if (onePiece) drawnPositions_ = now;
      else drawnPositions_.swap(positionsNow_);
      slimeMoved_ = false;
      sceneChanged_ = true;
    }
  }
  stats_.stages.refit = refitTime.milliseconds();
}

bool Viewer::motionWouldShow(const std::vector<glm::dvec3>& now) const {
  const glm::ivec2 size = tracedImageSize();
  return size.y <= 0 || largestMotionPixels(drawnPositions_, now, settings_.camera.position, settings_.camera.fov,
                                            size.y) >= kStillMotionPixels;
}

glm::ivec2 Viewer::fullImageSize() const {
  const glm::ivec2 view = viewSize(), window = backend_.windowSize();
  const glm::ivec2 full = backend_.framebufferSize();
  if (full.x <= 0 || full.y <= 0 || view.x <= 0 || window.x <= 0) return {0, 0};  // minimised: nothing to show
  return {full.x * view.x / window.x, full.y};
}

glm::ivec2 Viewer::tracedImageSize() const {
  const glm::ivec2 full = fullImageSize();
  if (full.x <= 0) return {0, 0};
  // Full resolution while the user moves things too (issue 15). render.scale is the user's own choice;
  // the adaptive factor is the fallback for frames over their budget, 1 unless a target is set. While
  // the camera moves, every pixel changes and the every-pixel frame (60–70 ms at 1280×720 on AMD
  // family 23) misses 30 fps: render.orbitFps's own factor then (traced at half the size, the shown
  // frames stay at 37 dB or more against the full trace; docs/performance.md, viewer section), and
  // full resolution the frame the camera stops.
  const double scale = settings_.render.scale * frameResolution().scale();
  if (scale >= 1.0) return full;
  return {std::max(1, static_cast<int>(std::lround(full.x * scale))),
          std::max(1, static_cast<int>(std::lround(full.y * scale)))};
}

void Viewer::traceImage() {
  imageTraced_ = newImageTraced_ = rendered_ = false;
  tracedRows_ = 0;
  const glm::ivec2 size = tracedImageSize();
  tracedAtFullSize_ = size == fullImageSize();
  if (size.x <= 0) return;
  const Stopwatch traceTime;
  if (!sceneChanged_ && size == glm::ivec2(image_.width, image_.height)) {  // nothing new: refine it
    imageTraced_ = refineImage(size);
    if (rendered_) stats_.stages.trace = traceTime.milliseconds();
    stats_.samplesPerPixel = std::max(1, refinement_.samples());
    return;
  }
  refinement_.reset();
  sampleRow_ = 0;
  framesSinceNewImage_ = 0;
  stats_.samplesPerPixel = 1;
  image_.resize(size.x, size.y);
  // image_ and imageBytes_ hold the last render()'s pixels (a refinement's average is kept apart), so
  // the pixels the slime cannot have changed stay as they are.
  const RenderStats render = renderer_.render(frameSettings(size), image_, &imageBytes_, /*buffersKept=*/true);
  rendered_ = true;
  tracedRows_ = size.y;
  imageChanged_ = showingAverage_ ? PixelRect{0, 0, size.x, size.y} : render.bytesWritten;  // the window showed the average
  showingAverage_ = false;
  stats_.stages.trace = traceTime.milliseconds();
  stats_.stages.caustics = render.causticsMs;
  stats_.causticPhotons = render.causticPhotons;
  stats_.rays = render.rays.total();
  stats_.megaraysPerSecond = render.traceMs > 0.0 ? static_cast<double>(stats_.rays) / (render.traceMs * 1e3) : 0.0;
  stats_.reusedFraction = static_cast<double>(render.reusedPixels) / (static_cast<double>(size.x) * size.y);
  stats_.traceThreads = render.threads;
  stats_.threadUse = render.traceMs > 0.0 && render.threads > 0 ? render.busyMs / (render.traceMs * render.threads) : 0.0;
  stats_.imageWidth = size.x;
  stats_.imageHeight = size.y;
  stats_.renderScale = static_cast<double>(size.y) / fullImageSize().y;
  sceneChanged_ = false;
  imageTraced_ = newImageTraced_ = true;
}

// Progressive anti-aliasing: once nothing has moved for kRefineAfterSeconds, the image is traced once
// more at another point of every pixel, and again, until ViewerOptions::refineSamples are averaged; any
// change (camera, slime, settings, size) resets it in traceImage. Each sample is traced a band of rows
// per frame (refineBandRows) and added once whole. Supersampled settings (render.spp > 1) already
// average their own samples.
bool Viewer::refineImage(glm::ivec2 size) {
  // Nothing may have moved lately: the user for kRefineAfterSeconds, the slime for kStillFramesBeforeRefining
  // frames. A slime creeping past the redraw threshold every other frame would otherwise alternate a
  // footprint frame with refinement bands that its next move throws away.
  framesSinceNewImage_ = std::min(framesSinceNewImage_ + 1, kStillFramesBeforeRefining);
  if (framesSinceNewImage_ < kStillFramesBeforeRefining) return false;
  if (refinement_.target() != refineTarget()) refinement_.setTarget(refineTarget());  // render.spp edited
  if (interacting() || refinement_.converged()) return false;
  if (frameResolution().scale() < 1.0) return false;  // the adaptive resolution returns to full first
  if (sampleRow_ == 0) sampleImage_.resize(size.x, size.y);
  const int rows = std::min(refineBandRows(size.y), size.y - sampleRow_);
  const RenderStats render =
      renderer_.renderRows(frameSettings(size), sampleImage_, refinement_.nextOffset(), sampleRow_, sampleRow_ + rows);
  rendered_ = true;
  tracedRows_ = rows;
  stats_.stages.caustics = render.causticsMs;
  stats_.causticPhotons = render.causticPhotons;
  // The band's cost, for the next samples' bands: a sample's first band sets up (the caustic photons,
  // the footprint, the grids) and the later ones reuse it; the rows' cost is kept per block of
  // kRefineBandRowStep rows, as rows through the slime cost several times those of the floor or sky.
  constexpr double kWeight = 0.3;
  if (sampleRow_ == 0)
    firstBandSetupMs_ = firstBandSetupMs_ < 0.0 ? render.setupMs : (1.0 - kWeight) * firstBandSetupMs_ + kWeight * render.setupMs;
  const double blockMs = std::max(0.0, render.traceMs - render.setupMs) * kRefineBandRowStep / rows;
  for (int row = sampleRow_; row < sampleRow_ + rows; row += kRefineBandRowStep) blockMs_[row / kRefineBandRowStep] = blockMs;
  sampleRow_ += rows;
  if (sampleRow_ < size.y) return false;  // the sample is not whole yet: the image shown stays
  sampleRow_ = 0;
  imageChanged_ = {0, 0, size.x, size.y};  // the average of every pixel
  const bool shown = refinement_.add(sampleImage_, averageImage_, &averageBytes_);
  showingAverage_ = showingAverage_ || shown;
  return shown;
}

int Viewer::refineBandRows(int height) {
  const int step = kRefineBandRowStep;
  const int blocks = (height + step - 1) / step;
  if (static_cast<int>(blockMs_.size()) != blocks) blockMs_.assign(blocks, -1.0);
  const int half = std::max(step, (height / 2) / step * step);  // never the whole sample in one frame
  const int first = sampleRow_ / step;
  if (blockMs_[first] < 0.0) return std::min(half, std::max(step, (height / 8) / step * step));  // not yet measured
  double budget = options_.refineBandMs - (sampleRow_ == 0 ? std::max(0.0, firstBandSetupMs_) : 0.0);
  int rows = step;
  budget -= blockMs_[first];
  for (int block = first + 1; block < blocks && rows < half && blockMs_[block] >= 0.0 && blockMs_[block] <= budget; ++block) {
    budget -= blockMs_[block];
    rows += step;
  }
  return rows;
}

// The image this frame shows (traced now or kept from an earlier frame) against the full trace of the
// physics state the frame stands for, with the camera in force (image_check.h).
bool Viewer::physicsBesideTrace() const {
  return stats_.stages.physics > stats_.stages.upload + stats_.stages.ui;
}

void Viewer::keepCheckState() {
  checkStateKept_ = check_.due(stats_.frames);
  if (!checkStateKept_) return;
  const std::vector<SurfaceView>& surfaces = simulation_.surfaces();
  checkPieces_.resize(surfaces.size());
  for (std::size_t piece = 0; piece < surfaces.size(); ++piece) {
    checkPieces_[piece].positions.assign(surfaces[piece].positions.begin(), surfaces[piece].positions.end());
    checkPieces_[piece].triangles.assign(surfaces[piece].triangles.begin(), surfaces[piece].triangles.end());
  }
  checkHandled_ = simulation_.anyGrabbing();
}

double Viewer::checkImage() {
  framePsnrDb_ = -1.0;
  if (!checkStateKept_) return 0.0;
  const glm::ivec2 full = fullImageSize();
  const std::vector<std::uint8_t>& shown = shownBytes();
  if (full.x <= 0 || image_.width <= 0 || shown.size() != 4 * image_.pixels.size()) return 0.0;
  // A still image part-way through its refinement averages several points of each pixel: neither the
  // one-sample nor the refined reference. Once refined fully it is the render.spp = target image.
  Settings reference = frameSettings(full);
  const int samples = refinement_.samples();
  if (samples > 1 && !refinement_.converged()) {
    check_.skipRefined();
    return 0.0;
  }
  if (samples > 1) reference.render.spp = refinement_.target();
  const double before = check_.milliseconds();
  const std::vector<SurfaceView> pieces(checkPieces_.begin(), checkPieces_.end());
  framePsnrDb_ = check_.check(reference, pieces, shown, image_.width, image_.height, checkHandled_);
  const double spent = check_.milliseconds() - before;
  checkSecondsToSkip_ = spent / 1000.0;
  return spent;
}

void Viewer::uploadImage() {
  const Stopwatch uploadTime;
  if (imageTraced_) compositor_.upload(shownBytes(), image_.width, image_.height, imageChanged_);
  stats_.stages.upload = uploadTime.milliseconds();
}

void Viewer::followTargetFps() {
  if (settings_.render.orbitFps != orbitResolution_.targetFps()) orbitResolution_.setTargetFps(settings_.render.orbitFps);
  if (settings_.render.targetFps == resolution_.targetFps()) return;
  resolution_.setTargetFps(settings_.render.targetFps);
  stats_.targetFps = resolution_.targetFps();
}

void Viewer::finishFrame(double frameMs) {
  stats_.tracedRows = tracedRows_;
  stats_.recordStages(imageTraced_, tracedAtFullSize_);
  stats_.recordFrame(frameMs);
  frameResolution().update(frameMs, newImageTraced_ ? stats_.stages.trace : 0.0, newImageTraced_);
  if (!keepsFrameRecords()) return;
  FrameRecord record;
  record.endSeconds = stats_.totalFrameMs / 1000.0;
  record.frameMs = frameMs;
  record.stages = stats_.stages;
  if (!imageTraced_ && tracedRows_ == 0) record.stages.trace = record.stages.refit = record.stages.caustics = 0.0;
  record.causticPhotons = stats_.causticPhotons;
  record.tracedRows = tracedRows_;
  record.phase = framePhase();
  record.traced = imageTraced_;
  record.fullResolution = imageTraced_ && tracedAtFullSize_;
  record.imageWidth = image_.width;
  record.imageHeight = image_.height;
  record.scale = stats_.renderScale;
  record.grabbed = simulation_.anyGrabbing();
  record.simulatedSeconds = simulation_.time();
  record.checkPsnrDb = framePsnrDb_;
  record.pieces = static_cast<int>(simulation_.pieceCount());
  record.tears = simulation_.tears();
  record.merges = simulation_.merges();
  record.topologyMs = topologyMs_;
  frameRecords_.push_back(record);
}

FramePhase Viewer::framePhase() const {
  if (simulation_.grabbing(0) && simulation_.grabbing(1)) return FramePhase::Stretched;
  if (simulation_.anyGrabbing()) return FramePhase::Held;
  if (cameraMoved_) return FramePhase::Orbiting;
  const std::int64_t frame = stats_.frames - 1;  // this one's index: finishFrame has counted it
  if (frame == editedFrame_ || frame == editDrawnFrame_) return FramePhase::Editing;
  if (!landed_) return FramePhase::Falling;
  // The fastest point's speed on screen, at the slime's distance.
  const glm::ivec2 size = fullImageSize();
  const double distance = glm::length(settings_.camera.position - slimeCentre());
  if (size.y <= 0 || !(distance > 0.0)) return FramePhase::Resting;
  const double pixelsPerSecond = metrics_.maxSpeed * pixelsPerMetre(distance, settings_.camera.fov, size.y);
  if (pixelsPerSecond >= kSettlingPixelsPerSecond) return FramePhase::Settling;
  if (pixelsPerSecond > kStillMotionPixels) return FramePhase::Creeping;
  return FramePhase::Resting;
}

// --- present ---------------------------------------------------------------------------------------

void Viewer::present() {
  const Stopwatch presentTime;
  const glm::ivec2 framebuffer = backend_.framebufferSize();
  static const std::vector<PixelRect> kNothingDrawn;
  const std::vector<PixelRect>* presented = &kNothingDrawn;
  if (framebuffer.x > 0 && framebuffer.y > 0) {
    const glm::ivec2 window = backend_.windowSize();
    const int left = window.x > 0 ? static_cast<int>(std::lround(columnWidth_ * framebuffer.x / window.x)) : 0;
    // What changed since the last frame, or everything where the back-end does not keep the pixels.
    presented = &compositor_.draw(*ImGui::GetDrawData(), framebuffer, left, !backend_.keepsFramebuffer());
    for (const std::string& path : screenshotPaths_) {
      writeFramebufferPng(framebuffer, path);
      std::printf("slime: wrote %s\n", path.c_str());
      screenshotsWritten_.push_back(path);
    }
    screenshotPaths_.clear();
  }
  backend_.present(*presented);
  stats_.stages.ui += presentTime.milliseconds();
}

// --- helpers ---------------------------------------------------------------------------------------

glm::ivec2 Viewer::viewSize() const {
  const glm::ivec2 window = backend_.windowSize();
  return {std::max(0, window.x - static_cast<int>(std::lround(columnWidth_))), window.y};
}

void Viewer::toViewCoordinates(FrameInput& input) const {
  const double left = std::lround(columnWidth_);
  input.cursor.x -= left;
  for (MouseButtonEvent& event : input.buttons) event.position.x -= left;
  input.windowSize = viewSize();
}

Settings Viewer::frameSettings(glm::ivec2 imageSize) const {
  Settings frame = settings_;
  frame.camera.width = imageSize.x;
  frame.camera.height = imageSize.y;
  // A refining viewer traces one sample a frame and reaches render.spp's samples by refining (the
  // still image's refineTarget); tracing them all in one frame took seconds at 64.
  if (options_.refineSamples > 1) frame.render.spp = 1;
  return frame;
}

int Viewer::refineTarget() const {
  return options_.refineSamples > 1 ? std::max(options_.refineSamples, settings_.render.spp) : 1;
}

glm::dvec3 Viewer::grabbedCentre() const { return simulation_.grabbedPoint(cursorHand_); }

glm::dvec3 Viewer::slimeCentre() const {
  glm::dvec3 sum(0.0);
  std::size_t count = 0;
  for (const SurfaceView& surface : simulation_.surfaces()) {
    for (const glm::dvec3& position : surface.positions) sum += position;
    count += surface.positions.size();
  }
  return count == 0 ? settings_.slime.position : sum / static_cast<double>(count);
}

}  // namespace slime
