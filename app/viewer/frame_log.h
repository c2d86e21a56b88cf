// The viewer's record of every frame (`slime view --frame-log FILE.csv`, and the exit report's figures
// over the frames the slime was held): wall time and stages, whether and at what size it traced,
// whether the slime was grabbed. The series behind the chart of fps over a scripted drag
// (scripts/plots/viewer_drag_fps.gp).
#pragma once

#include "app/viewer/frame_stats.h"

#include <cstdint>
#include <string>
#include <vector>

namespace slime {

// What the slime and the camera did in a frame, for the figures per phase (issue 43): the slow frames
// a person notices come in some phases and not others. The first that applies, in this order:
// stretched (both hands hold it), held (one hand), orbiting (the camera moved), editing (a setting was
// edited in this frame, or the frame draws the edit: the panels' are drawn in the next), falling (not yet on
// the floor), settling (its fastest point moves kSettlingPixelsPerSecond on screen or more), creeping
// (slower, but more than kStillMotionPixels a second), resting.
enum class FramePhase { Falling, Settling, Creeping, Resting, Held, Stretched, Orbiting, Editing };
constexpr int kFramePhases = 8;
const char* nameOf(FramePhase phase);  // "falling", "settling", ...
constexpr double kSettlingPixelsPerSecond = 30.0;  // a pixel a frame at 30 frames a second

struct FrameRecord {
  double endSeconds = 0.0;        // wall time from the start of the first frame to the end of this one
  double frameMs = 0.0;           // wall time of this frame
  StageTimes stages;              // trace and refit are 0 when the frame traced nothing
  bool traced = false;            // traced a new image, or one more sample of a still one
  bool fullResolution = false;    // ... at the full size of the view
  int imageWidth = 0;             // the image shown (traced now or earlier)
  int imageHeight = 0;
  double scale = 1.0;             // traced size / full size: render.scale × the adaptive factor
  bool grabbed = false;           // the slime was held, by the mouse or a scenario, at the frame's end
  double simulatedSeconds = 0.0;  // simulation time at the frame's end
  double checkPsnrDb = -1.0;      // --check-every: the shown image's PSNR against the full trace; < 0: unchecked
  std::uint64_t causticPhotons = 0;  // photons behind the caustic map of the frame's trace (0: none)
  int tracedRows = 0;             // image rows traced: a new image's, or a band of a refinement sample
  FramePhase phase = FramePhase::Resting;
  // slime.tearing: the pieces at the frame's end, the tears and merges since the slime was built, and
  // the milliseconds this frame's steps spent tearing and merging (Simulation::lastTopologyMilliseconds).
  int pieces = 1;
  int tears = 0;
  int merges = 0;
  double topologyMs = 0.0;
};

// One line per frame under a header naming the columns (units in the names: _s, _ms, _db; an
// unchecked frame leaves check_psnr_db empty; caustics_ms, caustic_photons, traced_rows, phase, then
// pieces, tears, merges and topology_ms come last, so the plot scripts' column numbers hold). Returns false
// if the file cannot be written.
bool writeFrameLogCsv(const std::vector<FrameRecord>& records, const std::string& path);

// Figures over a subset of the frames, for the report.
struct FrameSummary {
  std::int64_t frames = 0;
  double meanFps = 0.0;        // frames / their summed wall time
  double medianFrameMs = 0.0;
  StageTimes meanStages;       // trace and refit over the frames that traced
  std::int64_t fullResolutionFrames = 0;  // frames that traced at full resolution
  std::int64_t reducedResolutionFrames = 0;
};
FrameSummary summarizeFrames(const std::vector<FrameRecord>& records, bool (*include)(const FrameRecord&));

// Frame times of one phase: the slow frames, not only the typical one.
struct PhaseSummary {
  FramePhase phase = FramePhase::Resting;
  std::int64_t frames = 0;
  double seconds = 0.0;  // their summed wall time
  double medianMs = 0.0, p95Ms = 0.0, p99Ms = 0.0, longestMs = 0.0;
};
// One summary per phase that has frames, in FramePhase's order. `afterSeconds`: frames ending before
// this wall time (the window's first frames, shaders and caches warming) are left out.
std::vector<PhaseSummary> summarizePhases(const std::vector<FrameRecord>& records, double afterSeconds = 0.0);

// Frame times of the frames `include` takes, as a phase's (its `phase` left Resting); no frames: all 0.
PhaseSummary summarizeFrameTimes(const std::vector<FrameRecord>& records, bool (*include)(const FrameRecord&),
                                 double afterSeconds = 0.0);

// The fewest frames a second in any `windowSeconds` of wall time (frames counted by their end) from
// `afterSeconds` on, and where that window starts; {-1, 0} when the run is shorter than one window.
struct FrameWindow {
  double fps = -1.0;
  double startSeconds = 0.0;
};
FrameWindow slowestWindow(const std::vector<FrameRecord>& records, double windowSeconds, double afterSeconds = 0.0);

}  // namespace slime
