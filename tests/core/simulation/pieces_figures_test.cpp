// What `slime sim` reports of the pieces and of the shape: each piece's volume and centroid from its
// drawn surface (Simulation::pieceSolids), and the shape figures (SlimeMetrics) from the drawn surfaces
// of every piece. Nothing makes a second piece yet (tearing is to come), so the slime of two pieces
// here is two membrane balls given to Simulation as two bodies.
#include "simulation_fixture.h"

#include "core/geometry/enclosed_solid.h"
#include "core/membrane/slime_body.h"
#include "core/settings/settings_io.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace slime {
namespace {

// Two membrane balls of radius 3 and 2 cm, 12 cm apart, resting above the floor.
Simulation twoBalls() {
  Settings settings = defaultSettings();
  settings.slime.model = "membrane";
  settings.slime.level = 3;
  std::vector<SlimeBody> bodies;
  settings.slime.radius = 0.03;
  settings.slime.position = {-0.06, 0.0, 0.05};
  bodies.push_back(buildSlimeBody(settings.slime));
  settings.slime.radius = 0.02;
  settings.slime.position = {0.06, 0.01, 0.04};
  bodies.push_back(buildSlimeBody(settings.slime));
  return Simulation(settings, std::move(bodies));
}

struct Box {
  glm::dvec3 low{std::numeric_limits<double>::infinity()}, high{-std::numeric_limits<double>::infinity()};
};

Box boxOf(const std::vector<SurfaceView>& surfaces) {
  Box box;
  for (const SurfaceView& surface : surfaces)
    for (const glm::dvec3& p : surface.positions) {
      box.low = glm::min(box.low, p);
      box.high = glm::max(box.high, p);
    }
  return box;
}

// A ball's enclosed volume and centroid, against the closed forms: an icosphere of level 3 inscribed in
// a sphere of radius r holds a little less than 4/3 π r³ (0.6 % less at level 3), its centroid the centre.
TEST(EnclosedSolid, AnIcosphereHoldsNearlyTheBallAndCentresOnIt) {
  const glm::dvec3 centre(0.3, -0.2, 0.1);
  const TriangleMesh ball = makeIcosphere(3, 0.05, centre);
  const EnclosedSolid solid = enclosedSolid(ball);
  const double exact = 4.0 / 3.0 * std::numbers::pi * std::pow(0.05, 3);
  EXPECT_LT(solid.volume, exact);
  EXPECT_GT(solid.volume, 0.99 * exact);
  EXPECT_LT(glm::length(solid.centroid - centre), 1e-12);
  // Not the mean of the vertices: moved off-centre, the cap's solid centroid follows the volume.
  TriangleMesh egg = ball;
  for (glm::dvec3& p : egg.positions)
    if (p.z > centre.z) p.z = centre.z + 2.0 * (p.z - centre.z);  // upper half stretched twice
  const EnclosedSolid stretched = enclosedSolid(egg);
  // A half ball of radius r holds V/2 with its centroid 3r/8 above the cut; stretched twice, V at 3r/4.
  // The whole: (V · 3r/4 − V/2 · 3r/8) / (3V/2) = 3r/8 above the centre, where the mean of the vertices
  // lies near r/4. Faceted, and the icosphere's triangles straddle the cut: within 3 %.
  EXPECT_NEAR(stretched.centroid.z - centre.z, 3.0 * 0.05 / 8.0, 0.03 * 3.0 * 0.05 / 8.0);
  EXPECT_NEAR(stretched.volume, 1.5 * solid.volume, 0.03 * solid.volume);
}

TEST(PiecesFigures, EachPieceHasItsOwnVolumeAndCentroid) {
  Simulation simulation = twoBalls();
  ASSERT_EQ(simulation.pieceCount(), 2u);
  fixture::runFor(simulation, 0.05);
  const std::vector<EnclosedSolid> solids = simulation.pieceSolids();
  ASSERT_EQ(solids.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    const Piece& piece = simulation.piece(k);
    // The membrane draws its own points: the drawn volume is the piece's.
    EXPECT_DOUBLE_EQ(solids[k].volume, piece.volume()) << "piece " << k;
    EXPECT_NEAR(solids[k].volume, piece.restVolume(), 0.05 * piece.restVolume()) << "piece " << k;
  }
  EXPECT_NEAR(solids[0].centroid.x, -0.06, 0.005);
  EXPECT_NEAR(solids[1].centroid.x, 0.06, 0.005);
  EXPECT_NEAR(solids[1].centroid.y, 0.01, 0.005);
  EXPECT_GT(solids[0].volume, 3.0 * solids[1].volume);  // (3/2)³ = 3.4
}

// The shape covers both pieces, the volume ratio is the summed volume over the summed rest volume, the
// kinetic energy the sum and the speed the faster piece's.
TEST(PiecesFigures, MetricsCoverEveryPiece) {
  Simulation simulation = twoBalls();
  fixture::runFor(simulation, 0.05);
  const SlimeMetrics metrics = simulation.metrics();
  const Box box = boxOf(simulation.surfaces());
  EXPECT_EQ(metrics.width, std::max(box.high.x - box.low.x, box.high.y - box.low.y));
  EXPECT_EQ(metrics.height, box.high.z - box.low.z);
  EXPECT_EQ(metrics.minZ, box.low.z);
  EXPECT_GT(metrics.width, 0.12 + 0.03 + 0.02 - 0.005);  // from the left ball's left to the right one's right
  const SlimeMetrics left = simulation.piece(0).metrics(), right = simulation.piece(1).metrics();
  EXPECT_DOUBLE_EQ(metrics.kineticEnergy, left.kineticEnergy + right.kineticEnergy);
  EXPECT_GT(right.kineticEnergy, 0.0);
  EXPECT_EQ(metrics.maxSpeed, std::max(left.maxSpeed, right.maxSpeed));
  const double volume = simulation.piece(0).volume() + simulation.piece(1).volume();
  const double rest = simulation.piece(0).restVolume() + simulation.piece(1).restVolume();
  EXPECT_DOUBLE_EQ(metrics.volumeRatio, volume / rest);
}

// The bulk body's shape figures are the drawn surface's, exactly: the figures the exported mesh gives.
// (The body's outer nodes, which they came from before, lie 0.3-0.7 mm from the drawn surface.)
TEST(PiecesFigures, ShapeIsTheDrawnSurfaces) {
  Settings settings = defaultSettings();
  settings.slime.level = 3;
  Simulation simulation(settings);
  fixture::runFor(simulation, 0.5);  // fallen and pressed onto the floor
  const SlimeMetrics metrics = simulation.metrics();
  const Box box = boxOf(simulation.surfaces());
  EXPECT_EQ(metrics.height, box.high.z - box.low.z);
  EXPECT_EQ(metrics.width, std::max(box.high.x - box.low.x, box.high.y - box.low.y));
  EXPECT_EQ(metrics.minZ, box.low.z);
  EXPECT_EQ(metrics.aspect, metrics.height / metrics.width);
}

TEST(PiecesFigures, NoBodiesIsRefused) {
  try {
    Simulation simulation(defaultSettings(), std::vector<SlimeBody>{});
    FAIL() << "a Simulation of no pieces was made";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("at least one piece"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace slime
