// The sticky floor: stuck nodes hold up to adhesion × area, peel from the contact's edge inwards,
// and slime.adhesion = 0 leaves the floor as it was.
#include "core/scene/floor_adhesion.h"
#include "core/settings/settings_io.h"
#include "core/scene/simulation.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

namespace slime {
namespace {

// A 5×5 grid of nodes 1 cm apart, two triangles per cell facing down (the underside of a body), 1 g
// each; the outer ring 1 cm above the floor, so that the inner 3×3 nodes are the contact. Every node
// holds adhesion × a third of the projected area of its triangles.
struct Patch {
  std::vector<Triangle> surface;
  ParticleState state;
  std::vector<double> inverseMasses;
};

Patch makePatch() {
  Patch patch;
  const int n = 5;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const bool ring = i == 0 || j == 0 || i == n - 1 || j == n - 1;
      patch.state.positions.push_back(glm::dvec3(0.01 * i, 0.01 * j, ring ? 0.01 : 0.0));
      patch.state.velocities.push_back(glm::dvec3(0.0));
      patch.state.inverseMasses.push_back(1000.0);
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const auto at = [&](int a, int b) { return static_cast<std::uint32_t>(b * n + a); };
      patch.surface.push_back(Triangle(at(i, j), at(i, j + 1), at(i + 1, j)));  // normals −z
      patch.surface.push_back(Triangle(at(i + 1, j), at(i, j + 1), at(i + 1, j + 1)));
    }
  patch.inverseMasses = patch.state.inverseMasses;
  return patch;
}

// One substep of length h in which node `node` is pulled up by `force` (N): v += h F/m, x += h v.
void pullOnce(Patch& patch, FloorAdhesion& adhesion, std::uint32_t node, double force, double strength, double h) {
  adhesion.beginSubstep(patch.state);
  patch.state.velocities[node].z += h * force * patch.inverseMasses[node];
  patch.state.positions[node] += h * patch.state.velocities[node];
  adhesion.endSubstep(patch.state, patch.surface, patch.inverseMasses, strength, h);
}

TEST(FloorAdhesion, HoldsUpToItsStrengthAndPeelsOnlyFromTheEdge) {
  Patch patch = makePatch();
  FloorAdhesion adhesion;
  adhesion.reset(patch.surface, patch.state.size());
  const double h = 1e-3, strength = 100.0;  // Pa
  adhesion.endSubstep(patch.state, patch.surface, patch.inverseMasses, strength, h);  // lands: all stick
  EXPECT_EQ(adhesion.stuckCount(), 9u);
  // The contact's corner node (1, 1) holds a third of six triangles' projected 0.5 cm², 1e-4 m²:
  // 10 mN at 100 Pa.
  const std::uint32_t corner = 6, centre = 12;
  pullOnce(patch, adhesion, corner, 9e-3, strength, h);
  EXPECT_TRUE(adhesion.stuck(corner)) << "held below its strength";
  EXPECT_DOUBLE_EQ(patch.state.positions[corner].z, 0.0);  // put back
  pullOnce(patch, adhesion, corner, 11e-3, strength, h);
  EXPECT_FALSE(adhesion.stuck(corner)) << "peels above its strength";
  // The centre node (also 10 mN) is pulled ten times harder but is not on the edge: it holds.
  pullOnce(patch, adhesion, centre, 0.1, strength, h);
  EXPECT_TRUE(adhesion.stuck(centre));
  EXPECT_DOUBLE_EQ(patch.state.positions[centre].z, 0.0);
  EXPECT_EQ(adhesion.peeledCount(), 1u);
  // A peeled node lying on the floor does not stick again until it has left it.
  adhesion.endSubstep(patch.state, patch.surface, patch.inverseMasses, strength, h);
  EXPECT_FALSE(adhesion.stuck(corner));
}

TEST(FloorAdhesion, ZeroStrengthSticksNothing) {
  Patch patch = makePatch();
  FloorAdhesion adhesion;
  adhesion.reset(patch.surface, patch.state.size());
  adhesion.endSubstep(patch.state, patch.surface, patch.inverseMasses, 0.0, 1e-3);
  EXPECT_EQ(adhesion.stuckCount(), 0u);
  Settings settings = defaultSettings();
  settings.slime.adhesion = 0.0;
  Simulation simulation(settings);
  while (simulation.time() < 0.5) simulation.step();
  EXPECT_EQ(simulation.adhesion().stuckCount(), 0u);
}

glm::dvec3 centroid(const Simulation& simulation) {
  glm::dvec3 sum(0.0);
  for (const glm::dvec3& p : simulation.positions()) sum += p;
  return sum / static_cast<double>(simulation.positions().size());
}

// The slow one-hand pull: the slime pinched at its side and pulled 12 cm sideways over 1.5 s.
// On the default sticky floor it stretches (its width grows) and its centre moves much less than on
// a floor without adhesion, where the whole slime slides along.
struct SidePull {
  double centroidMove, width;
};

SidePull sidePull(double adhesion) {
  Settings settings = defaultSettings();
  settings.slime.adhesion = adhesion;
  Simulation simulation(settings);
  while (simulation.time() < 1.0 - 1e-9) simulation.step();
  const glm::dvec3 before = centroid(simulation);
  EXPECT_TRUE(simulation.grab(glm::dvec3(0.06, 0.0, 0.03), 0.015));
  const glm::dvec3 start = simulation.grabTarget();
  const double t0 = simulation.time();
  while (simulation.time() < t0 + 1.5 - 1e-9) {
    simulation.dragTo(start + glm::dvec3(0.12 * (simulation.time() - t0) / 1.5, 0.0, 0.0));
    simulation.step();
  }
  EXPECT_TRUE(simulation.divergences().empty());
  return {centroid(simulation).x - before.x, simulation.metrics().width};
}

// 6,000 Pa: the strength chosen by the pull (docs/physics.md); not the default yet, because a
// floor that strong holds a slime pressed or yanked flat (the torture runs' rest shape does not come back).
constexpr double kStickyFloor = 6000.0;

TEST(FloorAdhesion, AStickyFloorStretchesTheSlimeBeforeItSlides) {
  const SidePull slippery = sidePull(0.0);
  const SidePull sticky = sidePull(kStickyFloor);
  std::printf("side pull 12 cm / 1.5 s: centroid %.2f cm, width %.2f cm (adhesion 0); centroid %.2f cm, width "
              "%.2f cm (%.0f Pa)\n",
              slippery.centroidMove * 100, slippery.width * 100, sticky.centroidMove * 100, sticky.width * 100,
              kStickyFloor);
  EXPECT_GT(slippery.centroidMove, 0.09);  // today's: the whole slime slides
  EXPECT_LT(sticky.centroidMove, 0.5 * slippery.centroidMove);
  EXPECT_GT(sticky.width, slippery.width + 0.03);
}

}  // namespace
}  // namespace slime
