#include "app/viewer/frame_log.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>

namespace slime {

const char* nameOf(FramePhase phase) {
  switch (phase) {
    case FramePhase::Falling: return "falling";
    case FramePhase::Settling: return "settling";
    case FramePhase::Creeping: return "creeping";
    case FramePhase::Resting: return "resting";
    case FramePhase::Held: return "held";
    case FramePhase::Stretched: return "stretched";
    case FramePhase::Orbiting: return "orbiting";
    case FramePhase::Editing: return "editing";
  }
  return "unknown";
}

bool writeFrameLogCsv(const std::vector<FrameRecord>& records, const std::string& path) {
  std::ofstream file(path);
  file << "frame,end_s,frame_ms,physics_ms,refit_ms,trace_ms,upload_ms,ui_ms,"
          "traced,full_resolution,width,height,scale,grabbed,simulated_s,check_psnr_db,caustics_ms,caustic_photons,"
          "traced_rows,phase,pieces,tears,merges,topology_ms\n";
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
    std::snprintf(line, sizeof line, ",%.3f,%llu,%d,%s,%d,%d,%d,%.3f\n", stages.caustics,
                  static_cast<unsigned long long>(frame.causticPhotons), frame.tracedRows, nameOf(frame.phase),
                  frame.pieces, frame.tears, frame.merges, frame.topologyMs);
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

namespace {

// Median, 95th and 99th percentile (nearest rank: the smallest frame time that p of the frames do not
// exceed) and the longest of `times`, which it sorts.
PhaseSummary summarizeTimes(std::vector<double>& times) {
  PhaseSummary summary;
  if (times.empty()) return summary;
  std::sort(times.begin(), times.end());
  const auto percentile = [&times](double p) {
    const std::size_t rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(times.size())));
    return times[std::clamp<std::size_t>(rank, 1, times.size()) - 1];
  };
  summary.frames = static_cast<std::int64_t>(times.size());
  for (const double ms : times) summary.seconds += ms / 1000.0;
  summary.medianMs = percentile(0.5);
  summary.p95Ms = percentile(0.95);
  summary.p99Ms = percentile(0.99);
  summary.longestMs = times.back();
  return summary;
}

}  // namespace

std::vector<PhaseSummary> summarizePhases(const std::vector<FrameRecord>& records, double afterSeconds) {
  std::vector<double> frameMs[kFramePhases];
  for (const FrameRecord& record : records)
    if (record.endSeconds >= afterSeconds) frameMs[static_cast<int>(record.phase)].push_back(record.frameMs);
  std::vector<PhaseSummary> summaries;
  for (int phase = 0; phase < kFramePhases; ++phase) {
    if (frameMs[phase].empty()) continue;
    PhaseSummary summary = summarizeTimes(frameMs[phase]);
    summary.phase = static_cast<FramePhase>(phase);
    summaries.push_back(summary);
  }
  return summaries;
}

PhaseSummary summarizeFrameTimes(const std::vector<FrameRecord>& records, bool (*include)(const FrameRecord&),
                                 double afterSeconds) {
  std::vector<double> frameMs;
  for (const FrameRecord& record : records)
    if (record.endSeconds >= afterSeconds && include(record)) frameMs.push_back(record.frameMs);
  return summarizeTimes(frameMs);
}

FrameWindow slowestWindow(const std::vector<FrameRecord>& records, double windowSeconds, double afterSeconds) {
  FrameWindow slowest;
  if (records.empty() || !(windowSeconds > 0.0)) return slowest;
  // Windows [t, t + w) starting at afterSeconds and at every frame's end after it, while they fit in
  // the run: the count of frames ending inside only changes at those starts.
  const double last = records.back().endSeconds;
  std::size_t first = 0, end = 0;
  const auto consider = [&](double start) {
    if (start + windowSeconds > last + 1e-12) return;
    while (first < records.size() && records[first].endSeconds <= start) ++first;
    if (end < first) end = first;
    while (end < records.size() && records[end].endSeconds <= start + windowSeconds) ++end;
    const double fps = static_cast<double>(end - first) / windowSeconds;
    if (slowest.fps < 0.0 || fps < slowest.fps) slowest = {fps, start};
  };
  consider(afterSeconds);
  for (const FrameRecord& record : records)
    if (record.endSeconds > afterSeconds) consider(record.endSeconds);
  return slowest;
}

}  // namespace slime
