// Surfaces made afresh on a grid (core/geometry/surface_extraction.h): a sphere's signed distance gives
// back a closed, consistently wound surface on the sphere, enclosing its volume.
#include "core/bulk/normal_jumps.h"
#include "core/geometry/enclosed_solid.h"
#include "core/geometry/icosphere.h"
#include "core/geometry/surface_extraction.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
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
  EXPECT_NEAR(solid.volume / enclosedSolid(sphere).volume, 1.0, 0.02);  // the nets' vertices lie on chords
  EXPECT_LT(glm::length(solid.centroid - center), 1e-4);
}

// The smallest angle of any triangle, degrees.
double smallestAngle(const TriangleMesh& mesh) {
  double smallest = 180.0;
  for (const Triangle& t : mesh.triangles)
    for (int corner = 0; corner < 3; ++corner) {
      const glm::dvec3 p = mesh.positions[t[corner]];
      const glm::dvec3 u = mesh.positions[t[(corner + 1) % 3]] - p, v = mesh.positions[t[(corner + 2) % 3]] - p;
      const double cosine = glm::dot(u, v) / (glm::length(u) * glm::length(v));
      smallest = std::min(smallest, std::acos(std::clamp(cosine, -1.0, 1.0)) * 180.0 / std::numbers::pi);
    }
  return smallest;
}

// Marching tetrahedra cut a cell's tetrahedra near their corners into slivers (angles under a degree)
// whose normals jump by tens of degrees once smoothed; surface nets' triangles stay well shaped, and
// the ball's normals turn smoothly (the largest jump about the edge's angle at the centre, 2·l/r).
TEST(SurfaceExtraction, SphereHasNoSliversAndSmoothNormals) {
  const double radius = 0.04;
  const glm::dvec3 center(0.01, -0.02, 0.05);
  const TriangleMesh sphere = makeIcosphere(5, radius, center);
  const double spacing = 0.005;
  ScalarGrid grid = gridAround(center - glm::dvec3(radius), center + glm::dvec3(radius), spacing, 3.0 * spacing);
  signedDistanceOnGrid(sphere, grid);
  TriangleMesh mesh = extractSurface(grid);
  ASSERT_TRUE(isClosedManifold(mesh));
  taubinSmooth(mesh, 8);
  const NormalJumps jumps = normalJumps(mesh.positions, mesh.triangles);
  const double largest = jumps.largest * 180.0 / std::numbers::pi, angle = smallestAngle(mesh);
  TriangleMesh tetrahedra = extractSurfaceTetrahedra(grid);
  taubinSmooth(tetrahedra, 8);
  std::printf("sphere r %.0f mm on a %.0f mm grid: smallest angle %.1f deg, largest normal jump %.1f deg (marching tetrahedra: %.2f deg, %.1f deg)\n",
              radius * 1e3, spacing * 1e3, angle, largest, smallestAngle(tetrahedra),
              normalJumps(tetrahedra.positions, tetrahedra.triangles).largest * 180.0 / std::numbers::pi);
  EXPECT_GT(angle, 15.0);
  EXPECT_LT(largest, 20.0);
}

// Two grid points inside at diagonal corners of a cell face, the other two outside: the nets would
// join the two cells across that face by four triangles on one edge. The corner nearest zero changes
// side first, and the nets come out closed and manifold.
TEST(SurfaceExtraction, SaddleFaceIsResolvedBeforeTheNets) {
  ScalarGrid grid;
  grid.spacing = 0.01;
  grid.size = glm::ivec3(4, 4, 4);
  grid.values.assign(grid.count(), -1.0);
  grid.values[grid.index(1, 1, 1)] = 1.0;
  grid.values[grid.index(2, 2, 1)] = 1.0;
  grid.values[grid.index(2, 1, 1)] = -0.1;  // nearest zero of the outside pair
  EXPECT_FALSE(isClosedManifold(extractSurfaceNets(grid)));
  ScalarGrid resolved = grid;
  EXPECT_EQ(resolveSaddleFaces(resolved), 1u);
  EXPECT_EQ(resolveSaddleFaces(resolved), 0u);
  const TriangleMesh nets = extractSurfaceNets(resolved);
  EXPECT_TRUE(isClosedManifold(nets));
  EXPECT_GT(enclosedSolid(nets).volume, 0.0);
}

TEST(SurfaceExtraction, SmoothMaxIsAtLeastTheMaxAndEqualFarApart) {
  EXPECT_DOUBLE_EQ(smoothMax(1.0, -1.0, 0.1), 1.0);
  EXPECT_GE(smoothMax(0.0, 0.0, 0.1), 0.0);
  EXPECT_NEAR(smoothMax(0.0, 0.0, 0.1), 0.025, 1e-12);
}

}  // namespace
}  // namespace slime
