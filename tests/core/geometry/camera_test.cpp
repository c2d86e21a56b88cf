#include "core/geometry/camera.h"

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>

namespace slime {
namespace {

TEST(Camera, CentreRayIsTheViewDirection) {
  CameraSettings settings;
  settings.yaw = 30.0;
  settings.pitch = -15.0;
  const Camera camera = makeCamera(settings, 640, 480);
  const glm::dvec3 d = camera.rayDirection(0.5, 0.5);
  EXPECT_NEAR(glm::length(d - viewDirection(30.0, -15.0)), 0.0, 1e-12);
}

TEST(Camera, FrameIsOrthonormalAndRightHanded) {
  CameraSettings settings;
  settings.yaw = 123.0;
  settings.pitch = 40.0;
  const Camera c = makeCamera(settings, 100, 50);
  EXPECT_NEAR(glm::dot(c.forward, c.right), 0.0, 1e-12);
  EXPECT_NEAR(glm::dot(c.forward, c.up), 0.0, 1e-12);
  EXPECT_NEAR(glm::length(c.up), 1.0, 1e-12);
  EXPECT_GT(c.up.z, 0.0);
  EXPECT_NEAR(glm::length(glm::cross(c.right, c.forward) - c.up), 0.0, 1e-12);
}

TEST(Camera, TopEdgeRaySpansHalfTheVerticalFov) {
  CameraSettings settings;
  settings.yaw = 0.0;
  settings.pitch = 0.0;
  settings.fov = 60.0;
  const Camera camera = makeCamera(settings, 200, 100);
  const glm::dvec3 top = camera.rayDirection(0.5, 0.0);
  EXPECT_NEAR(std::asin(top.z), glm::radians(30.0), 1e-12);
  const glm::dvec3 left = camera.rayDirection(0.0, 0.5);
  EXPECT_GT(left.y, 0.0);  // looking along +x, left is +y
}

TEST(Camera, LookAtPointsTheCentreRayAtTheTarget) {
  CameraSettings settings;
  const glm::dvec3 eye{0.3, -0.4, 0.2}, target{0.0, 0.0, 0.04};
  lookAt(settings, eye, target);
  const glm::dvec3 d = makeCamera(settings, 64, 64).rayDirection(0.5, 0.5);
  EXPECT_NEAR(glm::length(d - glm::normalize(target - eye)), 0.0, 1e-12);
}

}  // namespace
}  // namespace slime
