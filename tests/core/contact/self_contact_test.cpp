// Self-contact (core/contact/self_contact.h): folded over itself the slime does not pass through its
// own sheet, two pieces stacked do not pass through each other, and touching sheets cling.
// The oracle is the generalised winding number (core/geometry/winding_number.h): a point inside two
// drawn sheets has w = 2.
#include "core/contact/self_contact.h"

#include "core/bulk/bulk_body.h"
#include "core/geometry/winding_number.h"
#include "core/settings/settings_io.h"
#include "core/simulation/scenario.h"
#include "core/simulation/simulation.h"
#include "tests/core/simulation_fixture.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

namespace slime {
namespace {

constexpr double kFoldDepth = 0.0005;  // the done-when's margin: 0.5 mm inside two sheets

// The fold (tests/scenarios/fold_over_and_hold.json: both hands stretch the slime into a strand on the
// table, hand 1 lifts its end up, over and presses it down onto the strand near hand 0) at drawn level 3,
// to `seconds`; the most points 0.5 mm under a drawn vertex inside two sheets, over samples every 0.1 s
// while the fold is pressed.
struct FoldResult {
  std::size_t mostInsideTwice = 0;
  double deepest = 0.0;
  std::size_t rollbacks = 0;
  double lowestRightSide = 1.0;  // where hand 1's part of the surface came down to, m
};

FoldResult fold(bool selfContact, double seconds = 4.0) {
  Settings settings = defaultSettings();
  settings.slime.level = 3;
  settings.slime.selfContact = selfContact;
  Simulation simulation(settings);
  ScenarioPlayer player(loadScenario(std::string(SLIME_SOURCE_DIR) + "/tests/scenarios/fold_over_and_hold.json"));
  FoldResult result;
  double nextSample = 3.4;
  while (simulation.time() < seconds) {
    player.advanceTo(simulation.time(), simulation, settings);
    simulation.step();
    if (simulation.time() + 1e-9 < nextSample) continue;
    nextSample += 0.1;
    const InsideTwice measure = insideTwiceUnderVertices(simulation.surfaces(), kFoldDepth);
    result.mostInsideTwice = std::max(result.mostInsideTwice, measure.insideTwice);
    result.deepest = std::max(result.deepest, measure.deepest);
    result.lowestRightSide = std::min(result.lowestRightSide, simulation.grabbedPoint(1).z);
  }
  result.rollbacks = simulation.divergences().size();
  return result;
}

// Switched off, the folded end sinks into the strand under it: the measure sees it. On, the sheets are
// held apart, and so is the patch the pressing hand crumples, whose folds lie nearer at rest than the
// contact's exclusion (only folded pairs of them are in contact: without them, 41 vertices counted);
// a few vertices there still count (docs/physics.md, self-contact, limits).
TEST(SelfContact, AFoldDoesNotPassThroughItself) {
  const FoldResult off = fold(false);
  EXPECT_GT(off.mostInsideTwice, 50u) << "without self-contact the fold should pass through itself";
  const FoldResult on = fold(true);
  std::printf("fold: vertices 0.5 mm inside two sheets, off %zu, on %zu (deepest %.2f mm)\n", off.mostInsideTwice,
              on.mostInsideTwice, 1e3 * on.deepest);
  EXPECT_LT(static_cast<double>(on.mostInsideTwice), 0.2 * static_cast<double>(off.mostInsideTwice))
      << "off " << off.mostInsideTwice << ", on " << on.mostInsideTwice;
  EXPECT_EQ(on.rollbacks, 0u);
  EXPECT_LT(on.lowestRightSide, 0.03) << "the end was not pressed down onto the strand";
}

// Flung up 25 cm and slammed back onto the floor (tests/scenarios/fling_up_and_slam.json, released at
// 1.1 s): the slam drives the sheets through each other for a moment (807 of 2,562 drawn vertices inside
// two sheets at 1.15 s without self-contact), and they come apart by 1.25 s. The contact must not hold
// that tangle: pushing vertices out along triangles that the slam had turned inside out kept 350–450
// vertices inside two sheets from 1.15 s on, and the slime stayed flattened (docs/physics.md, self-contact).
TEST(SelfContact, ASlamDoesNotTangleTheSurface) {
  Settings settings = defaultSettings();
  settings.slime.selfContact = true;
  Simulation simulation(settings);
  ScenarioPlayer player(loadScenario(std::string(SLIME_SOURCE_DIR) + "/tests/scenarios/fling_up_and_slam.json"));
  std::size_t most = 0;
  double nextSample = 1.25;
  while (simulation.time() < 2.0) {
    player.advanceTo(simulation.time(), simulation, settings);
    simulation.step();
    if (simulation.time() + 1e-9 < nextSample) continue;
    nextSample += 0.05;
    most = std::max(most, insideTwiceUnderVertices(simulation.surfaces(), kFoldDepth).insideTwice);
  }
  EXPECT_EQ(most, 0u) << "vertices 0.5 mm inside two sheets after the slam";
  EXPECT_TRUE(simulation.divergences().empty());
}

// Two balls, one above the other (the upper one first: the hands hold the first piece).
std::vector<BulkBody> stacked(const Settings& settings) {
  std::vector<BulkBody> bodies;
  for (double z : {0.095, 0.031}) {
    SlimeSettings slime = settings.slime;
    slime.radius = 0.03;
    slime.mass = 0.113;
    slime.position = glm::dvec3(0.0, 0.0, z);
    bodies.push_back(buildBulkBody(slime));
  }
  return bodies;
}

// A hand presses the upper piece 3 cm down onto the lower one and holds it there.
std::size_t pressPieceOnPiece(bool selfContact) {
  Settings settings = defaultSettings();
  settings.slime.level = 3;
  settings.slime.selfContact = selfContact;
  Simulation simulation(settings, stacked(settings));
  EXPECT_EQ(simulation.pieceCount(), 2u);
  simulation.grab(glm::dvec3(0.0, 0.0, 0.125), 0.015);
  std::size_t most = 0;
  for (int sample = 0; sample < 12; ++sample) {
    simulation.dragTo(glm::dvec3(0.0, 0.0, 0.125 - 0.03 * std::min(1.0, simulation.time() / 0.6)));
    fixture::runFor(simulation, 0.1);
    most = std::max(most, insideTwiceUnderVertices(simulation.surfaces(), kFoldDepth).insideTwice);
  }
  EXPECT_TRUE(simulation.divergences().empty());
  return most;
}

TEST(SelfContact, APiecePressedOntoAnotherDoesNotPassThroughIt) {
  const std::size_t off = pressPieceOnPiece(false);
  EXPECT_GT(off, 30u) << "without self-contact the pieces should pass through each other";
  const std::size_t on = pressPieceOnPiece(true);
  EXPECT_LT(on, off / 4) << "off " << off << ", on " << on;
}

TEST(SelfContact, ItsSettingsAreInTheTableAndBadValuesAreRefused) {
  Settings settings = defaultSettings();
  EXPECT_FALSE(settings.slime.selfContact) << "off until the fold leaves none and the untouched slime's cost is within 1.15x "
                                               "(docs/physics.md, self-contact, limits 1 and 7)";
  EXPECT_LT(settings.slime.cling, settings.slime.modulus) << "pieces must part before the material tears";
  EXPECT_THROW(applyOverride(settings, "slime.cling=-1"), SettingsError);
  EXPECT_THROW(applyOverride(settings, "slime.selfContact=maybe"), SettingsError);
  applyOverride(settings, "slime.selfContact=true");
  EXPECT_TRUE(settings.slime.selfContact);
}

}  // namespace
}  // namespace slime
