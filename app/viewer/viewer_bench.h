// `slime bench viewer`: the viewer's frames timed through a scripted run of every phase a person
// meets (falling, settling, creeping, resting, held, stretched, orbiting, editing a setting), drawn
// headless (EGL or OSMesa, Mesa's llvmpipe, as under Xvfb) with the wall clock running as in a window.
// Prints each phase's frames a second and median / 95th / 99th percentile / longest frame, the
// slowest 3-second window, and whether each phase meets the smoothness aims (docs/performance.md,
// viewer section); writes the frame log (frame_log.h's CSV, which scripts/plots/viewer_phases.gp
// charts) and a JSON of the same table. A run that tears or merges (slime.tearing) also gets the handled
// frames of one piece against those of several, and each frame that tore or merged, with its time.
#pragma once

#include "app/viewer/headless_gl.h"
#include "core/settings/settings.h"

#include <string>

namespace slime {

struct ViewerBenchOptions {
  int width = 1280;
  int height = 720;
  std::string scenarioPath = "tests/scenarios/viewer_phases.json";
  double seconds = 0.0;   // simulated seconds to run; 0: the scenario's last event + 6 s
  // Wall seconds at most; 0: twice the simulated seconds and 30 s more (a setting that cannot run in
  // real time, a level-7 surface, ends there with the simulation behind)
  double wallSeconds = 0.0;
  HeadlessApi api = HeadlessApi::Auto;
  std::string csvPath;    // the frame log; empty: none
  std::string jsonPath;   // the table; empty: none
  double afterSeconds = 1.0;  // wall seconds left out at the start (shaders and caches warming)
};

// Throws SettingsError for a bad scenario, std::runtime_error when there is no headless GL or a file
// cannot be written. Returns the process exit code (0).
int runViewerBench(const Settings& settings, const ViewerBenchOptions& options);

}  // namespace slime
