// What the viewer reads and writes besides the frame: scene files (Ctrl+S, Ctrl+O) and the
// `--report` JSON at exit.
#include "app/viewer/viewer.h"

#include "app/bench/report/bench_report.h"
#include "app/viewer/panel_fields.h"
#include "core/settings/file_output.h"
#include "core/settings/settings_io.h"
#include "render/image/image_io.h"

#include <nlohmann/json.hpp>

#include <cstdio>

namespace slime {

void checkSettings(const Settings& settings, const Settings& current) {
  validateSettings(settings);
  if (settings.floor.pattern != "image" || settings.floor.image == current.floor.image) return;
  try {
    readPng(settings.floor.image);
  } catch (const std::exception& error) {
    throw SettingsError("floor.image: " + std::string(error.what()));
  }
}


Settings Viewer::sceneToSave() const {
  Settings scene = settings_;
  copyReloadFields(wanted_, scene);
  const glm::ivec2 window = backend_.windowSize();
  if (window.x > 0 && window.y > 0) scene.camera.width = window.x, scene.camera.height = window.y;
  return scene;
}

// Written whole or not at all (writeFileAtomically): a failed save leaves no half file.
void Viewer::saveScene() {
  try {
    writeFileAtomically(scenePath_, settingsToJson(sceneToSave()).dump(2) + "\n");
    fileMessage_ = "Saved " + scenePath_;
    fileFailed_ = false;
  } catch (const std::runtime_error& e) {
    fileMessage_ = std::string("Not saved: ") + e.what();
    fileFailed_ = true;
  }
  std::printf("slime: %s\n", fileMessage_.c_str());
}

// A scene file is applied over the default scene, as `--scene` does; anything wrong leaves the
// running scene as it was. The window keeps its size.
void Viewer::loadScene() {
  Settings loaded = defaultSettings();
  try {
    applySceneFile(loaded, scenePath_);
    loaded.camera.width = settings_.camera.width;
    loaded.camera.height = settings_.camera.height;
    checkSettings(loaded, Settings{});
  } catch (const SettingsError& error) {
    fileMessage_ = std::string("Not loaded: ") + error.what();
    fileFailed_ = true;
    std::printf("slime: %s\n", fileMessage_.c_str());
    return;
  }
  settings_ = wanted_ = built_ = draft_ = loaded;
  editError_.clear();
  errorGroup_.clear();
  fileMessage_ = "Loaded " + scenePath_;
  fileFailed_ = false;
  if (grab_.active()) grab_.end();
  simulation_.reload(settings_);
  clock_.reset();
  slimeMoved_ = true;
  sceneChanged_ = true;
  drawnPositions_.clear();
  landed_ = false;
  metrics_ = simulation_.metrics();
  std::printf("slime: %s\n", fileMessage_.c_str());
}

namespace {

nlohmann::json stagesJson(const StageTimes& stages) {
  return {{"physics", stages.physics}, {"refit", stages.refit}, {"trace", stages.trace},
          {"caustics", stages.caustics}, {"upload", stages.upload},
          {"ui", stages.ui}};
}

nlohmann::json summaryJson(const FrameSummary& summary) {
  return {{"frames", summary.frames},
          {"mean_fps", summary.meanFps},
          {"median_frame_ms", summary.medianFrameMs},
          {"mean_stage_ms", stagesJson(summary.meanStages)},
          {"traced_full_resolution_frames", summary.fullResolutionFrames},
          {"traced_reduced_resolution_frames", summary.reducedResolutionFrames}};
}

// Per phase (frame_log.h), after the first second: frames, their fps, and the median, 95th and 99th
// percentile and longest frame times.
nlohmann::json phasesJson(const std::vector<PhaseSummary>& phases) {
  nlohmann::json json = nlohmann::json::object();
  for (const PhaseSummary& phase : phases)
    json[nameOf(phase.phase)] = {{"frames", phase.frames},
                                 {"fps", phase.seconds > 0.0 ? static_cast<double>(phase.frames) / phase.seconds : 0.0},
                                 {"median_ms", phase.medianMs},
                                 {"p95_ms", phase.p95Ms},
                                 {"p99_ms", phase.p99Ms},
                                 {"longest_ms", phase.longestMs}};
  return json;
}

nlohmann::json psnrJson(const PsnrFigures& figures) {
  return {{"frames", figures.frames}, {"psnr_db", {{"mean", figures.meanDb()}, {"min", figures.minimumDb()}}}};
}

nlohmann::json vectorJson(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

nlohmann::json handsJson(const std::vector<HandView>& hands) {
  nlohmann::json list = nlohmann::json::array();
  for (const HandView& hand : hands)
    list.push_back({{"holding", hand.holding},
                    {"position", vectorJson(hand.position)},
                    {"target", vectorJson(hand.target)},
                    {"force", vectorJson(hand.force)},
                    {"piece", hand.piece}});
  return list;
}

// --screenshot-at: each picture's simulated time and each piece's volume and centroid's window pixel
// (null when behind the eye).
nlohmann::json timedScreenshotsJson(const std::vector<TimedScreenshot>& shots) {
  nlohmann::json list = nlohmann::json::array();
  for (const TimedScreenshot& shot : shots) {
    nlohmann::json pieces = nlohmann::json::array();
    for (std::size_t piece = 0; piece < shot.volumes.size(); ++piece) {
      const std::optional<glm::dvec2>& pixel = shot.windowPixels[piece];
      pieces.push_back({{"volume", shot.volumes[piece]},
                        {"window_pixel", pixel ? nlohmann::json{pixel->x, pixel->y} : nlohmann::json(nullptr)}});
    }
    list.push_back({{"path", shot.path}, {"simulated_s", shot.simulatedSeconds}, {"pieces", pieces}});
  }
  return list;
}

}  // namespace

void Viewer::writeReport() const {
  if (options_.reportPath.empty()) return;
  const glm::ivec2 framebuffer = backend_.framebufferSize();
  const nlohmann::json report = {
      {"machine", machineJson()},  // frame rates from two machines are not comparable
      {"frames", stats_.frames},
      {"fps", stats_.fps},
      {"mean_fps", stats_.meanFps()},
      {"median_frame_ms_recent", stats_.medianRecentFrameMs()},
      {"traced_frames", stats_.tracedFrames},
      {"traced_full_resolution_frames", stats_.fullResolutionFrames},
      {"traced_reduced_resolution_frames", stats_.reducedResolutionFrames},
      {"adaptive_resolution", {{"target_fps", resolution_.targetFps()}, {"scale", resolution_.scale()}}},
      {"orbit_resolution", {{"target_fps", orbitResolution_.targetFps()}, {"scale", orbitResolution_.scale()}}},
      {"while_grabbed", summaryJson(summarizeFrames(frameRecords_, [](const FrameRecord& frame) {
         return frame.grabbed;
       }))},
      {"mean_stage_ms", stagesJson(stats_.meanStages())},
      {"phases", phasesJson(summarizePhases(frameRecords_, 1.0))},
      {"framebuffer", {framebuffer.x, framebuffer.y}},
      {"simulated_seconds", simulation_.time()},
      {"steps", simulation_.stepCount()},
      {"dropped_seconds", clock_.droppedSeconds()},
      {"grabs", grabCount_},
      {"grabbing", simulation_.grabbing()},
      {"height_at_grab", heightAtGrab_},
      {"peak_height_while_grabbing", peakHeightWhileGrabbing_},
      // Two hands: the width when the session's first grab began (-1: no grab), the widest while both
      // held, and each hand now (position: its part of the surface; force on the body, N).
      {"width_before_grabs", widthBeforeGrabs_},
      {"peak_width_while_two_hands", peakWidthWhileTwoHands_},
      {"hands", handsJson(handViews())},
      // slime.tearing: the pieces at exit and the most at once, the tears and merges since the slime was
      // built, and the longest a frame's steps spent on them (ms).
      {"pieces", simulation_.pieceCount()},
      {"peak_pieces", peakPieces_},
      {"tears", simulation_.tears()},
      {"merges", simulation_.merges()},
      {"longest_topology_ms", longestTopologyMs_},
      {"metrics",
       {{"volume_ratio", metrics_.volumeRatio}, {"height", metrics_.height}, {"width", metrics_.width},
        {"aspect", metrics_.aspect}, {"min_z", metrics_.minZ}}},
      {"edit_error", editError_},
      {"edit_errors", editErrors_},
      {"file_message", fileMessage_},
      {"reload_pending", differingReloadFields(wanted_, built_)},
      {"screenshots", screenshotsWritten_},
      {"timed_screenshots", timedScreenshotsJson(timedScreenshots_)},
      // --check-every K: the shown images against full traces of the same state (image_check.h);
      // "frames" is 0 and the PSNRs 0 when no frame was checked. 100 dB: identical.
      {"check",
       {{"every", check_.every()},
        {"frames", check_.all().frames},
        {"psnr_db", {{"mean", check_.all().meanDb()}, {"min", check_.all().minimumDb()}}},
        {"while_handled", psnrJson(check_.handled())},
        {"skipped_refining_frames", check_.skippedRefined()},
        {"milliseconds", check_.milliseconds()}}},
      {"settings", settingsToJson(settings_)}};
  try {
    writeFileAtomically(options_.reportPath, report.dump(2) + "\n");
  } catch (const std::runtime_error& e) {
    std::fprintf(stderr, "slime view: %s\n", e.what());
  }
}

}  // namespace slime
