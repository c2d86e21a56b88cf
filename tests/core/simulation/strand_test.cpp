// Long strands: two hands pull the default slime apart slowly into a strand at least five times its
// rest diameter, with no NaN, no inverted element, no rollback and its volume within 2 %; let go, it
// draws back towards its ball (the standard linear solid's long-term branch). Slow: HandsLong.
#include "core/settings/settings_io.h"
#include "core/simulation/simulation.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace slime {
namespace {

// Smallest det F = det(D_s D_m⁻¹) over the body's tetrahedra, as a ratio of rest to now (6V / 6V₀).
double smallestVolumeRatio(const Simulation& simulation) {
  const BulkBody& body = simulation.bulkBody();
  const std::vector<glm::dvec3>& x = body.state.positions;
  const std::vector<glm::dvec3>& x0 = body.mesh.positions;
  double smallest = 1e300;
  for (const Tetrahedron& t : body.mesh.tetrahedra) {
    const auto volume = [&](const std::vector<glm::dvec3>& p) {
      return glm::dot(glm::cross(p[t.y] - p[t.x], p[t.z] - p[t.x]), p[t.w] - p[t.x]);
    };
    smallest = std::min(smallest, volume(x) / volume(x0));
  }
  return smallest;
}

// The body's thickness across the pull (its y extent) among the nodes within 1 cm of the plane x = at.
double thicknessAt(const Simulation& simulation, double at) {
  double low = 1e300, high = -1e300;
  for (const glm::dvec3& p : simulation.bulkBody().state.positions)
    if (std::abs(p.x - at) < 0.01) {
      low = std::min(low, p.y);
      high = std::max(high, p.y);
    }
  return high > low ? high - low : 0.0;
}

struct StrandRun {
  double restDiameter, strand, smallestElement, volumeMin, volumeMax, released, nan;
  double middle, ends, neck;  // thickness across the strand: half-way, at the hands, thinnest between, m
  double quarter;             // the thicker of the two at a quarter and three quarters of the way, m
  std::size_t rollbacks;
};

// Each hand closes on the side of the slime: the nodes within 3 cm of the surface point (about 70),
// a fist's hold rather than a pinch's. Each pulls with at most the default sim.handForce (16 N, a
// child's firm pull; 10 N stopped the default slime at 4.0×).
StrandRun pullIntoAStrand(const std::string& integrator) {
  Settings settings = defaultSettings();
  settings.sim.integrator = integrator;
  Simulation simulation(settings);
  while (simulation.time() < 1.0 - 1e-9) simulation.step();
  StrandRun run{};
  run.restDiameter = simulation.metrics().width;
  const double r = settings.slime.radius, hold = 0.03;
  EXPECT_TRUE(simulation.grab(glm::dvec3(-2.0 * r, 0.0, 0.03), hold, 0));
  EXPECT_TRUE(simulation.grab(glm::dvec3(2.0 * r, 0.0, 0.03), hold, 1));
  const glm::dvec3 left = simulation.grabTarget(0), right = simulation.grabTarget(1);
  // Each hand goes out 22 cm and up 8 cm in 14 s (1.7 cm/s), then holds for 1 s.
  const double t0 = simulation.time(), pull = 14.0, out = 0.22, up = 0.08;
  run.volumeMin = run.volumeMax = 1.0;
  run.smallestElement = 1.0;
  while (simulation.time() < t0 + pull + 1.0 - 1e-9) {
    const double s = std::min(1.0, (simulation.time() - t0) / pull);
    simulation.dragTo(left + glm::dvec3(-out * s, 0.0, up * s), 0);
    simulation.dragTo(right + glm::dvec3(out * s, 0.0, up * s), 1);
    simulation.step();
    if (simulation.stepCount() % 20 == 0) {
      const SlimeMetrics m = simulation.metrics();
      run.volumeMin = std::min(run.volumeMin, m.volumeRatio);
      run.volumeMax = std::max(run.volumeMax, m.volumeRatio);
      run.smallestElement = std::min(run.smallestElement, smallestVolumeRatio(simulation));
      if (!std::isfinite(m.volumeRatio)) run.nan = 1.0;
    }
  }
  run.strand = simulation.metrics().width;
  const double a = simulation.grabbedPoint(0).x, b = simulation.grabbedPoint(1).x;
  run.middle = thicknessAt(simulation, 0.5 * (a + b));
  run.quarter = std::max(thicknessAt(simulation, a + 0.25 * (b - a)), thicknessAt(simulation, a + 0.75 * (b - a)));
  // The held ends: the thickest slab within the fist (3 cm inside each hand's point).
  const auto held = [&](double at, double inward) {
    double thickest = 0.0;
    for (double d = 0.0; d < 0.0301; d += 0.005) thickest = std::max(thickest, thicknessAt(simulation, at + inward * d));
    return thickest;
  };
  run.ends = std::min(held(a, 1.0), held(b, -1.0));
  run.neck = run.ends;
  for (double s = 0.1; s < 0.901; s += 0.05) run.neck = std::min(run.neck, thicknessAt(simulation, a + s * (b - a)));
  std::printf("strand (%s): hands at %.1f and %.1f cm, forces %.2f / %.2f N; thickness at the hands %.1f cm, "
              "¼ and ¾ of the way %.1f / %.1f cm, half-way %.1f cm, thinnest between %.1f cm\n", integrator.c_str(), a * 100,
              b * 100, glm::length(simulation.handForce(0)), glm::length(simulation.handForce(1)), run.ends * 100,
              thicknessAt(simulation, a + 0.25 * (b - a)) * 100, thicknessAt(simulation, a + 0.75 * (b - a)) * 100,
              run.middle * 100, run.neck * 100);
  simulation.releaseAll();
  const double t1 = simulation.time();
  while (simulation.time() < t1 + 3.0 - 1e-9) simulation.step();
  run.released = simulation.metrics().width;
  run.rollbacks = simulation.divergences().size();
  std::printf("strand (%s): rest diameter %.1f cm, strand %.1f cm (%.1f×), smallest element volume ratio %.3f, "
              "volume [%.4f, %.4f], 3 s after release %.1f cm, rollbacks %zu\n",
              integrator.c_str(), run.restDiameter * 100, run.strand * 100, run.strand / run.restDiameter,
              run.smallestElement, run.volumeMin, run.volumeMax, run.released * 100, run.rollbacks);
  return run;
}

void expectAStrandThatComesBack(const StrandRun& run) {
  EXPECT_EQ(run.nan, 0.0);
  EXPECT_GE(run.strand, 5.0 * run.restDiameter);
  EXPECT_GT(run.smallestElement, 0.0);  // no inverted element
  EXPECT_GT(run.volumeMin, 0.98);
  EXPECT_LT(run.volumeMax, 1.02);
  EXPECT_EQ(run.rollbacks, 0u);
  EXPECT_LT(run.released, 0.6 * run.strand);  // draws back towards its ball
}

// Issue 29 item 2. Before (9cf43e6): symplectic_euler rolled back 12–20 times (its step limit came
// from the rest shape, and every 500 clean steps it coarsened back to one substep and diverged) and
// the pinch's nodes were drawn to points; projective stopped at 4.7× with both hands at 10 N.
// Not asserted yet: thinning in the middle. The held ends are drawn thin (2.4 cm across at the
// hands, necks of 1.1 cm beside them, 3.2 cm half-way): an elastic ball's equator holds the most
// material. A rigid fist (holding the patch's shape) made the middle the thinnest (2.6 cm against 4.7)
// but inverted elements at the fist's edge and needed more than 20 N for 5×.
TEST(HandsLong, TwoHandsPullTheDefaultSlimeIntoAStrandThatComesBack) {
  expectAStrandThatComesBack(pullIntoAStrand(defaultSettings().sim.integrator));
}

}  // namespace
}  // namespace slime
