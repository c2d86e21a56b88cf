// The interactive viewer: the ray-traced slime with Dear ImGui panels over it. One frame is a list of
// named steps — input → refit → trace → upload → panels → present, with the physics steps on a
// second thread beside the panels and present — run the same way in a GLFW window and headless (the
// ViewerBackend seam), so `snapshot --ui` shows what the window shows.
//
// Ordering that matters: ImGui's frame starts before the input step so that io.WantCaptureMouse/
// Keyboard can hide input the panels take; panel edits land in the settings at the end of a frame
// and take effect from the next one.
#pragma once

#include "app/viewer/adaptive_resolution.h"
#include "app/viewer/camera_controller.h"
#include "app/viewer/frame_compositor.h"
#include "app/viewer/frame_log.h"
#include "app/viewer/frame_stats.h"
#include "app/viewer/image_check.h"
#include "app/viewer/interaction.h"
#include "app/viewer/panels.h"
#include "app/viewer/physics_clock.h"
#include "app/viewer/viewer_backend.h"
#include "core/simulation/scenario.h"
#include "core/settings/settings.h"
#include "core/simulation/simulation.h"
#include "render/trace/accumulation_buffer.h"
#include "render/trace/renderer.h"

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <optional>
#include <string>
#include <vector>

namespace slime {

struct ViewerOptions {
  int maxFrames = 0;                                // quit after this many frames; 0 = until Esc
  double quitAtSimulatedSeconds = 0.0;              // quit once the simulation reaches this time; 0 = never
  double quitAtWallSeconds = 0.0;                   // ... or once the frames have taken this long; 0 = never
  std::string screenshotOnExit;                     // PNG of the last frame, if set
  std::string reportPath;                           // JSON summary written at exit, if set
  std::string frameLogPath;                         // CSV of every frame (frame_log.h) at exit, if set
  std::string screenshotPrefix = "slime-screenshot";  // F12 writes <prefix>-<n>.png
  // ... and so does the first frame that starts at or after each of these simulated times (seconds, ascending):
  // a scenario's moments, whatever the machine's speed. The report lists them with each piece's centroid's
  // window pixel (timed_screenshots), so a script can look for every piece in the picture.
  std::vector<double> screenshotTimes;
  std::optional<Scenario> scenario;                 // timed grab/drag/press/set events to replay
  std::string scenePath = "slime-scene.json";       // where Ctrl+S saves and Ctrl+O loads (panel field)
  int refineSamples = 16;  // samples per pixel a still image accumulates (1: none, as `snapshot` shows it)
  int checkEvery = 0;      // every K-th frame, the image shown against a full trace (image_check.h); 0: never
  double refineBandMs = 14.0;  // wall time a frame may spend on a band of a refinement sample (Viewer::refineBandRows)
};

// A screenshot of ViewerOptions::screenshotTimes, as the report lists it.
struct TimedScreenshot {
  std::string path;
  double simulatedSeconds = 0.0;
  std::vector<double> volumes;                          // per piece, m³
  std::vector<std::optional<glm::dvec2>> windowPixels;  // per piece, its centroid in the window; empty: behind the eye
};

// validateSettings, and what only the renderer finds out: that a floor image can be read
// (`current`: the settings in force, whose image is known to be readable). Throws SettingsError.
void checkSettings(const Settings& settings, const Settings& current);

class Viewer {
 public:
  static constexpr double kRefineAfterSeconds = 0.25;  // stillness before the image starts refining
  // ... and frames with no new image before it does: a creeping slime that crosses the redraw threshold
  // every other or every third frame is redrawn in its footprint, not refined in whole between its moves.
  static constexpr int kStillFramesBeforeRefining = 3;
  // A frame that traced nothing new (the scene still, the image refined) lasts at least this long
  // unless input arrives: a still window shows 60 frames a second, not as many as a core can draw.
  static constexpr double kIdleFrameSeconds = 1.0 / 60.0;
  // Wall time physics may take per frame: the steps left when it runs out are given back to the clock
  // and run in the next frames' slices (PhysicsClock::giveBack), so no frame waits on a long physics
  // step (35–41 ms in single frames before). The steps run beside the trace, whose own frame is
  // about this long while the slime moves. When steps cost more than real time allows, the slime runs
  // slower than real time (the Stats panel says how much) instead of the window freezing.
  static constexpr double kPhysicsBudgetMs = 20.0;
  // A still image's refinement sample is traced a band of rows per frame, as many as the last bands'
  // cost predicts to fit ViewerOptions::refineBandMs, at most half the image, so a whole-image sample
  // (about 60 ms at 1280×720 on two cores) is spread over several frames.
  static constexpr int kRefineBandRowStep = 8;  // bands are multiples of the renderer's tile rows
  // Wall time a frame may spend tracing caustic photons (Caustics::setFrameBudget): the default 10,000
  // photons fit (about 10 ms on AMD family 25); render.photons up to 10⁷ would take seconds a frame,
  // and are gathered over more frames instead.
  static constexpr double kCausticsBudgetMs = 12.0;

  Viewer(ViewerBackend& backend, const Settings& settings, ViewerOptions options = {});
  ~Viewer();
  Viewer(const Viewer&) = delete;
  Viewer& operator=(const Viewer&) = delete;

  // Runs one frame; false once the user has asked to quit (Esc, window closed, --frames reached).
  bool frame();

  // Frames until quit; writes the report; returns the exit code.
  int run();

  // The next frame also writes its picture (image and panels) to `path`.
  void requestScreenshot(const std::string& path) { screenshotPaths_.push_back(path); }

  Simulation& simulation() { return simulation_; }
  // Call after advancing simulation() from outside the frame loop, so the next frame draws it.
  void simulationAdvanced();
  const Settings& settings() const { return settings_; }
  const FrameStats& stats() const { return stats_; }
  // Every frame's record so far (kept when a frame log or a report is asked for).
  const std::vector<FrameRecord>& frameRecords() const { return frameRecords_; }

  // The scene as the panels show it (rebuild-type values waiting for Reload included), with the
  // window's size as the image size: what Ctrl+S saves.
  Settings sceneToSave() const;

 private:
  // The frame's steps, in order.
  FrameInput readInput();
  void handleInput(const FrameInput& input);
  // The grab target of the hand the cursor moves (cursorHand_) for this frame's steps, read from the
  // window on the main thread.
  glm::dvec3 grabTargetFor() const;
  // What a frame's steps did, handed back from the physics thread and applied after it joined.
  struct PhysicsOutcome {
    int steps = 0;
    double milliseconds = 0.0;
    double wallSeconds = 0.0;     // the frame time the steps were for
    SlimeMetrics metrics;         // after the steps, if there were any
    bool grabbing = false;        // the slime is held (by the mouse or the scenario) after the steps
    bool twoHands = false;        // ... by both hands
    int scenarioGrabs = 0;        // the scenario's grabs and presses that took hold during the steps
    double heightAtGrab = 0.0;    // the slime's height when the last of them took hold
    bool settingsEdited = false;  // a scenario "set" event fired
    double topologyMs = 0.0;      // spent on the tears and merges among the steps (slime.tearing)
  };
  PhysicsOutcome stepPhysics(double wallSeconds, const glm::dvec3& target);  // touches simulation_ only
  void playScenarioAt(double time, PhysicsOutcome& outcome);
  bool scenarioSetPending() const;  // a "set" event of the scenario is still to come
  void applyPhysicsOutcome(const PhysicsOutcome& outcome);
  void refitSlime();
  // The slime moved visibly since it was last drawn: `now` (every piece's drawn vertices) against drawnPositions_.
  bool motionWouldShow(const std::vector<glm::dvec3>& now) const;
  glm::ivec2 fullImageSize() const;     // the view's framebuffer pixels; {0, 0} when minimised
  glm::ivec2 tracedImageSize() const;   // ... scaled by render.scale and the adaptive resolution
  void traceImage();
  bool refineImage(glm::ivec2 size);    // traces a band of the next sample of a still image; true if it shows
  int refineBandRows(int height);        // rows of that band: refineBandMs by the last samples' cost
  FramePhase framePhase() const;         // what the slime and the camera did this frame (frame_log.h)
  void uploadImage();
  const std::vector<std::uint8_t>& shownBytes() const { return showingAverage_ ? averageBytes_ : imageBytes_; }
  // --check-every: the image this frame shows against the full trace of the same state (image_check.h);
  // returns the milliseconds it took, which the frame's time and the physics clock leave out.
  double checkImage();
  // The physics state a checked frame stands for, kept before the steps start beside the trace.
  void keepCheckState();
  // Whether this frame's steps start with the trace (they outlasted the panels last frame) or after it.
  bool physicsBesideTrace() const;
  // Where each hand's grab ring and its line go: the target and the grabbed surface, whoever holds
  // the slime (the mouse or the scenario).
  struct GrabMark {
    std::optional<glm::dvec3> target;  // empty when the hand holds nothing
    glm::dvec3 held{0.0};
  };
  // Read before the physics thread starts, with what the Hands section shows: the panels are drawn
  // while the steps run and must not read the simulation.
  struct GrabMarks {
    GrabMark hands[kHands];
    std::vector<HandView> views;
    std::size_t pieces = 1;  // ... and the pieces, tears and merges the Simulation section shows
    int tears = 0, merges = 0;
  };
  GrabMarks grabMarks() const;
  std::vector<HandView> handViews() const;  // what the Hands section shows
  PanelRequests drawPanelsAndOverlay(const GrabMarks& marks);  // reads, never edits, the slime
  void applyPanelRequests(const PanelRequests& requests);
  void followTargetFps();  // the adaptive resolutions' targets from render.targetFps and render.orbitFps
  void present();
  void finishFrame(double frameMs);     // stats, the adaptive resolution, the frame log

  // Helpers of the steps.
  void handleButton(const MouseButtonEvent& event, const FrameInput& input);
  void applyEdit(const std::string& group);
  void reloadSlime();
  void saveScene();
  void loadScene();
  // The part of the window the traced image fills: right of the panel column.
  glm::ivec2 viewSize() const;
  void toViewCoordinates(FrameInput& input) const;
  Settings frameSettings(glm::ivec2 imageSize) const;
  // Samples per pixel a still image refines to: ViewerOptions::refineSamples or render.spp, the more.
  int refineTarget() const;
  glm::dvec3 slimeCentre() const;  // the mean of every piece's drawn vertices
  glm::dvec3 grabbedCentre() const;  // where the grabbed points are now
  bool interacting() const { return wallClock_ - lastInteraction_ < kRefineAfterSeconds; }
  void writeReport() const;
  bool keepsFrameRecords() const { return !options_.frameLogPath.empty() || !options_.reportPath.empty(); }

  ViewerBackend& backend_;
  ViewerOptions options_;
  Settings settings_;              // applied: what the simulation and renderer use
  Settings draft_;                 // what the panels edit; becomes settings_ when valid
  Settings wanted_;                // its rebuild-type values (panel_fields.h) wait here for Reload
  Settings built_;                 // ... and settings_ keeps those the slime was last built from
  std::string editError_;
  std::vector<std::string> editErrors_;  // every refused edit of the session, in order (the report's)
  std::string errorGroup_;
  std::string scenePath_;
  std::string fileMessage_;        // the outcome of the last save or load, shown in the panel
  bool fileFailed_ = false;
  bool showHelp_ = false;          // the F1/H overlay
  float columnWidth_ = 0.0f;       // window pixels the panel column covers (last frame's)
  Simulation simulation_;
  Renderer renderer_;
  Image image_;
  std::vector<std::uint8_t> imageBytes_;  // image_ as sRGB RGBA bytes, for the blit
  AccumulationBuffer refinement_;         // a still image's frames, averaged (progressive AA) ...
  Image averageImage_;                    // ... into these, apart from image_, which keeps the last
  std::vector<std::uint8_t> averageBytes_;  // render()'s pixels for the next one to reuse
  bool showingAverage_ = false;           // the window shows averageBytes_, not imageBytes_
  Image sampleImage_;                     // one of those frames, traced off the pixels' centres
  int sampleRow_ = 0;                     // ... traced a band a frame: its rows above this are done
  double firstBandSetupMs_ = -1.0;        // a sample's first band's setup, smoothed (< 0: none traced yet)
  std::vector<double> blockMs_;           // per block of kRefineBandRowStep rows, their cost when last traced (< 0: not yet)
  int tracedRows_ = 0;                    // rows this frame traced (a new image's or a band's)
  PixelRect imageChanged_;                // the pixels of imageBytes_ the last trace wrote
  FrameCompositor compositor_;
  CameraController cameraController_;
  GrabInteraction grab_;           // the hand the cursor moves while the left button is down
  int cursorHand_ = 0;             // ... which one: 0 (left-drag) or 1 (Ctrl+left-drag, kept on release)
  PhysicsClock clock_;
  FrameStats stats_;
  AdaptiveResolution resolution_;       // frames whose camera stands (render.targetFps)
  AdaptiveResolution orbitResolution_;  // frames whose camera moves (render.orbitFps): its own scale, kept between moves
  // The adaptive resolution of this frame's kind: the camera moving or not.
  AdaptiveResolution& frameResolution() { return cameraMoved_ ? orbitResolution_ : resolution_; }
  const AdaptiveResolution& frameResolution() const { return cameraMoved_ ? orbitResolution_ : resolution_; }
  ImageCheck check_;
  double checkSecondsToSkip_ = 0.0;  // the last check's time, taken off the next frame's elapsed time
  double framePsnrDb_ = -1.0;        // this frame's checked PSNR; < 0: not checked
  bool checkStateKept_ = false;      // this frame is checked: the state below is the traced one
  std::vector<TriangleMesh> checkPieces_;  // one per piece
  bool checkHandled_ = false;
  std::vector<FrameRecord> frameRecords_;  // every frame, when a frame log or report is wanted
  SlimeMetrics metrics_;
  std::optional<ScenarioPlayer> scenario_;
  std::size_t scenarioEventsFired_ = 0;  // options_.scenario's events the player has fired so far
  glm::dvec2 orbitApplied_{0.0};  // the scenario's orbits the camera has turned by so far (orbitAt), degrees
  // The last frame a setting was edited in (panels or a "set" event) and the frame that draws the edit:
  // the same for a "set" event, which fires before the frame's trace; the next for the panels'.
  std::int64_t editedFrame_ = -1;
  std::int64_t editDrawnFrame_ = -1;

  bool quit_ = false;
  bool singleStepPending_ = false;
  bool slimeMoved_ = true;         // the mesh changed since the last refit
  std::vector<glm::dvec3> drawnPositions_;  // every piece's vertices, piece after piece, as the renderer last got them
  std::vector<glm::dvec3> positionsNow_;    // ... and as they are now (refitSlime's, storage kept)
  bool sceneChanged_ = true;       // camera, settings or size changed since the last trace
  bool cameraMoved_ = false;       // this frame's input moved the camera
  bool landed_ = false;            // the slime has touched the floor since it was (re)built
  bool imageTraced_ = false;       // this frame traced an image (a new one, or a refinement sample)
  bool newImageTraced_ = false;    // ... a new one: the view changed
  bool tracedAtFullSize_ = false;  // ... at the full size of the view
  bool rendered_ = false;          // this frame ran the renderer (a new image or a sample of one)
  glm::dvec3 grabTargetDrawn_[kHands]{};  // per hand, the target its grabbed points were last pulled to
  double wallClock_ = 0.0;
  double lastInteraction_ = -1e9;
  int framesSinceNewImage_ = 0;     // frames since the last one that traced a new image
  int grabCount_ = 0;
  double heightAtGrab_ = 0.0;       // the slime's height when the last grab began
  double peakHeightWhileGrabbing_ = 0.0;
  double widthBeforeGrabs_ = -1.0;      // the slime's width when the session's first grab began (< 0: none yet)
  double peakWidthWhileTwoHands_ = 0.0; // the widest the slime was while both hands held it
  std::size_t peakPieces_ = 1;          // slime.tearing: the most pieces at once since the start
  double topologyMs_ = 0.0;             // ... this frame's steps' tears and merges, ms
  double longestTopologyMs_ = 0.0;      // ... the longest of those in one frame
  int screenshotCount_ = 0;
  std::vector<std::string> screenshotPaths_;
  std::vector<std::string> screenshotsWritten_;
  std::vector<TimedScreenshot> timedScreenshots_;  // those requested so far, for the report
  void requestTimedScreenshots();  // those due at the frame's start
};

}  // namespace slime
