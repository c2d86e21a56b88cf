// The viewer's Dear ImGui panels. They edit a draft copy of the Settings; the viewer validates the
// draft (validateSettings) and applies it only if it is valid, otherwise the panel shows the error.
// Nothing here owns simulation state: the panels only read the stats and metrics they display.
#pragma once

#include "app/viewer/frame_stats.h"
#include "core/settings.h"
#include "core/simulation.h"

#include <string>

namespace slime {

enum class Panel { None, Slime, Render, Simulation };

// What the user asked for this frame.
struct PanelRequests {
  Panel edited = Panel::None;  // a setting in this panel changed (the draft holds the new value)
  bool reloadSlime = false;    // "Reload slime": rebuild the slime from the settings (level, radius, ...)
  bool singleStep = false;     // "Step": one physics step while paused
};

// Read-only facts the panels display.
struct PanelView {
  const FrameStats& stats;
  const SlimeMetrics& metrics;
  const std::string& editError;  // why the last edit was not applied; empty if it was
  Panel errorPanel = Panel::None;
  bool reloadPending = false;    // level or radius changed since the slime was built
};

// Draws the Controls window (Slime, Render, Simulation sections) and the Stats window.
PanelRequests drawPanels(Settings& draft, const PanelView& view);

}  // namespace slime
