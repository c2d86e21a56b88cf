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
};

// One line per frame under a header naming the columns (units in the names: _s, _ms, _db; an
// unchecked frame leaves check_psnr_db empty; caustics_ms and caustic_photons come last, so the
// plot scripts' column numbers hold). Returns false
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

}  // namespace slime
