// The interactive viewer: the ray-traced slime with Dear ImGui panels over it. One frame is a list of
// named steps — input → refit → trace → upload → panels → present, with the physics steps on a
// second thread beside the panels and present — run the same way in a GLFW window and headless (the
// ViewerBackend seam), so `snapshot --ui` shows what the window shows.
//
// Ordering that matters: ImGui's frame starts before the input step so that io.WantCaptureMouse/
// Keyboard can hide input the panels take; panel edits land in the settings at the end of a frame
// and take effect from the next one.
#pragma once

#include "app/viewer/camera_controller.h"
#include "app/viewer/frame_stats.h"
#include "app/viewer/gl_blit.h"
#include "app/viewer/interaction.h"
#include "app/viewer/panels.h"
#include "app/viewer/physics_clock.h"
#include "app/viewer/viewer_backend.h"
#include "core/scenario.h"
#include "core/settings.h"
#include "core/simulation.h"
#include "render/renderer.h"

#include <glm/vec3.hpp>

#include <optional>
#include <string>
#include <vector>

namespace slime {

struct ViewerOptions {
  int maxFrames = 0;                                // quit after this many frames; 0 = until Esc
  std::string screenshotOnExit;                     // PNG of the last frame, if set
  std::string reportPath;                           // JSON summary written at exit, if set
  std::string screenshotPrefix = "slime-screenshot";  // F12 writes <prefix>-<n>.png
  std::optional<Scenario> scenario;                 // timed grab/drag/press/set events to replay
};

class Viewer {
 public:
  static constexpr double kInteractiveScale = 0.5;  // image scale while the user moves things
  static constexpr double kRefineAfterSeconds = 0.25;  // stillness before the full-resolution image
  // Wall time physics may take per frame. When steps cost more than real time allows, the slime runs
  // slower than real time (the Stats panel says how much) instead of the window freezing.
  static constexpr double kPhysicsBudgetMs = 60.0;

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

 private:
  // The frame's steps, in order.
  FrameInput readInput();
  void handleInput(const FrameInput& input);
  // The grab target for this frame's steps, read from the window on the main thread.
  glm::dvec3 grabTargetFor() const;
  // What a frame's steps did, handed back from the physics thread and applied after it joined.
  struct PhysicsOutcome {
    int steps = 0;
    double milliseconds = 0.0;
    double wallSeconds = 0.0;  // the frame time the steps were for
    SlimeMetrics metrics;      // after the steps, if there were any
  };
  PhysicsOutcome stepPhysics(double wallSeconds, const glm::dvec3& target);  // touches simulation_ only
  void applyPhysicsOutcome(const PhysicsOutcome& outcome);
  void refitSlime();
  bool motionWouldShow() const;         // the slime moved visibly since it was last drawn
  glm::ivec2 tracedImageSize() const;   // the image this frame traces; {0, 0} when minimised
  void traceImage();
  void uploadImage();
  PanelRequests drawPanelsAndOverlay(const glm::dvec3& heldCentre);  // reads, never edits, the slime
  void applyPanelRequests(const PanelRequests& requests);
  void present();

  // Helpers of the steps.
  void handleButton(const MouseButtonEvent& event, const FrameInput& input);
  void applyEdit(Panel panel);
  void reloadSlime();
  Settings frameSettings(glm::ivec2 imageSize) const;
  glm::dvec3 slimeCentre() const;
  glm::dvec3 grabbedCentre() const;  // where the grabbed points are now
  bool interacting() const { return wallClock_ - lastInteraction_ < kRefineAfterSeconds; }
  void writeReport() const;

  ViewerBackend& backend_;
  ViewerOptions options_;
  Settings settings_;              // applied: what the simulation and renderer use
  Settings draft_;                 // what the panels edit; becomes settings_ when valid
  SlimeSettings builtSlime_;       // the slime settings the simulation was last built from
  std::string editError_;
  Panel errorPanel_ = Panel::None;
  Simulation simulation_;
  Renderer renderer_;
  Image image_;
  std::vector<std::uint8_t> imageBytes_;  // image_ as sRGB RGBA bytes, for the blit
  GlBlit blit_;
  CameraController cameraController_;
  GrabInteraction grab_;
  PhysicsClock clock_;
  FrameStats stats_;
  SlimeMetrics metrics_;
  std::optional<ScenarioPlayer> scenario_;

  bool quit_ = false;
  bool singleStepPending_ = false;
  bool slimeMoved_ = true;         // the mesh changed since the last refit
  std::vector<glm::dvec3> drawnPositions_;  // the vertices as the renderer last got them
  bool sceneChanged_ = true;       // camera, settings or size changed since the last trace
  bool imageTraced_ = false;       // this frame traced a new image
  glm::dvec3 grabTargetDrawn_{0.0};  // the target the grabbed points were last pulled to
  double wallClock_ = 0.0;
  double lastInteraction_ = -1e9;
  int grabCount_ = 0;
  double heightAtGrab_ = 0.0;       // the slime's height when the last grab began
  double peakHeightWhileGrabbing_ = 0.0;
  int screenshotCount_ = 0;
  std::vector<std::string> screenshotPaths_;
  std::vector<std::string> screenshotsWritten_;
};

}  // namespace slime
