// The drawn surface stays smooth where the body bends: under a pinch that lifts the slime by its top
// and under a press into its top, at the default resolution, the largest angle between neighbouring
// drawn triangles' normals (normal_jumps.h) stays close to what the drawn level's own curvature gives,
// with no creases along the body's elements (issue 29 item 4). The metric itself is checked on shapes
// whose answer is known.
#include "core/bulk/normal_jumps.h"
#include "core/settings/settings_io.h"
#include "core/scene/simulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace slime {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

void runFor(Simulation& simulation, double seconds) {
  const double end = simulation.time() + seconds - 1e-9;
  while (simulation.time() < end) simulation.step();
}

glm::dvec3 topOf(const Simulation& simulation) {
  const std::vector<glm::dvec3>& x = simulation.positions();
  return *std::max_element(x.begin(), x.end(), [](const auto& a, const auto& b) { return a.z < b.z; });
}

// Moves the grab target from `from` by `offset` over `duration`, then holds it for `hold`.
void dragOver(Simulation& simulation, const glm::dvec3& from, const glm::dvec3& offset, double duration, double hold) {
  const double start = simulation.time();
  while (simulation.time() < start + duration + hold - 1e-9) {
    simulation.dragTo(from + offset * std::min(1.0, (simulation.time() - start) / duration));
    simulation.step();
  }
}

NormalJumps report(const char* what, const Simulation& simulation) {
  const NormalJumps jumps = normalJumps(simulation.positions(), simulation.triangles());
  std::printf("%s: normal jump largest %.1f°, 99th percentile %.1f°, median %.2f° over %zu edges\n", what,
              jumps.largest / kDegree, jumps.percentile99 / kDegree, jumps.median / kDegree, jumps.edges);
  return jumps;
}

}  // namespace

// A flat fan has no jump; a tent folded by 90° has one of 90° on its ridge.
TEST(NormalJumps, FlatIsZeroAndAFoldIsItsAngle) {
  const std::vector<glm::dvec3> flat{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<Triangle> pair{{0, 1, 2}, {0, 2, 3}};
  NormalJumps jumps = normalJumps(flat, pair);
  EXPECT_EQ(jumps.edges, 1u);
  EXPECT_NEAR(jumps.largest, 0.0, 1e-12);
  const std::vector<glm::dvec3> tent{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  // Triangles (0,1,2) in z = 0 and (0,3,1) in y = 0 share the edge 0-1; their normals are +z and −y.
  jumps = normalJumps(tent, {{0, 1, 2}, {0, 3, 1}});
  EXPECT_NEAR(jumps.largest, 0.5 * std::numbers::pi, 1e-12);
}

// The icosphere's jumps are its level's curvature: about its edge over its radius.
TEST(NormalJumps, AnIcosphereJumpsByItsEdgeOverItsRadius) {
  const TriangleMesh sphere = makeIcosphere(4, 0.04, glm::dvec3(0.0));
  const NormalJumps jumps = normalJumps(sphere.positions, sphere.triangles);
  EXPECT_EQ(jumps.edges, sphere.triangles.size() * 3 / 2);
  EXPECT_GT(jumps.largest, 2.0 * kDegree);
  EXPECT_LT(jumps.largest, 6.0 * kDegree);
}

TEST(SmoothSurface, PinchAndPress) {
  const Settings settings = defaultSettings();
  Simulation rest(settings);
  report("rest", rest);
  {
    Simulation pinched(settings);
    runFor(pinched, 1.0);
    const glm::dvec3 top = topOf(pinched);
    ASSERT_TRUE(pinched.grab(top, 0.35 * settings.slime.radius));
    dragOver(pinched, top, glm::dvec3(0.0, 0.0, 0.12), 0.8, 0.2);
    report("pinch", pinched);
  }
  {
    Simulation pressed(settings);
    runFor(pressed, 1.0);
    const glm::dvec3 top = topOf(pressed);
    ASSERT_TRUE(pressed.grab(top, 0.015));
    dragOver(pressed, top, glm::dvec3(0.0, 0.0, -0.03), 0.3, 0.1);
    report("press", pressed);
  }
}

}  // namespace slime
