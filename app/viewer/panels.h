// The viewer's Dear ImGui panels: one column at the left side of the window with a section per group
// of the scene file (camera, light, floor, slime, render, sim), each setting generated from the table
// of settings (panel_fields.h), a Scene section that saves and loads, the Stats window, and the help
// overlay. The panels edit a draft copy of the Settings; the viewer validates the draft
// (validateSettings) and applies it only if it is valid, otherwise the section shows the error.
// Nothing here owns simulation state: the panels only read the stats and metrics they display.
#pragma once

#include <string>
#include <vector>

#include "app/viewer/frame_stats.h"
#include "core/settings/settings.h"
#include "core/simulation/simulation.h"

#include <glm/vec3.hpp>

namespace slime {

// What the user asked for this frame.
struct PanelRequests {
  std::string editedGroup;   // a setting of this group changed (the draft holds the new value)
  bool reloadSlime = false;  // "Reload slime": rebuild the slime from the settings (level, radius, ...)
  bool singleStep = false;   // "Step": one physics step while paused
  bool save = false;         // "Save": write the scene to the path field
  bool load = false;         // "Load": read the scene at the path field
  float columnWidth = 0.0f;  // window pixels the column covers at the left (0 when collapsed)
  int targetFps = -1;        // the Stats window set the adaptive resolution's target (0: off); -1: it did not
  int releaseHand = -1;      // the Hands section's "release" button of this hand; -1: none pressed
};

// One hand as the Hands section shows it.
struct HandView {
  bool holding = false;
  glm::dvec3 position{0.0};  // where the hand's part of the surface is now, m
  glm::dvec3 target{0.0};    // where the hand pulls it, m
  glm::dvec3 force{0.0};     // the hand's force on the body, N (bulk)
  std::size_t piece = 0;     // the piece it holds (slime.tearing: after a tear, the part that kept its nodes)
};

// Read-only facts the panels display.
struct PanelView {
  const FrameStats& stats;
  const SlimeMetrics& metrics;
  const std::string& editError;            // why the last edit was not applied; empty if it was
  std::string errorGroup;                  // the group whose edit it was
  std::vector<std::string> reloadPending;  // rebuild-type keys changed since the slime was built
  const std::string& fileMessage;          // the outcome of the last save or load
  bool fileFailed = false;                 // ... and whether it failed (shown in red)
  // What is on screen (the slime as built, the floor as applied): settings that do nothing to it are
  // left out (inactiveReason, panel_fields.h). Null: judged from the draft.
  const Settings* shown = nullptr;
  std::vector<HandView> hands{};  // hand 0 (left-drag) and hand 1 (Ctrl+left-drag)
  std::string integrator{};      // the one stepping the slime (sim.integrator with auto resolved)
  std::size_t pieces = 1;        // slime.tearing: the pieces now, and the tears and merges since the slime was built
  int tears = 0;
  int merges = 0;
};

// Width of the column for a display of this width, in window pixels.
float panelColumnWidth(float displayWidth);

// Draws the column and the Stats window (with the adaptive resolution's target frame rate).
// `scenePath` is the Scene section's path field.
PanelRequests drawPanels(Settings& draft, std::string& scenePath, const PanelView& view);

// Draws the controls (keys, mouse) over the middle of the free part of the window.
void drawHelpOverlay(float columnWidth);

}  // namespace slime
