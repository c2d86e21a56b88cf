// SlimeGeometry's supporting triangles (a ray leaving through one cannot meet the slime again, so
// the tracer skips its query) against the brute-force oracle: every vertex against every
// triangle's plane.
#include "render/slime/slime_geometry.h"

#include "core/geometry/icosphere.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

namespace slime::testing {
namespace {

// The definition, by brute force: no vertex more than the tolerance above the triangle's plane.
std::vector<bool> supportingByBruteForce(const SlimeGeometry& geometry) {
  const float tolerance = SlimeGeometry::kConvexTolerance * geometry.boundRadius;
  std::vector<bool> result(geometry.triangles.size(), true);
  for (std::size_t f = 0; f < geometry.triangles.size(); ++f) {
    const glm::vec3 n = geometry.faceNormals[f], a = geometry.positions[geometry.triangles[f].x];
    for (std::size_t v = 0; v < geometry.vertexCount(); ++v)
      if (glm::dot(n, geometry.positions[v]) > glm::dot(n, a) + tolerance) result[f] = false;
  }
  return result;
}

void expectSupportingAsBruteForce(const TriangleMesh& mesh, const char* what, int expectedNonSupporting) {
  SlimeGeometry geometry;
  geometry.update(mesh.positions, mesh.triangles);
  const std::vector<bool> expected = supportingByBruteForce(geometry);
  int mismatches = 0, nonSupporting = 0;
  for (std::size_t f = 0; f < expected.size(); ++f) {
    nonSupporting += !expected[f];
    if (geometry.supports(static_cast<std::uint32_t>(f)) != expected[f] && ++mismatches <= 5)
      ADD_FAILURE() << what << ": triangle " << f << " supports " << geometry.supports(static_cast<std::uint32_t>(f))
                    << ", brute force " << expected[f];
  }
  EXPECT_EQ(mismatches, 0) << what;
  EXPECT_EQ(geometry.isConvex(), nonSupporting == 0) << what;
  if (expectedNonSupporting >= 0) {
    EXPECT_EQ(nonSupporting == 0, expectedNonSupporting == 0) << what << ": " << nonSupporting << " non-supporting";
  }
}

TEST(SlimeGeometry, SupportingTrianglesAreThoseWithTheWholeSlimeBelowTheirPlane) {
  const TriangleMesh ball = makeIcosphere(4, 0.04, {0.0, 0.0, 0.04});
  expectSupportingAsBruteForce(ball, "round ball", 0);

  TriangleMesh dented = ball;  // a press: the top pushed in by a quarter of the radius
  for (auto& p : dented.positions) {
    const double fromAxis = std::hypot(p.x, p.y);
    if (p.z > 0.06 && fromAxis < 0.02) p.z -= 0.01 * std::cos(fromAxis / 0.02 * 1.5707963);
  }
  expectSupportingAsBruteForce(dented, "dented top", 1);

  TriangleMesh necked = ball;  // a pinch: a waist below the top
  for (auto& p : necked.positions) {
    const double height = (p.z - 0.04) / 0.04, waist = 1.0 - 0.4 * std::exp(-std::pow((height - 0.5) / 0.15, 2.0));
    p.x *= waist;
    p.y *= waist;
  }
  expectSupportingAsBruteForce(necked, "necked", 1);

  TriangleMesh rough = ball;  // facets: every vertex moved by up to 0.5 % of the radius
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(-2e-4, 2e-4);
  for (auto& p : rough.positions) p += glm::dvec3(jitter(random), jitter(random), jitter(random));
  expectSupportingAsBruteForce(rough, "rough", -1);

  // A later frame of the same topology: the clusters are those of the first frame.
  SlimeGeometry geometry;
  geometry.update(ball.positions, ball.triangles);
  geometry.update(dented.positions, dented.triangles);
  const std::vector<bool> expected = supportingByBruteForce(geometry);
  for (std::size_t f = 0; f < expected.size(); ++f)
    ASSERT_EQ(geometry.supports(static_cast<std::uint32_t>(f)), expected[f]) << "dented after round, triangle " << f;
}

// The bounds tree from one level (a handful of vertices: a single cluster) to four (level 5:
// ~10,000 vertices), each against the brute force.
TEST(SlimeGeometry, EveryDepthOfTheBoundsTreeAgreesWithBruteForce) {
  for (int level : {0, 1, 2, 5}) {
    const TriangleMesh ball = makeIcosphere(level, 0.04, {0.0, 0.0, 0.04});
    TriangleMesh rough = ball;  // facets and a dent, so that some planes cut the body and some do not
    std::mt19937 random(11);
    std::uniform_real_distribution<double> jitter(-2e-4, 2e-4);
    for (auto& p : rough.positions) {
      p += glm::dvec3(jitter(random), jitter(random), jitter(random));
      const double fromAxis = std::hypot(p.x, p.y);
      if (p.z > 0.06 && fromAxis < 0.02) p.z -= 0.01 * std::cos(fromAxis / 0.02 * 1.5707963);
    }
    const std::string what = "level " + std::to_string(level);
    expectSupportingAsBruteForce(ball, (what + " ball").c_str(), 0);
    expectSupportingAsBruteForce(rough, (what + " rough and dented").c_str(), -1);
  }
}

TEST(SlimeGeometry, NoSlimeSupportsNothing) {
  SlimeGeometry geometry;
  geometry.update({}, {});
  EXPECT_FALSE(geometry.isConvex());
  EXPECT_FALSE(geometry.supports(0));
}

}  // namespace
}  // namespace slime::testing
