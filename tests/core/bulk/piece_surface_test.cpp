// A drawn surface cut in two (core/bulk/piece_surface.h) and the bodies made of the two halves
// (sub_body.h): away from the cut each half's surface is the ball's (no pop), together they enclose
// the ball's volume, and the halves' bodies keep the rest volume, the mass and the Maxwell states.
#include "core/bulk/bulk_body.h"
#include "core/bulk/piece_surface.h"
#include "core/bulk/sub_body.h"
#include "core/bulk/surface_embedding.h"
#include "core/geometry/enclosed_solid.h"
#include "core/settings/settings_io.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

namespace slime {
namespace {

TEST(PieceSurface, HalvesMatchTheBallAwayFromTheCut) {
  const Settings settings = defaultSettings();
  const BulkBody body = buildBulkBody(settings.slime);
  std::vector<glm::dvec3> drawn;
  placeEmbedded(body.embedding, body.state.positions, drawn);
  const SurfaceView ball(drawn, body.drawn.triangles);
  std::vector<std::uint32_t> partOf(body.mesh.tetrahedra.size());
  const glm::dvec3 center = settings.slime.position;
  for (std::size_t e = 0; e < partOf.size(); ++e) {
    const Tetrahedron& t = body.mesh.tetrahedra[e];
    const glm::dvec3 c = 0.25 * (body.state.positions[t.x] + body.state.positions[t.y] + body.state.positions[t.z] + body.state.positions[t.w]);
    partOf[e] = c.x < center.x ? 0 : 1;
  }
  const double spacing = 2.0 * meanEdgeLength(ball);
  const std::vector<TriangleMesh> halves = splitDrawnSurface(ball, body, partOf, 2, spacing);
  ASSERT_EQ(halves.size(), 2u);
  const double radius = settings.slime.radius;
  double pop = 0.0, volume = 0.0;
  for (std::uint32_t part = 0; part < 2; ++part) {
    volume += enclosedSolid(halves[part]).volume;
    for (const glm::dvec3& p : halves[part].positions) {
      EXPECT_LT(part == 0 ? p.x - center.x : center.x - p.x, 0.012);  // the cut follows the elements' faces
      if (std::abs(p.x - center.x) > 0.02) pop = std::max(pop, std::abs(glm::length(p - center) - radius));
    }
  }
  EXPECT_LT(pop, 0.5e-3) << "the drawn surface away from the cut moved";
  // The cut's rim is rounded (a smooth min of two spacings): 6 % short, which offsetToVolume gives back
  // (the tear moves each part's surface along its normals to its share, by under a millimetre here).
  EXPECT_NEAR(volume / enclosedSolid(ball).volume, 1.0, 0.08);
  TriangleMesh half = halves[0];
  const double target = 0.5 * enclosedSolid(ball).volume;
  offsetToVolume(half, target);
  EXPECT_NEAR(enclosedSolid(half).volume / target, 1.0, 1e-4);
}

TEST(SubBody, HalvesKeepRestVolumeMassAndMaxwellStates) {
  const Settings settings = defaultSettings();
  BulkBody body = buildBulkBody(settings.slime);
  std::vector<std::uint32_t> left, right;
  for (std::uint32_t e = 0; e < body.mesh.tetrahedra.size(); ++e) {
    const Tetrahedron& t = body.mesh.tetrahedra[e];
    (body.mesh.positions[t.x].x + body.mesh.positions[t.y].x + body.mesh.positions[t.z].x + body.mesh.positions[t.w].x < 4.0 * settings.slime.position.x ? left : right).push_back(e);
  }
  const double density = body.totalMass / body.restVolume;
  double restVolume = 0.0, mass = 0.0;
  for (const auto* half : {&left, &right}) {
    std::vector<std::uint32_t> partNode, order;
    const BulkBody part = assembleBody(partsOf(body, *half, partNode), settings.slime, density, body.mesh.shellLevel, order);
    restVolume += part.restVolume;
    mass += part.totalMass;
    EXPECT_EQ(part.mesh.tetrahedra.size(), half->size());
    // Its surface closes (its volume is its tetrahedra's) over its first nodes.
    double tetrahedra = 0.0;
    for (const Tetrahedron& t : part.mesh.tetrahedra)
      tetrahedra += tetrahedronVolume(part.state.positions[t.x], part.state.positions[t.y], part.state.positions[t.z], part.state.positions[t.w]);
    EXPECT_NEAR(enclosedSolid(SurfaceView(part.state.positions, part.mesh.surface)).volume / tetrahedra, 1.0, 1e-9);
    for (const Triangle& t : part.mesh.surface)
      for (int corner = 0; corner < 3; ++corner) EXPECT_LT(t[corner], part.mesh.surfaceNodes);
    for (std::size_t k = 0; k < half->size(); ++k)
      EXPECT_EQ(maxwellInverse(part, k), maxwellInverse(body, (*half)[k]));
  }
  EXPECT_NEAR(restVolume / body.restVolume, 1.0, 1e-12);
  EXPECT_NEAR(mass / body.totalMass, 1.0, 1e-12);
}

// A drawn surface made afresh has its smooth map fitted a few vertices a step (BulkPiece::endStep):
// the element map places it meanwhile, and the map fitted over the steps is the one fitted at once.
TEST(SubBody, SmoothMapFittedOverStepsIsTheFitAtOnce) {
  const SlimeSettings slime = defaultSettings().slime;
  const BulkBody body = buildBulkBody(slime);
  const double support = kSmoothSupportSteps * slime.radius / std::ldexp(1.0, slime.resolution);
  TetMesh reference;
  reference.positions = body.state.positions;
  SurfaceEmbedding atOnce = body.embedding, overSteps = body.embedding;
  embedSmoothly(reference, body.drawn.positions, support, atOnce);
  beginSmoothFit(body.state.positions, body.drawn.positions, support, overSteps);
  std::vector<glm::dvec3> moved = body.state.positions, placed, expected;
  for (glm::dvec3& x : moved) x += glm::dvec3(0.3 * x.y * x.y, 0.0, 0.2 * x.x);  // not affine: the maps differ
  int steps = 1;
  for (constexpr std::size_t kPerStep = 100; !continueSmoothFit(overSteps, kPerStep); ++steps) {
    placeEmbedded(overSteps, moved, placed);
    placeByElements(overSteps, moved, expected);
    ASSERT_EQ(placed, expected) << "step " << steps << ": the element map places the surface until the fit is done";
  }
  EXPECT_EQ(steps, static_cast<int>((body.drawn.positions.size() + 99) / 100));
  ASSERT_EQ(overSteps.smoothStart, atOnce.smoothStart);
  ASSERT_EQ(overSteps.smoothTerms.size(), atOnce.smoothTerms.size());
  for (std::size_t k = 0; k < atOnce.smoothTerms.size(); ++k) {
    EXPECT_EQ(overSteps.smoothTerms[k].node, atOnce.smoothTerms[k].node);
    EXPECT_EQ(overSteps.smoothTerms[k].weight, atOnce.smoothTerms[k].weight);
  }
  placeEmbedded(overSteps, moved, placed);
  placeEmbedded(atOnce, moved, expected);
  EXPECT_EQ(placed, expected);
  placeByElements(overSteps, moved, expected);
  EXPECT_NE(placed, expected);
}

// A merged piece's rest shape is derived again as a ball (rebaseRestTowardBall): re-based, the body's
// stress is what it was; its long-term branch flowed all the way to the new reference, a body squashed
// into an oblate ellipsoid is free of stress as the ball again (the affine part of the map undoes the
// squash), and its rest volume is kept.
TEST(SubBody, RestDerivedAgainIsABallAndKeepsTheStressNow) {
  const Settings settings = defaultSettings();
  BulkBody body = buildBulkBody(settings.slime);
  const glm::dvec3 centre = settings.slime.position;
  const glm::dmat3 squash(glm::dvec3(1.25, 0.0, 0.0), glm::dvec3(0.0, 1.25, 0.0), glm::dvec3(0.0, 0.0, 0.64));  // det 1
  for (std::size_t i = 0; i < body.state.positions.size(); ++i) body.state.positions[i] = centre + squash * (body.mesh.positions[i] - centre);
  std::vector<std::uint32_t> all(body.mesh.tetrahedra.size()), partNode, order;
  std::iota(all.begin(), all.end(), 0u);
  const double density = body.totalMass / body.restVolume;
  BodyParts parts = partsOf(body, all, partNode);
  const BulkBody before = assembleBody(parts, settings.slime, density, body.mesh.shellLevel, order);
  rebaseRestTowardBall(parts);
  BulkBody rebased = assembleBody(parts, settings.slime, density, body.mesh.shellLevel, order);
  const double squashed = bulkElasticEnergy(before, before.state.positions);
  ASSERT_GT(squashed, 0.0);
  EXPECT_NEAR(bulkElasticEnergy(rebased, rebased.state.positions) / squashed, 1.0, 1e-6) << "re-basing adds no stress";
  EXPECT_NEAR(rebased.restVolume / body.restVolume, 1.0, 1e-9);
  relaxLongTermTowardReference(rebased, 1.0);
  const double asBall = bulkElasticEnergy(rebased, rebased.mesh.positions);  // the nodes where the ball had them
  std::printf("squashed %.3g J; flowed to the new reference: %.3g J as the ball (%.2f %%)\n", squashed, asBall, 100.0 * asBall / squashed);
  EXPECT_LT(asBall / squashed, 0.05);
}

}  // namespace
}  // namespace slime
