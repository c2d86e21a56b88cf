// slime.level=auto: the sagitta table against the real icosphere, the projection, and the choice.
#include "core/geometry/icosphere.h"
#include "core/geometry/level_of_detail.h"
#include "core/settings/settings_io.h"
#include "core/simulation/simulation.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace slime {
namespace {

// 1 − min over faces of the distance from the centre to the face's plane, on the unit icosphere.
double measuredSagitta(int level) {
  const TriangleMesh mesh = makeIcosphere(level, 1.0, glm::dvec3(0.0));
  double nearest = 1.0;
  for (const Triangle& t : mesh.triangles) {
    const glm::dvec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
    nearest = std::min(nearest, std::abs(glm::dot(glm::normalize(glm::cross(b - a, c - a)), a)));
  }
  return 1.0 - nearest;
}

TEST(LevelOfDetail, SagittaTableMatchesTheIcosphere) {
  for (int level = 0; level <= 6; ++level) EXPECT_NEAR(icosphereSagitta(level), measuredSagitta(level), 1e-6 * (1 + level)) << level;
}

TEST(LevelOfDetail, SagittaQuartersPerLevel) {
  for (int level = 2; level < kMaxLevel + 3; ++level)
    EXPECT_NEAR(icosphereSagitta(level + 1) / icosphereSagitta(level), 0.25, 0.01) << level;
}

TEST(LevelOfDetail, ProjectionIsSagittaTimesPixelsPerMetre) {
  // 90° field of view: tan 45° = 1, so 1 m at distance 1 m spans H/2 pixels.
  EXPECT_NEAR(projectedSagittaPixels(3, 1.0, 1.0, 90.0, 600), icosphereSagitta(3) * 300.0, 1e-9);
  // Twice as far: half the pixels.
  EXPECT_NEAR(projectedSagittaPixels(4, 0.04, 0.5, 45.0, 564), 0.5 * projectedSagittaPixels(4, 0.04, 0.25, 45.0, 564), 1e-12);
}

TEST(LevelOfDetail, ChoosesTheSmallestLevelUnderTheThreshold) {
  const double radius = 0.04, distance = 0.228, fov = 45.0;
  const int height = 564;
  const int level = chooseLevel(radius, distance, fov, height, 0.25);
  EXPECT_LE(projectedSagittaPixels(level, radius, distance, fov, height), 0.25);
  ASSERT_GT(level, 0);
  EXPECT_GT(projectedSagittaPixels(level - 1, radius, distance, fov, height), 0.25);
}

TEST(LevelOfDetail, FartherOrSmallerNeedsFewerLevels) {
  const int near = chooseLevel(0.04, 0.2, 45.0, 564);
  EXPECT_LE(chooseLevel(0.04, 2.0, 45.0, 564), near);
  EXPECT_LE(chooseLevel(0.04, 0.2, 45.0, 120), near);
  EXPECT_GE(chooseLevel(0.04, 0.2, 45.0, 2160), near);
  EXPECT_EQ(chooseLevel(0.04, 1000.0, 45.0, 564), 0);  // a dot on screen
}

TEST(LevelOfDetail, DegenerateViewsGetTheFinestLevel) {
  EXPECT_EQ(chooseLevel(0.04, 0.03, 45.0, 564), kMaxLevel);  // eye inside the slime
  EXPECT_EQ(chooseLevel(0.04, 0.2, 45.0, 0), kMaxLevel);
  EXPECT_EQ(chooseLevel(0.04, 0.2, 0.0, 564), kMaxLevel);
  EXPECT_EQ(chooseLevel(0.04, 0.2, 45.0, 564, 0.0), kMaxLevel);  // nothing is exact
}

TEST(EffectiveLevel, AutoPicksLevelFourAtTheDefaultViewAndFollowsTheDistance) {
  Settings settings = defaultSettings();
  EXPECT_EQ(effectiveLevel(settings), settings.slime.level);  // not auto: the level as set
  settings.slime.autoLevel = true;
  EXPECT_EQ(effectiveLevel(settings), 4);  // what `slime bench accuracy` found invisible here
  settings.camera.position *= 4.0;         // four times as far: a quarter of the pixels across
  EXPECT_LT(effectiveLevel(settings), 4);
  settings.camera.position = glm::dvec3(0.0, -0.06, 0.04);  // close up
  EXPECT_GT(effectiveLevel(settings), 4);
}

TEST(EffectiveLevel, SimulationBuildsTheAutoLevel) {
  Settings settings = defaultSettings();
  applyOverride(settings, "slime.level=auto");
  settings.camera.position *= 4.0;
  const Simulation simulation(settings);
  EXPECT_EQ(simulation.settings().slime.level, effectiveLevel(settings));
  const std::size_t fourToL = std::size_t{1} << (2 * effectiveLevel(settings));
  EXPECT_EQ(simulation.triangles().size(), 20 * fourToL);
}

TEST(VisibleMotion, LargestDisplacementSeenAtTheNearestDepth) {
  // A unit-radius ball 3 m in front of the eye: its nearest point is 2 m away, where with a 90° field
  // of view on 600 pixels one metre spans 150 pixels.
  const TriangleMesh mesh = makeIcosphere(2, 1.0, glm::dvec3(0.0, 3.0, 0.0));
  std::vector<glm::dvec3> moved = mesh.positions;
  EXPECT_EQ(largestMotionPixels(mesh.positions, moved, glm::dvec3(0.0), 90.0, 600), 0.0);
  moved[5] += glm::dvec3(0.0, 0.0, 1e-3);  // the largest of several moves counts
  moved[7] += glm::dvec3(2e-4, 0.0, 0.0);
  EXPECT_NEAR(largestMotionPixels(mesh.positions, moved, glm::dvec3(0.0), 90.0, 600), 0.15, 1e-4);  // the move shifts the bound by < 1 mm
}

TEST(VisibleMotion, UnboundedWhenTheMeshChangedOrTheEyeIsInside) {
  const TriangleMesh mesh = makeIcosphere(1, 1.0, glm::dvec3(0.0, 3.0, 0.0));
  const TriangleMesh finer = makeIcosphere(2, 1.0, glm::dvec3(0.0, 3.0, 0.0));
  EXPECT_TRUE(std::isinf(largestMotionPixels(mesh.positions, finer.positions, glm::dvec3(0.0), 45.0, 564)));
  EXPECT_TRUE(std::isinf(largestMotionPixels({}, {}, glm::dvec3(0.0), 45.0, 564)));
  EXPECT_TRUE(std::isinf(largestMotionPixels(mesh.positions, mesh.positions, glm::dvec3(0.0, 3.5, 0.0), 45.0, 564)));
  std::vector<glm::dvec3> broken = mesh.positions;
  broken[0].x = std::nan("");
  EXPECT_TRUE(std::isinf(largestMotionPixels(mesh.positions, broken, glm::dvec3(0.0), 45.0, 564)));
}

}  // namespace
}  // namespace slime
