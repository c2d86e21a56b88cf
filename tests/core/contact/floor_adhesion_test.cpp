// The sticky floor: stuck nodes hold up to adhesion × area, peel from the contact's edge inwards,
// and slime.adhesion = 0 leaves the floor as it was.
#include "core/contact/floor_adhesion.h"
#include "core/settings/settings_io.h"
#include "core/simulation/simulation.h"

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

// Leaves the patch at rest for 5 s (ten dwell times): its contacts reach their full strength.
void ageContact(Patch& patch, FloorAdhesion& adhesion, double strength, double h) {
  for (int k = 0; k < 5000; ++k) {
    adhesion.beginSubstep(patch.state);
    adhesion.endSubstep(patch.state, patch.surface, patch.inverseMasses, strength, h);
  }
}

// Pulls `node` up by `force` every substep, from rest each time (a sustained load), for `seconds`;
// returns how long it stayed stuck (s), `seconds` if it never peeled.
double holdUnder(Patch& patch, FloorAdhesion& adhesion, std::uint32_t node, double force, double strength, double h,
                 double seconds) {
  for (int k = 0; k * h < seconds; ++k) {
    pullOnce(patch, adhesion, node, force, strength, h);
    if (!adhesion.stuck(node)) return k * h;
    patch.state.velocities[node] = glm::dvec3(0.0);
  }
  return seconds;
}

TEST(FloorAdhesion, HoldsUpToItsStrengthAndPeelsOnlyFromTheEdge) {
  Patch patch = makePatch();
  FloorAdhesion adhesion;
  adhesion.reset(patch.surface, patch.state.size());
  const double h = 1e-3, strength = 100.0;  // Pa
  adhesion.endSubstep(patch.state, patch.surface, patch.inverseMasses, strength, h);  // lands: all stick
  EXPECT_EQ(adhesion.stuckCount(), 9u);
  ageContact(patch, adhesion, strength, h);
  // The contact's corner node (1, 1) holds a third of six triangles' projected 0.5 cm², 1e-4 m²:
  // 10 mN at 100 Pa.
  const std::uint32_t corner = 6, centre = 12;
  pullOnce(patch, adhesion, corner, 9e-3, strength, h);
  EXPECT_TRUE(adhesion.stuck(corner)) << "held below its strength";
  EXPECT_LT(patch.state.positions[corner].z, 1e-5);  // put back, but for a substep's creep (5 µm)
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

// Rate dependence (floor_adhesion.h): the corner node (10 mN strength at 100 Pa) loaded at half its
// strength holds a hand's quick tug of 50 ms, but under the same load sustained it creeps up out of
// the contact band and peels within a second (v_c r^n = 3.5 mm/s over the 2 mm band: 0.57 s).
TEST(FloorAdhesion, AQuickPullHoldsAndASustainedLoadBelowItsStrengthPeels) {
  Patch patch = makePatch();
  FloorAdhesion adhesion;
  adhesion.reset(patch.surface, patch.state.size());
  const double h = 1e-3, strength = 100.0;
  adhesion.endSubstep(patch.state, patch.surface, patch.inverseMasses, strength, h);
  ageContact(patch, adhesion, strength, h);
  const std::uint32_t corner = 6;
  EXPECT_DOUBLE_EQ(holdUnder(patch, adhesion, corner, 5e-3, strength, h, 0.05), 0.05) << "a quick tug holds";
  EXPECT_LT(patch.state.positions[corner].z, 0.5e-3);
  const double held = holdUnder(patch, adhesion, corner, 5e-3, strength, h, 3.0);
  std::printf("half the strength sustained: peeled after %.3f s more\n", held);
  EXPECT_GT(held, 0.3);
  EXPECT_LT(held, 1.0) << "a sustained load below the strength must creep and peel";
}

// Contact ageing: a contact just made holds a fifth of σ_a (a landing slime is not glued down at once);
// after a few dwell times it holds all of it.
TEST(FloorAdhesion, AFreshContactIsWeakAndStrengthensWithTimeInContact) {
  const double h = 1e-3, strength = 100.0;
  const std::uint32_t corner = 6;
  Patch fresh = makePatch();
  FloorAdhesion freshAdhesion;
  freshAdhesion.reset(fresh.surface, fresh.state.size());
  freshAdhesion.endSubstep(fresh.state, fresh.surface, fresh.inverseMasses, strength, h);
  pullOnce(fresh, freshAdhesion, corner, 5e-3, strength, h);
  EXPECT_FALSE(freshAdhesion.stuck(corner)) << "half σ_a peels a fresh contact";
  Patch aged = makePatch();
  FloorAdhesion agedAdhesion;
  agedAdhesion.reset(aged.surface, aged.state.size());
  agedAdhesion.endSubstep(aged.state, aged.surface, aged.inverseMasses, strength, h);
  ageContact(aged, agedAdhesion, strength, h);
  pullOnce(aged, agedAdhesion, corner, 5e-3, strength, h);
  EXPECT_TRUE(agedAdhesion.stuck(corner)) << "an aged contact holds half σ_a";
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

// The done-when, on the default settings (slime.adhesion = 8000 Pa, docs/physics.md): the
// slow side pull stretches the slime before it slides.
TEST(FloorAdhesion, TheStickyDefaultStretchesBeforeItSlides) {
  const double sticky = defaultSettings().slime.adhesion;
  const SidePull slippery = sidePull(0.0);
  const SidePull pulled = sidePull(sticky);
  std::printf("side pull 12 cm / 1.5 s: centroid %.2f cm, width %.2f cm (adhesion 0); centroid %.2f cm, width "
              "%.2f cm (the default, %.0f Pa)\n",
              slippery.centroidMove * 100, slippery.width * 100, pulled.centroidMove * 100, pulled.width * 100,
              sticky);
  EXPECT_GT(slippery.centroidMove, 0.09);  // without adhesion: the whole slime slides
  EXPECT_LT(pulled.centroidMove, 0.5 * slippery.centroidMove);
  EXPECT_GT(pulled.width, slippery.width + 0.03);
}

}  // namespace
}  // namespace slime
