#include "app/viewer/physics_clock.h"

#include <gtest/gtest.h>

namespace slime {
namespace {

TEST(PhysicsClock, OneSecondOfWallTimeIsOneThousandStepsOfOneMillisecondWhateverTheFrameRate) {
  for (int framesPerSecond : {7, 30, 60, 144}) {
    PhysicsClock clock;
    int steps = 0;
    for (int frame = 0; frame < framesPerSecond; ++frame) steps += clock.stepsFor(1.0 / framesPerSecond, 1.0, 0.001);
    EXPECT_NEAR(steps, 1000, 1) << framesPerSecond << " fps";
    EXPECT_EQ(clock.droppedSeconds(), 0.0);
  }
}

TEST(PhysicsClock, TheRemainderCarriesOverToTheNextFrame) {
  PhysicsClock clock;
  EXPECT_EQ(clock.stepsFor(0.0015, 1.0, 0.001), 1);
  EXPECT_EQ(clock.stepsFor(0.0015, 1.0, 0.001), 2);  // 0.5 ms left over plus 1.5 ms
}

TEST(PhysicsClock, TimeScaleScalesTheSimulatedTime) {
  PhysicsClock clock;
  EXPECT_EQ(clock.stepsFor(0.1, 0.5, 0.001), 50);
  EXPECT_EQ(clock.stepsFor(0.1, 2.0, 0.001), 200);
}

TEST(PhysicsClock, ASlowFrameIsCappedAndItsBacklogDroppedSoTheNextFrameIsNotSlowerStill) {
  PhysicsClock clock;
  const int capped = clock.stepsFor(3.0, 1.0, 0.001);
  EXPECT_EQ(capped, static_cast<int>(PhysicsClock::kMaxCatchUpSeconds / 0.001));
  EXPECT_NEAR(clock.droppedSeconds(), 3.0 - PhysicsClock::kMaxCatchUpSeconds, 1e-9);
  EXPECT_EQ(clock.stepsFor(0.01, 1.0, 0.001), 10);  // no backlog left to catch up on
}

// A frame whose time budget ran out gives its unrun steps back: the next frames step them (in slices of
// their own budget), and only what exceeds kMaxCatchUpSeconds is dropped.
TEST(PhysicsClock, StepsGivenBackAreSteppedByTheNextFrames) {
  PhysicsClock clock;
  const int given = clock.stepsFor(0.1, 1.0, 0.001);
  ASSERT_EQ(given, 100);
  clock.giveBack(70, 0.001);  // the budget ran out after 30
  EXPECT_EQ(clock.droppedSeconds(), 0.0);
  EXPECT_NEAR(clock.stepsFor(0.01, 1.0, 0.001), 80, 1);  // the 70 given back and the frame's own 10
  clock.giveBack(400, 0.001);  // more than kMaxCatchUpSeconds: the excess is dropped
  EXPECT_NEAR(clock.droppedSeconds(), 0.4 - PhysicsClock::kMaxCatchUpSeconds, 1e-9);
  EXPECT_EQ(clock.stepsFor(0.0, 1.0, 0.001), 0);  // no wall time: nothing to step, the backlog waits
  EXPECT_EQ(clock.stepsFor(1e-6, 1.0, 0.001), static_cast<int>(PhysicsClock::kMaxCatchUpSeconds / 0.001));
}

TEST(PhysicsClock, NoTimeOrABadStepGivesNoSteps) {
  PhysicsClock clock;
  EXPECT_EQ(clock.stepsFor(0.0, 1.0, 0.001), 0);
  EXPECT_EQ(clock.stepsFor(0.1, 1.0, 0.0), 0);
  EXPECT_EQ(clock.stepsFor(-1.0, 1.0, 0.001), 0);
}

}  // namespace
}  // namespace slime
