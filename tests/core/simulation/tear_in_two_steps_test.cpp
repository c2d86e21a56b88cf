// A tear spread over two steps (Simulation::tearPieces, BulkPiece::splitSurfaces then split): the parts'
// drawn surfaces are made at the state of the first step and carried to the state of the second, where
// the pieces are built, by maps fitted where they were made. A body that moved in between (here rotated,
// stretched and carried 5 cm) gets the surfaces the tear would have made there, to the grid's accuracy.
#include "core/bulk/piece_surface.h"
#include "core/bulk/surface_embedding.h"
#include "core/geometry/enclosed_solid.h"
#include "core/settings/settings_io.h"
#include "core/simulation/bulk_piece.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>

namespace slime {
namespace {

TEST(TearInTwoSteps, SurfacesMadeBeforeAreCarriedToTheStateNow) {
  const Settings settings = defaultSettings();
  const glm::dvec3 centre = settings.slime.position;
  const double support = kSmoothSupportSteps * settings.slime.radius / std::ldexp(1.0, settings.slime.resolution);
  BulkPiece before(buildBulkBody(settings.slime));
  before.rebuildModels(settings, Integrator::SymplecticEuler);
  TearPlan plan;
  plan.parts = 2;
  for (const Tetrahedron& t : before.body().mesh.tetrahedra) {
    const std::vector<glm::dvec3>& x = before.state().positions;
    plan.partOf.push_back((x[t.x].x + x[t.y].x + x[t.z].x + x[t.w].x) * 0.25 < centre.x ? 0u : 1u);
  }
  // Rotated 30° about z, stretched 1.2 along x and 1/1.2 along y, carried (5, 0, 2) cm: affine, det 1.
  const double c = std::cos(0.5236), s = std::sin(0.5236);
  const glm::dmat3 map = glm::dmat3(glm::dvec3(c, s, 0.0), glm::dvec3(-s, c, 0.0), glm::dvec3(0.0, 0.0, 1.0)) *
                         glm::dmat3(glm::dvec3(1.2, 0.0, 0.0), glm::dvec3(0.0, 1.0 / 1.2, 0.0), glm::dvec3(0.0, 0.0, 1.0));
  const glm::dvec3 carried(0.05, 0.0, 0.02);
  BulkPiece moved = before;  // copied before its drawn surface is first placed (and kept)
  for (glm::dvec3& x : moved.state().positions) x = centre + carried + map * (x - centre);
  const double spacing = 2.0 * meanEdgeLength(before.surface());

  const BulkPiece::SplitSurfaces early = before.splitSurfaces(plan, spacing);  // the first step, before the move
  const BulkPiece::SplitSurfaces late = moved.splitSurfaces(plan, spacing);    // as if made after it
  ASSERT_EQ(early.surfaces.size(), 2u);
  ASSERT_EQ(late.surfaces.size(), 2u);
  std::array<int, kHands> hands{};
  BulkPiece second = moved, fresh = moved;
  const auto carriedParts = second.split(early, support, hands);
  const auto freshParts = fresh.split(late, support, hands);
  ASSERT_EQ(carriedParts.size(), 2u);
  for (std::size_t part = 0; part < 2; ++part) {
    const EnclosedSolid a = enclosedSolid(carriedParts[part]->surface()), b = enclosedSolid(freshParts[part]->surface());
    std::printf("part %zu: carried %.4g m3 at (%.2f %.2f %.2f) mm, made there %.4g m3 at (%.2f %.2f %.2f) mm\n", part, a.volume,
                a.centroid.x * 1e3, a.centroid.y * 1e3, a.centroid.z * 1e3, b.volume, b.centroid.x * 1e3, b.centroid.y * 1e3, b.centroid.z * 1e3);
    EXPECT_NEAR(a.volume / b.volume, 1.0, 0.01);
    EXPECT_LT(glm::length(a.centroid - b.centroid), 1e-3);  // 0.3–0.4 mm: the grid does not turn with the body
  }
}

}  // namespace
}  // namespace slime
