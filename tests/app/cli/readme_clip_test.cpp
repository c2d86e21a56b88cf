// The README's clip (docs/pull-snap-press-back.gif, assets/scenarios/pull_snap_press_back.json) does what
// its sentence says on today's physics: with the command's settings, the two hands' pull snaps the slime
// into pieces while they still pull, and the pieces pressed back end as one. When the physics changes so
// that this no longer holds, the clip is out of date: record it again with the README's command.
#include "core/settings/settings_io.h"
#include "core/simulation/scenario.h"
#include "core/simulation/simulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace slime {
namespace {

TEST(ReadmeClip, ThePullSnapsAndThePiecesPressedBackBecomeOne) {
  Settings settings = defaultSettings();
  settings.slime.tearing = true;             // --set slime.tearing=true
  settings.slime.position = {0.0, 0.0, 0.04};  // --set slime.position=0,0,0.04
  Simulation simulation(settings);
  ScenarioPlayer player(loadScenario(std::string(SLIME_SOURCE_DIR) + "/assets/scenarios/pull_snap_press_back.json"));
  constexpr double kPullEnds = 1.5;   // the hands reach their ends ...
  constexpr double kReleased = 3.1;   // ... and let go here
  constexpr double kClipEnds = 5.5;   // --seconds 5.5
  std::size_t piecesWhilePulled = 1, piecesAtRelease = 0;
  while (simulation.time() < kClipEnds - 1e-9) {
    player.advanceTo(simulation.time(), simulation, settings);
    simulation.step();
    if (simulation.time() <= kPullEnds) piecesWhilePulled = std::max(piecesWhilePulled, simulation.pieceCount());
    if (piecesAtRelease == 0 && simulation.time() >= kReleased) piecesAtRelease = simulation.pieceCount();
  }
  EXPECT_GE(piecesWhilePulled, 2u) << "the pull did not snap the slime";
  EXPECT_EQ(piecesAtRelease, 1u) << "the pieces pressed together had not merged when the hands let go";
  EXPECT_EQ(simulation.pieceCount(), 1u);
  EXPECT_GE(simulation.merges(), 1);
  EXPECT_TRUE(simulation.divergences().empty());
  EXPECT_NEAR(simulation.metrics().volumeRatio, 1.0, 0.01);
}

}  // namespace
}  // namespace slime
