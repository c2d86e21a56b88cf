#include "app/viewer/frame_log.h"

#include <algorithm>
#include <cstdio>
#include <fstream>

namespace slime {

bool writeFrameLogCsv(const std::vector<FrameRecord>& records, const std::string& path) {
  std::ofstream file(path);
  file << "frame,end_s,frame_ms,physics_ms,refit_ms,trace_ms,upload_ms,ui_ms,"
          "traced,full_resolution,width,height,scale,grabbed,simulated_s,check_psnr_db,caustics_ms,caustic_photons\n";
  char line[360];
  for (std::size_t index = 0; index < records.size(); ++index) {
    const FrameRecord& frame = records[index];
    const StageTimes& stages = frame.stages;
    std::snprintf(line, sizeof line, "%zu,%.4f,%.3f,%.3f,%.3f,%.3f,%.3f,%.3f,%d,%d,%d,%d,%.3f,%d,%.4f,",
                  index, frame.endSeconds, frame.frameMs, stages.physics, stages.refit, stages.trace,
                  stages.upload, stages.ui, frame.traced ? 1 : 0, frame.fullResolution ? 1 : 0,
                  frame.imageWidth, frame.imageHeight, frame.scale, frame.grabbed ? 1 : 0,
                  frame.simulatedSeconds);
    file << line;
    if (frame.checkPsnrDb >= 0.0) {
      std::snprintf(line, sizeof line, "%.2f", frame.checkPsnrDb);
      file << line;
    }
    std::snprintf(line, sizeof line, ",%.3f,%llu\n", stages.caustics, static_cast<unsigned long long>(frame.causticPhotons));
    file << line;
  }
  file.flush();
  return static_cast<bool>(file);
}

FrameSummary summarizeFrames(const std::vector<FrameRecord>& records, bool (*include)(const FrameRecord&)) {
  FrameSummary summary;
  std::vector<double> frameMs;
  double totalMs = 0.0;
  std::int64_t traced = 0;
  for (const FrameRecord& record : records) {
    if (!include(record)) continue;
    ++summary.frames;
    totalMs += record.frameMs;
    frameMs.push_back(record.frameMs);
    summary.meanStages.physics += record.stages.physics;
    summary.meanStages.upload += record.stages.upload;
    summary.meanStages.ui += record.stages.ui;
    if (!record.traced) continue;
    ++traced;
    summary.meanStages.trace += record.stages.trace;
    summary.meanStages.refit += record.stages.refit;
    summary.meanStages.caustics += record.stages.caustics;
    ++(record.fullResolution ? summary.fullResolutionFrames : summary.reducedResolutionFrames);
  }
  if (summary.frames == 0) return summary;
  const double frames = static_cast<double>(summary.frames);
  summary.meanFps = totalMs > 0.0 ? 1000.0 * frames / totalMs : 0.0;
  std::nth_element(frameMs.begin(), frameMs.begin() + frameMs.size() / 2, frameMs.end());
  summary.medianFrameMs = frameMs[frameMs.size() / 2];
  summary.meanStages.physics /= frames;
  summary.meanStages.upload /= frames;
  summary.meanStages.ui /= frames;
  if (traced > 0) {
    summary.meanStages.trace /= static_cast<double>(traced);
    summary.meanStages.refit /= static_cast<double>(traced);
    summary.meanStages.caustics /= static_cast<double>(traced);
  }
  return summary;
}

}  // namespace slime
