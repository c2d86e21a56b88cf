// The generalised winding number: 1 inside a closed surface and 0 outside, 2 where two overlap; the
// fold's measure counts the overlap of two spheres as the lens between them.
#include "core/geometry/winding_number.h"

#include "core/geometry/icosphere.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace slime {
namespace {

TEST(WindingNumber, OneInsideAClosedSurfaceAndZeroOutside) {
  const TriangleMesh sphere = makeIcosphere(3, 1.0, glm::dvec3(0.0));
  const std::vector<SurfaceView> surfaces{SurfaceView(sphere)};
  EXPECT_NEAR(windingNumber(surfaces, glm::dvec3(0.0)), 1.0, 1e-9);
  EXPECT_NEAR(windingNumber(surfaces, glm::dvec3(0.3, -0.5, 0.2)), 1.0, 1e-9);
  EXPECT_NEAR(windingNumber(surfaces, glm::dvec3(2.0, 0.1, 0.0)), 0.0, 1e-9);
}

TEST(WindingNumber, TwoInsideTwoOverlappingSurfaces) {
  const TriangleMesh a = makeIcosphere(3, 1.0, glm::dvec3(0.0)), b = makeIcosphere(3, 1.0, glm::dvec3(1.0, 0.0, 0.0));
  const std::vector<SurfaceView> surfaces{SurfaceView(a), SurfaceView(b)};
  EXPECT_NEAR(windingNumber(surfaces, glm::dvec3(0.5, 0.0, 0.0)), 2.0, 1e-9);
  EXPECT_NEAR(windingNumber(surfaces, glm::dvec3(-0.5, 0.0, 0.0)), 1.0, 1e-9);
}

TEST(WindingNumber, TheGridCountsTheLensOfTwoOverlappingSpheresAndNothingOfOne) {
  const TriangleMesh a = makeIcosphere(3, 1.0, glm::dvec3(0.0)), b = makeIcosphere(3, 1.0, glm::dvec3(1.0, 0.0, 0.0));
  const std::vector<SurfaceView> one{SurfaceView(a)}, two{SurfaceView(a), SurfaceView(b)};
  EXPECT_EQ(insideTwiceOnGrid(one, 8, 0.0).insideTwice, 0u);
  EXPECT_EQ(insideTwiceUnderVertices(one, 0.01).insideTwice, 0u);
  // The lens of two unit spheres d = 1 apart: V = π (4 + d)(2 − d)² / 12 = 5π/12, in a 3 × 2 × 2 box.
  const InsideTwice measure = insideTwiceOnGrid(two, 16, 0.0);
  EXPECT_NEAR(measure.share(), 5.0 * std::numbers::pi / 12.0 / 12.0, 0.015);
  // Deeper than 0.2 from both surfaces, fewer points count, and none is nearer than that.
  const InsideTwice deep = insideTwiceOnGrid(two, 16, 0.2);
  EXPECT_LT(deep.insideTwice, measure.insideTwice);
  EXPECT_GT(deep.insideTwice, 0u);
  // Under the vertices: those of each sphere inside the other (about a third of each) count.
  const InsideTwice under = insideTwiceUnderVertices(two, 0.01);
  EXPECT_NEAR(under.share(), 0.25, 0.05);
}

}  // namespace
}  // namespace slime
