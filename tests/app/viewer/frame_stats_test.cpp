// The Stats panel's and the viewer report's frame figures: the run's mean rate and a robust recent median.
#include "app/viewer/frame_stats.h"

#include <gtest/gtest.h>

namespace slime {
namespace {

TEST(FrameStats, MeanFpsCountsEveryFrameOfTheRun) {
  FrameStats stats;
  for (int i = 0; i < 10; ++i) stats.recordFrame(20.0);
  for (int i = 0; i < 10; ++i) stats.recordFrame(60.0);
  EXPECT_DOUBLE_EQ(stats.meanFps(), 20.0 / 0.8);  // 20 frames in 800 ms
}

TEST(FrameStats, MedianOfRecentFramesIgnoresAFewStalls) {
  FrameStats stats;
  EXPECT_EQ(stats.medianRecentFrameMs(), 0.0);
  for (int i = 0; i < 7; ++i) stats.recordFrame(30.0);
  stats.recordFrame(500.0);
  EXPECT_EQ(stats.medianRecentFrameMs(), 30.0);
  // After the ring wraps only the last kHistory frames count.
  for (int i = 0; i < FrameStats::kHistory; ++i) stats.recordFrame(i % 10 == 0 ? 200.0 : 25.0);
  EXPECT_EQ(stats.medianRecentFrameMs(), 25.0);
}

TEST(FrameStats, MeanStagesAverageTraceOverTracedFramesOnly) {
  FrameStats stats;
  EXPECT_EQ(stats.meanStages().trace, 0.0);
  // Two frames that trace (20 ms each) and two that only run physics and draw the panels.
  for (int i = 0; i < 4; ++i) {
    const bool traced = i % 2 == 0;
    stats.stages.physics = 4.0 + i;  // 4, 5, 6, 7
    stats.stages.ui = 2.0;
    stats.stages.upload = traced ? 1.0 : 0.0;
    if (traced) stats.stages.trace = 20.0 + i;  // 20, 22; the others keep the last traced value
    stats.recordStages(traced);
    stats.recordFrame(30.0);
  }
  const StageTimes mean = stats.meanStages();
  EXPECT_DOUBLE_EQ(mean.physics, 5.5);
  EXPECT_DOUBLE_EQ(mean.ui, 2.0);
  EXPECT_DOUBLE_EQ(mean.upload, 0.5);
  EXPECT_DOUBLE_EQ(mean.trace, 21.0);
  EXPECT_EQ(stats.tracedFrames, 2);
}

}  // namespace
}  // namespace slime
