// The snapshot pipeline as one reusable call: settings → a settled slime → one traced Image.
// `slime snapshot` writes it to a PNG; the viewer's `--ui` mode can call the same function.
#pragma once

#include "core/export/surface_mesh.h"

#include "core/settings/settings.h"
#include "core/simulation/simulation.h"
#include "render/trace/renderer.h"

#include <string>

namespace slime {

struct SnapshotResult {
  Image image;              // linear RGB, settings.camera.width × settings.camera.height
  RenderStats stats;        // the traced frame's timing and ray counts
  double simulatedSeconds = 0.0;
  SlimeMetrics metrics;     // the slime's shape when the frame was taken
  std::size_t divergences = 0;  // steps the physics rolled back while settling
  SurfaceMesh surface;      // the drawn surface the frame shows (`--export-mesh`)
  SlimeSettings slime;      // the slime's settings the frame was drawn with (its exported material)
};

// Simulates the slime for `settleSeconds` (negative: until it rests, at most kMaxSettleSeconds after
// the scenario's last event), replaying `scenarioFile` if one is given, and renders one frame of it
// with the settings' camera and image size. Deterministic: the same inputs give the same pixels.
SnapshotResult takeSnapshot(const Settings& settings, double settleSeconds, const std::string& scenarioFile = "");

// Advances `simulation` by the rule above: `settleSeconds` of simulated time or, when negative, until
// the slime rests. Returns the settings as the scenario's "set" events left them.
Settings settleForSnapshot(Simulation& simulation, const Settings& settings, double settleSeconds,
                           const std::string& scenarioFile);

constexpr double kMaxSettleSeconds = 3.0;
// "At rest": no vertex faster than this (m/s), checked after at least kMinSettleSeconds.
constexpr double kRestSpeed = 0.005;
constexpr double kMinSettleSeconds = 0.3;

// Parses an image size "WxH" into the settings' camera; W and H are integers in 1..8192.
// Throws SettingsError naming --size and the allowed range otherwise.
void applyImageSize(Settings& settings, const std::string& size);

}  // namespace slime
