// The drawn level (slime.level) is a render setting: the bulk body's physics does the same work and
// reaches the same state at every level, and the drawn surface still rests on the floor it lands on.
#include "simulation_fixture.h"
#include "core/bulk/bulk_body.h"
#include "core/bulk/surface_embedding.h"
#include "core/settings/settings_io.h"
#include "core/simulation/simulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace slime {
namespace {

constexpr double kLanded = 0.4;  // s: the default drop lands at about 0.11 s and is in contact after

struct LevelRun {
  std::size_t floorPoints = 0;  // the floor points the contact read, summed over the steps
  std::vector<glm::dvec3> nodes;  // the body's nodes at the end
};

LevelRun runAtLevel(const std::string& integrator, int level) {
  Settings settings = defaultSettings();
  settings.sim.integrator = integrator;
  settings.slime.level = level;
  Simulation simulation(settings);
  LevelRun run;
  while (simulation.time() < kLanded - 1e-9) {
    simulation.step();
    run.floorPoints += floorPointsNearFloor(simulation.bulkBody());
  }
  run.nodes = simulation.state().positions;
  return run;
}

class DrawnLevel : public ::testing::TestWithParam<std::string> {};

// The landing and the contact after it, at drawn levels 2, 4 (the floor points' own) and 6: the
// floor contact reads as many points every step (it read the drawn vertices over the contact patch:
// 16 times as many at level 6, and the step cost 2.0× level 4's), and the body ends bitwise the same.
TEST_P(DrawnLevel, ThePhysicsDoesTheSameWorkAndReachesTheSameState) {
  ASSERT_EQ(floorContactLevel(defaultSettings().slime.resolution), kFloorContactLevel);
  const LevelRun reference = runAtLevel(GetParam(), kFloorContactLevel);
  EXPECT_GT(reference.floorPoints, 0u) << "the slime never came near the floor";
  for (int level : {2, 6}) {
    const LevelRun run = runAtLevel(GetParam(), level);
    EXPECT_EQ(run.floorPoints, reference.floorPoints) << "level " << level;
    EXPECT_TRUE(run.nodes == reference.nodes) << "level " << level << ": the body moved otherwise than at level "
                                              << kFloorContactLevel;
  }
}

// Two levels finer than the body's shells, at most level 4: the coarsest body (resolution 1, shell level 1)
// is held up at level 3, every finer one at level 4.
TEST(DrawnLevel, TheFloorPointsAreTwoLevelsFinerThanTheShellsAtMostFour) {
  EXPECT_EQ(floorContactLevel(1), 3);
  for (int shell : {2, 3, 4}) EXPECT_EQ(floorContactLevel(shell), 4) << "shell level " << shell;
  SlimeSettings slime = defaultSettings().slime;
  slime.resolution = 1;
  slime.level = 6;
  const BulkBody body = buildBulkBody(slime);
  EXPECT_EQ(body.floorPoints.nodes.size(), 642u) << "level 3's icosphere";
}

INSTANTIATE_TEST_SUITE_P(Integrators, DrawnLevel, ::testing::Values("symplectic_euler", "projective"));

double lowestOf(const std::vector<glm::dvec3>& points) {
  double lowest = points.front().z;
  for (const glm::dvec3& p : points) lowest = std::min(lowest, p.z);
  return lowest;
}

// Drawn at level 6 over the body that rests on level 4's floor points, the drawn surface lies as level
// 4's does: between the floor points, the element map dips under the floor by less than a tenth of a
// millimetre (the sphere's sagitta over level 4's edges is 0.02 mm at R = 4 cm; measured 0.03); the
// smooth map, which the drawn surface shows before its vertices are set on the floor where they dip
// under it, comes as near the floor as level 4's (both 0.55 mm under it); and the shape the report
// gives is level 4's.
TEST(DrawnLevel, AFinerDrawnSurfaceRestsOnTheFloorAsLevelFoursDoes) {
  Settings settings = defaultSettings();
  settings.slime.level = 6;
  Simulation fine(settings);
  settings.slime.level = kFloorContactLevel;
  Simulation coarse(settings);
  fixture::runFor(fine, 1.0);
  fixture::runFor(coarse, 1.0);
  std::vector<glm::dvec3> elements, smooth, coarseSmooth;
  placeByElements(fine.bulkBody().embedding, fine.state().positions, elements);
  placeEmbedded(fine.bulkBody().embedding, fine.state().positions, smooth);
  placeEmbedded(coarse.bulkBody().embedding, coarse.state().positions, coarseSmooth);
  EXPECT_GT(lowestOf(elements), -1e-4) << "the drawn surface sinks into the floor between the floor points";
  EXPECT_LT(lowestOf(elements), 1e-4) << "the drawn surface hovers over the floor";
  EXPECT_NEAR(lowestOf(smooth), lowestOf(coarseSmooth), 5e-5);
  EXPECT_EQ(fixture::lowestDrawnZ(fine), 0.0);
  const SlimeMetrics a = fine.metrics(), b = coarse.metrics();
  EXPECT_NEAR(a.height, b.height, 1e-4);
  EXPECT_NEAR(a.width, b.width, 1e-4);
}

}  // namespace
}  // namespace slime
