// What the Stats panel shows: time per frame stage, rays traced, and a history of frame times.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

namespace slime {

// Milliseconds spent in each named step of one frame.
struct StageTimes {
  double physics = 0.0;
  double refit = 0.0;
  double trace = 0.0;
  double caustics = 0.0;  // the caustic photons traced and gathered: part of trace, not beside it
  double upload = 0.0;
  double ui = 0.0;
};

struct FrameStats {
  static constexpr int kHistory = 120;

  StageTimes stages;                     // the last frame (trace, refit: the last traced frame)
  double frameMs = 0.0;                  // wall time of the last frame
  double fps = 0.0;                      // smoothed frames per second
  std::uint64_t rays = 0;                // rays traced in the last frame
  double megaraysPerSecond = 0.0;        // rays / trace time of the last traced frame
  double reusedFraction = 0.0;           // pixels copied from the frame before, not traced (still view)
  int traceThreads = 0;                  // threads tracing the last traced frame
  double threadUse = 0.0;                // their busy time / (trace time × threads), 0..1
  std::uint64_t causticPhotons = 0;      // photons behind the last traced frame's caustic map (0: none)
  int physicsSteps = 0;                  // fixed steps run in the last frame
  int samplesPerPixel = 1;               // samples averaged in the image shown (progressive anti-aliasing)
  int tracedRows = 0;                    // image rows the last frame traced: a new image's, or a band of a sample's
  int imageWidth = 0;                    // traced image size of the last frame
  int imageHeight = 0;
  double renderScale = 1.0;              // its size / the full size (render.scale × the adaptive factor)
  double targetFps = 0.0;                // the adaptive resolution's target; 0: off
  std::array<float, kHistory> frameHistoryMs{};  // ring buffer of frame times
  int historyNext = 0;                   // where the next frame time goes
  std::int64_t frames = 0;
  double totalFrameMs = 0.0;             // every frame's wall time, summed
  double simulationSpeed = 1.0;          // simulated seconds per wall second, smoothed
  StageTimes stageSums;                  // every frame's stages summed (trace, refit: traced frames only)
  std::int64_t tracedFrames = 0;         // frames that traced an image
  std::int64_t fullResolutionFrames = 0;     // ... at the full size of the view
  std::int64_t reducedResolutionFrames = 0;  // ... smaller (render.scale or the adaptive resolution)

  // Adds the frame's stages to the sums; `traced`: this frame traced (and refitted) an image,
  // `fullResolution`: at the full size of the view.
  void recordStages(bool traced, bool fullResolution = true) {
    stageSums.physics += stages.physics;
    stageSums.upload += stages.upload;
    stageSums.ui += stages.ui;
    if (!traced) return;
    stageSums.refit += stages.refit;
    stageSums.trace += stages.trace;
    stageSums.caustics += stages.caustics;
    ++tracedFrames;
    ++(fullResolution ? fullResolutionFrames : reducedResolutionFrames);
  }

  // Mean milliseconds per frame of each stage (trace and refit: per traced frame).
  StageTimes meanStages() const {
    StageTimes mean;
    if (frames > 0) {
      mean.physics = stageSums.physics / static_cast<double>(frames);
      mean.upload = stageSums.upload / static_cast<double>(frames);
      mean.ui = stageSums.ui / static_cast<double>(frames);
    }
    if (tracedFrames > 0) {
      mean.refit = stageSums.refit / static_cast<double>(tracedFrames);
      mean.trace = stageSums.trace / static_cast<double>(tracedFrames);
      mean.caustics = stageSums.caustics / static_cast<double>(tracedFrames);
    }
    return mean;
  }

  void recordSimulatedTime(double simulatedSeconds, double wallSeconds) {
    if (wallSeconds <= 0.0) return;
    simulationSpeed = 0.9 * simulationSpeed + 0.1 * (simulatedSeconds / wallSeconds);
  }

  // Records the wall time of a finished frame.
  void recordFrame(double milliseconds) {
    frameMs = milliseconds;
    frameHistoryMs[historyNext] = static_cast<float>(milliseconds);
    historyNext = (historyNext + 1) % kHistory;
    const double instantFps = milliseconds > 0.0 ? 1000.0 / milliseconds : 0.0;
    fps = frames == 0 ? instantFps : 0.9 * fps + 0.1 * instantFps;
    ++frames;
    totalFrameMs += milliseconds;
  }

  // Frames per second over the whole run.
  double meanFps() const { return totalFrameMs > 0.0 ? 1000.0 * static_cast<double>(frames) / totalFrameMs : 0.0; }

  // Median wall time of the last min(frames, kHistory) frames.
  double medianRecentFrameMs() const {
    const int count = static_cast<int>(std::min<std::int64_t>(frames, kHistory));
    if (count == 0) return 0.0;
    std::array<float, kHistory> recent = frameHistoryMs;  // until the ring wraps, its first `count` entries
    std::nth_element(recent.begin(), recent.begin() + count / 2, recent.begin() + count);
    return recent[count / 2];
  }
};

}  // namespace slime
