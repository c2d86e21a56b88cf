#include "app/viewer/camera_controller.h"

#include "core/geometry/camera.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace slime {
namespace {

FrameInput holding(CameraKey key, double seconds) {
  FrameInput input;
  input.elapsedSeconds = seconds;
  input.cameraKeys[static_cast<int>(key)] = true;
  return input;
}

TEST(CameraController, WMovesForwardAtTheSameSpeedWhateverTheFrameRate) {
  const CameraController controller;
  CameraSettings oneFrame, tenFrames;
  const glm::dvec3 start = oneFrame.position;
  const glm::dvec3 forward = viewDirection(oneFrame.yaw, oneFrame.pitch);
  EXPECT_TRUE(controller.applyKeys(holding(CameraKey::Forward, 1.0), oneFrame));
  for (int frame = 0; frame < 10; ++frame) controller.applyKeys(holding(CameraKey::Forward, 0.1), tenFrames);
  EXPECT_NEAR(glm::length(oneFrame.position - start), CameraController::kMoveSpeed, 1e-12);
  EXPECT_NEAR(glm::dot(oneFrame.position - start, forward), CameraController::kMoveSpeed, 1e-12);
  EXPECT_NEAR(glm::length(tenFrames.position - oneFrame.position), 0.0, 1e-12);
}

TEST(CameraController, TheSeedsKeysTurnTiltAndStrafe) {
  const CameraController controller;
  CameraSettings camera;
  controller.applyKeys(holding(CameraKey::TurnLeft, 1.0), camera);
  EXPECT_NEAR(camera.yaw, 90.0 + CameraController::kTurnSpeed, 1e-9);  // counter-clockwise seen from above
  controller.applyKeys(holding(CameraKey::TiltUp, 1.0), camera);
  EXPECT_NEAR(camera.pitch, -20.0 + CameraController::kTurnSpeed, 1e-9);
  controller.applyKeys(holding(CameraKey::TiltUp, 10.0), camera);
  EXPECT_EQ(camera.pitch, CameraController::kMaxPitch);  // never over the top

  CameraSettings strafed;
  controller.applyKeys(holding(CameraKey::Right, 1.0), strafed);
  EXPECT_NEAR(strafed.position.x, CameraSettings{}.position.x + CameraController::kMoveSpeed, 1e-12);  // yaw 90: right is +x
  EXPECT_FALSE(controller.applyKeys(FrameInput{}, strafed));  // nothing held, nothing moves
}

TEST(CameraController, RightDragOrbitsAroundTheCentreAtTheSameDistanceAndLooksAtIt) {
  CameraController controller;
  CameraSettings camera;
  const glm::dvec3 centre{0.0, 0.0, 0.04};
  const double distance = glm::length(camera.position - centre);
  controller.handleButton({MouseButton::Right, true, {100.0, 100.0}});
  EXPECT_TRUE(controller.applyMouse({160.0, 120.0}, {480, 360}, 0.0, centre, camera));
  EXPECT_NEAR(glm::length(camera.position - centre), distance, 1e-9);
  const glm::dvec3 toCentre = glm::normalize(centre - camera.position);
  EXPECT_NEAR(glm::dot(viewDirection(camera.yaw, camera.pitch), toCentre), 1.0, 1e-9);
  controller.handleButton({MouseButton::Right, false, {160.0, 120.0}});
  EXPECT_FALSE(controller.dragging());
}

TEST(CameraController, TheWheelZoomsTowardsTheCentreButNeverThroughIt) {
  CameraController controller;
  CameraSettings camera;
  const glm::dvec3 centre{0.0, 0.0, 0.04};
  const double distance = glm::length(camera.position - centre);
  controller.applyMouse({0.0, 0.0}, {480, 360}, 1.0, centre, camera);
  EXPECT_LT(glm::length(camera.position - centre), distance);
  controller.applyMouse({0.0, 0.0}, {480, 360}, 100.0, centre, camera);
  EXPECT_GE(glm::length(camera.position - centre), CameraController::kMinDistance * 0.5);
}

}  // namespace
}  // namespace slime
