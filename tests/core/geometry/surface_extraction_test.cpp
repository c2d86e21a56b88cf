// Surfaces made afresh on a grid (core/geometry/surface_extraction.h): a sphere's signed distance gives
// back a closed, consistently wound surface on the sphere, enclosing its volume.
#include "core/geometry/enclosed_solid.h"
#include "core/geometry/icosphere.h"
#include "core/geometry/surface_extraction.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <utility>

namespace slime {
namespace {

TEST(SurfaceExtraction, SphereComesBackClosedAndOnTheSphere) {
  const double radius = 0.04;
  const glm::dvec3 center(0.01, -0.02, 0.05);
  const TriangleMesh sphere = makeIcosphere(5, radius, center);
  const double spacing = 0.005;
  ScalarGrid grid = gridAround(center - glm::dvec3(radius), center + glm::dvec3(radius), spacing, 3.0 * spacing);
  signedDistanceOnGrid(sphere, grid);
  TriangleMesh mesh = extractSurface(grid);
  taubinSmooth(mesh, 4);
  ASSERT_GT(mesh.triangles.size(), 100u);
  // Closed and consistently wound: every directed edge once, and its reverse once.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (const Triangle& t : mesh.triangles)
    for (int e = 0; e < 3; ++e) ++edges[{t[e], t[(e + 1) % 3]}];
  for (const auto& [edge, count] : edges) {
    ASSERT_EQ(count, 1);
    ASSERT_EQ(edges.count({edge.second, edge.first}), 1u);
  }
  double farthest = 0.0;
  for (const glm::dvec3& p : mesh.positions) farthest = std::max(farthest, std::abs(glm::length(p - center) - radius));
  EXPECT_LT(farthest, 0.3e-3);
  const EnclosedSolid solid = enclosedSolid(mesh);
  EXPECT_NEAR(solid.volume / enclosedSolid(sphere).volume, 1.0, 0.01);
  EXPECT_LT(glm::length(solid.centroid - center), 1e-4);
}

TEST(SurfaceExtraction, SmoothMaxIsAtLeastTheMaxAndEqualFarApart) {
  EXPECT_DOUBLE_EQ(smoothMax(1.0, -1.0, 0.1), 1.0);
  EXPECT_GE(smoothMax(0.0, 0.0, 0.1), 0.0);
  EXPECT_NEAR(smoothMax(0.0, 0.0, 0.1), 0.025, 1e-12);
}

}  // namespace
}  // namespace slime
