#include "app/viewer/interaction.h"

#include "core/geometry/camera.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace slime {
namespace {

constexpr glm::ivec2 kWindow{480, 360};

Camera defaultCamera() { return makeCamera(CameraSettings{}, kWindow.x, kWindow.y); }

void expectNear(const glm::dvec3& actual, const glm::dvec3& expected, double tolerance) {
  EXPECT_NEAR(actual.x, expected.x, tolerance);
  EXPECT_NEAR(actual.y, expected.y, tolerance);
  EXPECT_NEAR(actual.z, expected.z, tolerance);
}

TEST(ProjectToWindow, InvertsTheRayThroughAPixel) {
  const Camera camera = defaultCamera();
  const glm::dvec2 cursor{123.0, 250.0};
  const glm::dvec3 point = camera.position + 0.3 * cursorRay(camera, cursor, kWindow);
  const auto projected = projectToWindow(camera, point, kWindow);
  ASSERT_TRUE(projected);
  EXPECT_NEAR(projected->x, cursor.x, 1e-6);
  EXPECT_NEAR(projected->y, cursor.y, 1e-6);
  EXPECT_FALSE(projectToWindow(camera, camera.position - camera.forward, kWindow));  // behind the eye
}

TEST(GrabInteraction, TheTargetStartsAtTheGrabbedPointAndFollowsTheCursorInThePlaneFacingTheCamera) {
  const Camera camera = defaultCamera();
  const glm::dvec2 cursor{240.0, 150.0};
  const glm::dvec3 point = camera.position + 0.2 * cursorRay(camera, cursor, kWindow);
  GrabInteraction grab;
  grab.begin(point, camera, cursor);
  ASSERT_TRUE(grab.active());
  expectNear(grab.target(camera, kWindow), point, 1e-12);

  grab.moveCursor({240.0, 60.0}, false, camera, kWindow);  // 90 pixels up
  const glm::dvec3 moved = grab.target(camera, kWindow);
  EXPECT_NEAR(glm::dot(moved - point, camera.forward), 0.0, 1e-12);  // still in the plane
  EXPECT_GT(moved.z, point.z + 0.01);                                // and higher up
  const auto projected = projectToWindow(camera, moved, kWindow);
  ASSERT_TRUE(projected);
  EXPECT_NEAR(projected->y, 60.0, 1e-6);  // under the cursor
  grab.end();
  EXPECT_FALSE(grab.active());
}

TEST(GrabInteraction, PressingPushesTheTargetAlongTheViewRayIntoTheBody) {
  const Camera camera = defaultCamera();
  const glm::dvec2 cursor{240.0, 150.0};
  const glm::dvec3 point = camera.position + 0.2 * cursorRay(camera, cursor, kWindow);
  GrabInteraction grab;
  grab.begin(point, camera, cursor);
  grab.pressBy(2.0);  // two wheel notches
  const glm::dvec3 pressed = grab.target(camera, kWindow);
  EXPECT_NEAR(glm::length(pressed - point), 2.0 * GrabInteraction::kPressPerNotch, 1e-12);
  EXPECT_GT(glm::length(pressed - camera.position), glm::length(point - camera.position));  // away from the eye

  // Shift-drag down presses further; the target keeps its place on screen.
  grab.moveCursor({240.0, 170.0}, true, camera, kWindow);
  EXPECT_GT(grab.pressDepth(), 2.0 * GrabInteraction::kPressPerNotch);
  const auto projected = projectToWindow(camera, grab.target(camera, kWindow), kWindow);
  ASSERT_TRUE(projected);
  EXPECT_NEAR(projected->y, 150.0, 1e-6);
}

}  // namespace
}  // namespace slime
