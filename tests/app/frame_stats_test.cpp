// The Stats panel's and the viewer report's frame figures: the run's mean rate and a robust recent median.
#include "app/frame_stats.h"

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

}  // namespace
}  // namespace slime
