// The viewer's per-frame record: the CSV behind the drag chart and the report's figures over the
// frames the slime was held.
#include "app/viewer/frame_log.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

namespace slime {
namespace {

FrameRecord record(double frameMs, bool traced, bool full, bool grabbed) {
  FrameRecord frame;
  frame.frameMs = frameMs;
  frame.stages.physics = 5.0;
  frame.stages.ui = 8.0;
  frame.stages.trace = traced ? 40.0 : 0.0;
  frame.traced = traced;
  frame.fullResolution = traced && full;
  frame.grabbed = grabbed;
  return frame;
}

TEST(FrameLog, SummaryOfTheGrabbedFramesOnly) {
  const std::vector<FrameRecord> records = {
      record(100.0, true, true, false),  // before the grab: left out
      record(50.0, true, true, true),   record(40.0, true, false, true), record(60.0, false, false, true),
      record(30.0, true, true, false)};
  const FrameSummary summary = summarizeFrames(records, [](const FrameRecord& r) { return r.grabbed; });
  EXPECT_EQ(summary.frames, 3);
  EXPECT_DOUBLE_EQ(summary.meanFps, 3.0 / 0.150);
  EXPECT_DOUBLE_EQ(summary.medianFrameMs, 50.0);
  EXPECT_DOUBLE_EQ(summary.meanStages.trace, 40.0);  // over the two frames that traced
  EXPECT_DOUBLE_EQ(summary.meanStages.physics, 5.0);
  EXPECT_EQ(summary.fullResolutionFrames, 1);
  EXPECT_EQ(summary.reducedResolutionFrames, 1);
}

TEST(FrameLog, NoFramesGiveZeros) {
  const FrameSummary summary = summarizeFrames({record(50.0, true, true, false)},
                                               [](const FrameRecord& r) { return r.grabbed; });
  EXPECT_EQ(summary.frames, 0);
  EXPECT_EQ(summary.meanFps, 0.0);
  EXPECT_EQ(summary.medianFrameMs, 0.0);
}

TEST(FrameLog, CsvHasAHeaderAndOneLinePerFrame) {
  const std::filesystem::path path = std::filesystem::path(SLIME_TEST_OUTPUT_DIR) / "frame_log_test.csv";
  FrameRecord frame = record(33.5, true, false, true);
  frame.imageWidth = 320;
  frame.imageHeight = 180;
  frame.scale = 0.5;
  frame.checkPsnrDb = 41.257;
  frame.stages.caustics = 3.25;
  frame.causticPhotons = 20000;
  frame.tracedRows = 90;
  frame.phase = FramePhase::Held;
  frame.pieces = 2;
  frame.tears = 1;
  frame.topologyMs = 12.5;
  ASSERT_TRUE(writeFrameLogCsv({record(40.0, true, true, false), frame}, path.string()));
  std::ifstream file(path);
  std::string header, first, second, extra;
  std::getline(file, header);
  std::getline(file, first);
  std::getline(file, second);
  EXPECT_FALSE(std::getline(file, extra));
  EXPECT_EQ(header,
            "frame,end_s,frame_ms,physics_ms,refit_ms,trace_ms,upload_ms,ui_ms,"
            "traced,full_resolution,width,height,scale,grabbed,simulated_s,check_psnr_db,caustics_ms,caustic_photons,"
            "traced_rows,phase,pieces,tears,merges,topology_ms");
  EXPECT_EQ(second,
            "1,0.0000,33.500,5.000,0.000,40.000,0.000,8.000,1,0,320,180,0.500,1,0.0000,41.26,3.250,20000,90,held,2,1,0,12.500");
  EXPECT_EQ(first.substr(first.size() - 38), ",0.0000,,0.000,0,0,resting,1,0,0,0.000");  // unchecked: check_psnr_db empty
}

// Per phase: the median, 95th and 99th percentile (nearest rank) and the longest frame, the first
// second left out; phases without frames are not listed.
TEST(FrameLog, PhasesHaveTheirPercentilesAndLongestFrame) {
  std::vector<FrameRecord> records;
  for (int i = 1; i <= 100; ++i) {  // resting: 1 .. 100 ms
    FrameRecord frame = record(static_cast<double>(i), false, false, false);
    frame.endSeconds = 2.0;
    frame.phase = FramePhase::Resting;
    records.push_back(frame);
  }
  FrameRecord held = record(30.0, true, true, true);
  held.endSeconds = 2.0;
  held.phase = FramePhase::Held;
  records.push_back(held);
  FrameRecord early = record(500.0, true, true, false);  // the first second: left out
  early.endSeconds = 0.5;
  early.phase = FramePhase::Falling;
  records.push_back(early);
  const std::vector<PhaseSummary> phases = summarizePhases(records, 1.0);
  ASSERT_EQ(phases.size(), 2u);
  EXPECT_EQ(phases[0].phase, FramePhase::Resting);
  EXPECT_EQ(phases[0].frames, 100);
  EXPECT_EQ(phases[0].medianMs, 50.0);
  EXPECT_EQ(phases[0].p95Ms, 95.0);
  EXPECT_EQ(phases[0].p99Ms, 99.0);
  EXPECT_EQ(phases[0].longestMs, 100.0);
  EXPECT_NEAR(phases[0].seconds, 5.05, 1e-9);
  EXPECT_EQ(phases[1].phase, FramePhase::Held);
  EXPECT_EQ(phases[1].frames, 1);
  EXPECT_EQ(phases[1].p99Ms, 30.0);
  EXPECT_STREQ(nameOf(FramePhase::Orbiting), "orbiting");
  EXPECT_STREQ(nameOf(FramePhase::Editing), "editing");
}

// The frames a predicate takes (here the torn ones, pieces > 1), with the first second left out.
TEST(FrameLog, FrameTimesOfTheFramesAPredicateTakes) {
  std::vector<FrameRecord> records;
  for (int i = 1; i <= 20; ++i) {  // one piece at 100 ms, two pieces at 1 .. 20 ms
    FrameRecord frame = record(i % 2 == 0 ? 100.0 : static_cast<double>(i), false, false, false);
    frame.endSeconds = 2.0;
    frame.pieces = i % 2 == 0 ? 1 : 2;
    records.push_back(frame);
  }
  FrameRecord early = record(500.0, false, false, false);
  early.endSeconds = 0.5;
  early.pieces = 2;
  records.push_back(early);
  const auto torn = [](const FrameRecord& frame) { return frame.pieces > 1; };
  const PhaseSummary summary = summarizeFrameTimes(records, torn, 1.0);
  EXPECT_EQ(summary.frames, 10);
  EXPECT_EQ(summary.medianMs, 9.0);  // 1, 3, .., 19: the 5th
  EXPECT_EQ(summary.p95Ms, 19.0);
  EXPECT_EQ(summary.longestMs, 19.0);
  EXPECT_NEAR(summary.seconds, 0.1, 1e-12);
  const auto none = [](const FrameRecord&) { return false; };
  EXPECT_EQ(summarizeFrameTimes(records, none).frames, 0);
}

TEST(FrameLog, TheSlowestWindowCountsTheFramesEndingInIt) {
  std::vector<FrameRecord> records;
  double t = 0.0;
  for (int i = 0; i < 300; ++i) {  // 10 s at 30 fps ...
    t += 1.0 / 30.0;
    FrameRecord frame = record(1000.0 / 30.0, true, true, false);
    frame.endSeconds = t;
    records.push_back(frame);
  }
  for (int i = 0; i < 10; ++i) {  // ... then 1 s at 10 fps ...
    t += 0.1;
    FrameRecord frame = record(100.0, true, true, false);
    frame.endSeconds = t;
    records.push_back(frame);
  }
  for (int i = 0; i < 300; ++i) {  // ... then 5 s at 60 fps
    t += 1.0 / 60.0;
    FrameRecord frame = record(1000.0 / 60.0, true, true, false);
    frame.endSeconds = t;
    records.push_back(frame);
  }
  const FrameWindow slowest = slowestWindow(records, 3.0, 1.0);
  // The slowest 3 s: 2 s at 30 fps and the 1 s at 10 fps, (60 + 10) / 3 frames a second.
  EXPECT_NEAR(slowest.fps, 70.0 / 3.0, 1.0 / 3.0 + 1e-9);
  EXPECT_NEAR(slowest.startSeconds, 8.0, 0.05);
  EXPECT_LT(slowestWindow(records, 30.0).fps, 0.0) << "a run shorter than the window has no window";
  EXPECT_NEAR(slowestWindow(std::vector<FrameRecord>(records.begin(), records.begin() + 300), 3.0, 1.0).fps, 30.0,
              1.0 / 3.0 + 1e-9);
}

TEST(FrameLog, AnUnwritablePathIsReported) {
  EXPECT_FALSE(writeFrameLogCsv({}, "/nonexistent-directory/frames.csv"));
}

}  // namespace
}  // namespace slime
