// Merging (slime.mergeTime, core/simulation/merging.h): a piece torn off and pressed back onto the slime
// for a second fuses with it; two seconds later the seam leaves no crease on the drawn surface; five
// seconds after it is let go the slime has the aspect of one never torn; the volume is kept.
#include "core/bulk/normal_jumps.h"
#include "core/hands/grab.h"
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

struct DrawnCopy {
  std::vector<glm::dvec3> positions;
  std::vector<Triangle> triangles;
};

// The seam: the vertices of each of two drawn surfaces within `touch` of the other's.
std::vector<glm::dvec3> seamPoints(const DrawnCopy& a, const DrawnCopy& b, double touch) {
  std::vector<glm::dvec3> seam;
  for (const auto& [one, other] : {std::pair{&a, &b}, std::pair{&b, &a}})
    for (const glm::dvec3& p : one->positions)
      if (glm::length(nearestSurfacePoint(other->positions, other->triangles, p) - p) < touch) seam.push_back(p);
  return seam;
}

TEST(Merging, TornPiecePressedBackFusesAndRoundsUp) {
  Settings settings = defaultSettings();
  settings.slime.tearing = true;
  Simulation simulation(settings);
  ScenarioPlayer player(loadScenario(std::string(SLIME_SOURCE_DIR) + "/tests/scenarios/tear_off_and_press_back.json"));
  double beforeTear = 0.0, mergedAt = -1.0, lowest = 1e300, highest = 0.0;
  DrawnCopy pieces[2];
  std::vector<std::uint8_t> nearSeam;  // per drawn vertex of the merged piece: within kSeamReach of the seam
  constexpr double kTouch = 4e-3, kSeamReach = 12e-3;
  NormalJumps seam, whole;
  std::size_t seamPointCount = 0;
  while (simulation.time() < 8.6 - 1e-9) {
    player.advanceTo(simulation.time(), simulation, settings);
    const int tears = simulation.tears(), merges = simulation.merges();
    if (tears == 0 && simulation.stepCount() % 10 == 0) beforeTear = totalDrawnVolume(simulation);
    if (simulation.pieceCount() == 2)
      for (std::size_t p = 0; p < 2; ++p) pieces[p] = {simulation.piece(p).drawnPositions(), simulation.piece(p).drawnTriangles()};
    simulation.step();
    if (merges == 0 && simulation.merges() > 0) {
      mergedAt = simulation.time();
      const std::vector<glm::dvec3> points = seamPoints(pieces[0], pieces[1], kTouch);
      seamPointCount = points.size();
      nearSeam.assign(simulation.positions().size(), 0);
      for (std::size_t v = 0; v < nearSeam.size(); ++v)
        for (const glm::dvec3& p : points)
          if (glm::length(simulation.positions()[v] - p) < kSeamReach) nearSeam[v] = 1;
    }
    if (simulation.tears() > 0 && simulation.stepCount() % 50 == 0) {
      lowest = std::min(lowest, totalDrawnVolume(simulation));
      highest = std::max(highest, totalDrawnVolume(simulation));
    }
    if (mergedAt > 0.0 && std::abs(simulation.time() - (mergedAt + 2.0)) < 0.5e-3) {
      // Across the seam: the triangles whose corners all lay near it at the merge (the drawn surface's
      // vertices keep their numbers while it is carried).
      std::vector<Triangle> across;
      for (const Triangle& t : simulation.triangles())
        if (nearSeam[t.x] && nearSeam[t.y] && nearSeam[t.z]) across.push_back(t);
      seam = normalJumps(simulation.positions(), across);
      whole = normalJumps(simulation.positions(), simulation.triangles());
    }
  }
  ASSERT_EQ(simulation.tears(), 1);
  ASSERT_EQ(simulation.merges(), 1);
  EXPECT_EQ(simulation.pieceCount(), 1u);
  EXPECT_LT(mergedAt, 3.6) << "pressed together for a second, the pieces fuse while held";
  EXPECT_GT(seamPointCount, 20u) << "the pieces touched over a patch before they fused";
  EXPECT_GT(seam.edges, 100u);
  // Two seconds after the merge the seam is gone from the drawn surface: no normal jump over 10° across it.
  EXPECT_LT(inDegrees(seam.largest), 10.0);
  EXPECT_LT(inDegrees(whole.median), 4.0);
  // Five seconds after the hands let go (at 3.6 s), the aspect of a slime never torn.
  Simulation untorn(defaultSettings());
  while (untorn.time() < 8.6 - 1e-9) untorn.step();
  EXPECT_NEAR(simulation.metrics().aspect, untorn.metrics().aspect, 0.05);
  EXPECT_GT(lowest / beforeTear, 0.99);
  EXPECT_LT(highest / beforeTear, 1.01);
  EXPECT_NEAR(simulation.volume() / simulation.restVolume(), 1.0, 0.01);
  EXPECT_TRUE(simulation.divergences().empty());
  std::printf("merged at %.3f s; 2 s later across the seam (%zu edges): largest %.2f deg, 99th %.2f deg; whole surface: largest %.2f deg "
              "at z %.1f mm, 99th %.2f deg, median %.2f deg; aspect %.3f (untorn %.3f); drawn volume %.4f..%.4f of before the tear\n",
              mergedAt, seam.edges, inDegrees(seam.largest), inDegrees(seam.percentile99), inDegrees(whole.largest), whole.largestAt.z * 1e3,
              inDegrees(whole.percentile99), inDegrees(whole.median), simulation.metrics().aspect, untorn.metrics().aspect, lowest / beforeTear,
              highest / beforeTear);
}

}  // namespace
}  // namespace slime
