#include "core/geometry/icosphere.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <map>

namespace slime {
namespace {

TEST(Icosphere, CountsFollowTheSubdivisionFormulas) {
  for (int level = 0; level <= 5; ++level) {
    const TriangleMesh mesh = makeIcosphere(level, 1.0, {});
    const std::size_t fourToL = std::size_t{1} << (2 * level);
    EXPECT_EQ(mesh.triangles.size(), 20 * fourToL) << "level " << level;
    EXPECT_EQ(mesh.positions.size(), 10 * fourToL + 2) << "level " << level;
    EXPECT_EQ(uniqueEdges(mesh.triangles).size(), 30 * fourToL) << "level " << level;
  }
}

TEST(Icosphere, LevelFourMatchesTheSpec) {
  const TriangleMesh mesh = makeIcosphere(4, 0.04, {0, 0, 0.1});
  EXPECT_EQ(mesh.triangles.size(), 5120u);
  EXPECT_EQ(mesh.positions.size(), 2562u);
  EXPECT_EQ(uniqueEdges(mesh.triangles).size(), 7680u);
}

TEST(Icosphere, VerticesLieOnTheSphere) {
  const glm::dvec3 center{0.3, -0.2, 0.1};
  const TriangleMesh mesh = makeIcosphere(3, 0.04, center);
  for (const auto& p : mesh.positions) EXPECT_NEAR(glm::length(p - center), 0.04, 1e-12);
}

TEST(Icosphere, ClosedAndOutwardOriented) {
  const glm::dvec3 center{0, 0, 1};
  const TriangleMesh mesh = makeIcosphere(3, 2.0, center);
  // Closed and consistently oriented: every directed edge appears once, its reverse once.
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
  for (const Triangle& t : mesh.triangles)
    for (int i = 0; i < 3; ++i) ++directed[{t[i], t[(i + 1) % 3]}];
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1u);
  }
  for (const Triangle& t : mesh.triangles) {
    const glm::dvec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
    const glm::dvec3 normal = glm::cross(b - a, c - a);
    EXPECT_GT(glm::dot(normal, (a + b + c) / 3.0 - center), 0.0);
  }
}

TEST(Icosphere, RejectsLevelsOutsideTheRange) {
  EXPECT_THROW(makeIcosphere(-1, 1.0, {}), std::invalid_argument);
  EXPECT_THROW(makeIcosphere(kMaxLevel + 1, 1.0, {}), std::invalid_argument);
}

}  // namespace
}  // namespace slime
