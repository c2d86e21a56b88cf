// The slime's pieces (core/simulation/piece.h): one per Simulation today, each a body behind one
// interface, with its own hands, drawn surface and guard state.
#include "simulation_fixture.h"

#include "core/settings/settings_io.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>

namespace slime {
namespace {

Settings smallSlime(const std::string& model) {
  Settings settings = defaultSettings();
  settings.slime.model = model;
  settings.slime.level = 2;
  settings.slime.resolution = 1;
  settings.sim.integrator = "rk4";  // it reads the acceleration field, which the copy must own
  return settings;
}

// A copied Simulation steps on by itself: its pieces' models point at its own bodies. After the copy
// the original grabs and drags (a mouse spring on the bulk body, kinematic points on the membrane); the
// copy must go on exactly as a run that was never copied and never grabbed.
TEST(Pieces, ACopyStepsOnByItselfWhateverTheOriginalDoes) {
  for (const char* model : {"bulk", "membrane"}) {
    const Settings settings = smallSlime(model);
    Simulation reference(settings);
    fixture::runFor(reference, 0.02);
    Simulation original(settings);
    fixture::runFor(original, 0.01);
    const Simulation copy = original;
    Simulation stepped = copy;
    ASSERT_TRUE(original.grab(fixture::topOf(original), 0.02)) << model;
    original.dragTo(fixture::topOf(original) + glm::dvec3(0.0, 0.0, 0.05));
    for (int i = 0; i < 10; ++i) {
      original.step();
      stepped.step();
    }
    EXPECT_FALSE(stepped.grabbing()) << model;
    ASSERT_EQ(stepped.stepCount(), reference.stepCount()) << model;
    EXPECT_TRUE(stepped.state().positions == reference.state().positions) << model << ": the copy felt the original's hand";
    EXPECT_TRUE(stepped.state().velocities == reference.state().velocities) << model;
    EXPECT_EQ(copy.surfaces().size(), 1u) << model;
  }
}

// The list of drawn surfaces is the pieces' (one), each closed: every edge shared by two triangles.
TEST(Pieces, TheDrawnSurfacesAreOnePiecePerBodyAndClosed) {
  for (const char* model : {"bulk", "membrane"}) {
    Simulation simulation(smallSlime(model));
    fixture::runFor(simulation, 0.01);
    const std::vector<SurfaceView>& surfaces = simulation.surfaces();
    ASSERT_EQ(surfaces.size(), simulation.pieceCount()) << model;
    ASSERT_EQ(surfaces.size(), 1u) << model;
    EXPECT_EQ(surfaces[0].positions.data(), simulation.positions().data()) << model;
    const std::vector<Triangle> triangles(surfaces[0].triangles.begin(), surfaces[0].triangles.end());
    const std::size_t edges = uniqueEdges(triangles).size();
    EXPECT_EQ(2 * edges, 3 * triangles.size()) << model << ": an edge not shared by exactly two triangles";
    EXPECT_EQ(surfaces[0].positions.size() + triangles.size() - edges, 2u) << model << ": Euler characteristic of a sphere";
  }
}

}  // namespace
}  // namespace slime
