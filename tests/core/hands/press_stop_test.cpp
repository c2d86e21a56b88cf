// The press stop (grab.h's kPressStopFraction): a hand driving its nodes into the floor leaves each one
// at least that fraction of the material it had under it at the grab above the floor, and the stop
// counts the material, not the height, so a body grabbed in the air can still be put down.
#include "simulation_fixture.h"
#include "core/settings/settings_io.h"
#include "core/hands/grab.h"
#include "core/simulation/simulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <limits>
#include <vector>

namespace slime {
namespace {

using fixture::runFor;
using fixture::topOf;

double lowestNode(const Simulation& simulation) {
  double lowest = std::numeric_limits<double>::infinity();
  for (const glm::dvec3& x : simulation.state().positions) lowest = std::min(lowest, x.z);
  return lowest;
}

// Pressed from the top to 5 cm below the floor and held there for a second: no grabbed node goes
// below its stop, c·(z_i − bottom) (1 mm allowed for the spring's damped swing), and the patch rests
// on its stops as the spring law puts it: on average above them by the hand's force over the spring's
// stiffness, |F| / k (the material under the patch pushes back), 1 mm allowed.
TEST(PressStop, AHandPressingIntoTheFloorStopsAtAFractionOfTheMaterialUnderIt) {
  Settings settings = defaultSettings();
  settings.slime.level = 2;
  Simulation simulation(settings);
  runFor(simulation, 1.0);
  const glm::dvec3 top = topOf(simulation);
  ASSERT_TRUE(simulation.grab(top, 0.015));
  const double bottom = lowestNode(simulation);
  const std::vector<std::uint32_t> nodes = simulation.grabbedIndices();
  std::vector<double> stops;
  for (std::uint32_t i : nodes) stops.push_back(kPressStopFraction * (simulation.state().positions[i].z - bottom));
  simulation.dragTo(glm::dvec3(top.x, top.y, -0.05));
  double deepest = std::numeric_limits<double>::infinity();  // the nearest a node came to its stop (below: < 0)
  for (int step = 0; step < 1000; ++step) {
    simulation.step();
    for (std::size_t k = 0; k < nodes.size(); ++k)
      deepest = std::min(deepest, simulation.state().positions[nodes[k]].z - stops[k]);
  }
  double above = 0.0;
  for (std::size_t k = 0; k < nodes.size(); ++k) above += simulation.state().positions[nodes[k]].z - stops[k];
  above /= static_cast<double>(nodes.size());
  const double lag = glm::length(simulation.handForce()) / kMouseStiffness;
  std::printf("%zu nodes grabbed, stops %.4f–%.4f m; the patch rests %.4f m above them on average (|F|/k %.4f m); "
              "the nearest a node came to its stop: %.4f m above it\n",
              nodes.size(), *std::min_element(stops.begin(), stops.end()), *std::max_element(stops.begin(), stops.end()),
              above, lag, deepest);
  EXPECT_GE(deepest, -0.001);
  EXPECT_NEAR(above, lag, 0.001);
}

// Thrown up at 3 m/s and grabbed by the top in its flight (its bottom over 10 cm up), the body is put
// back down by the hand, its top to 6 cm (about its resting height): the stop counts the material
// under each node, not its height (a quarter of the top's 47 cm would hold it at 12 cm), so the body
// reaches the floor and the grabbed point ends where the spring law puts it, within |F| / k of the
// target (1 mm allowed).
TEST(PressStop, ABodyGrabbedInTheAirCanBePutDown) {
  Settings settings = defaultSettings();
  settings.slime.level = 2;
  Simulation simulation(settings);
  runFor(simulation, 1.0);
  simulation.setVelocities(std::vector<glm::dvec3>(simulation.state().size(), glm::dvec3(0.0, 0.0, 3.0)));
  runFor(simulation, 0.25);
  ASSERT_GT(lowestNode(simulation), 0.1);
  const glm::dvec3 top = topOf(simulation);
  ASSERT_TRUE(simulation.grab(top, 0.015));
  const glm::dvec3 target(top.x, top.y, 0.06);
  simulation.dragTo(target);
  runFor(simulation, 1.0);
  const double lag = glm::length(simulation.handForce()) / kMouseStiffness;
  std::printf("grabbed at %.3f m; after 1 s the lowest node is at %.2e m and the grabbed point at %.4f m (target "
              "%.4f m, |F|/k %.4f m)\n",
              top.z, lowestNode(simulation), simulation.grabbedPoint().z, target.z, lag);
  EXPECT_LT(lowestNode(simulation), 0.001);
  EXPECT_NEAR(simulation.grabbedPoint().z, target.z, lag + 0.001);
}

}  // namespace
}  // namespace slime
